// Bodies that collide with nothing (BodyDef::collides false), as a robot
// link without collision geometry: never in a contact, but integrated,
// jointed, pushed, put to sleep and checkpointed like any other body.
// Against closed forms: such a box dropped onto the ground falls through it
// exactly as each integrator's free fall says, while a colliding box beside
// it rests; an arm of that kind hinged to a colliding pillar swings through
// it to its limit, where a colliding twin is stopped by the pillar.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rbsim/physics/world.h"

namespace rbsim {
namespace {

constexpr double kGravity = 9.81;

WorldSettings settingsFor(IntegratorKind integrator, double dt) {
  WorldSettings settings;
  settings.dt = dt;
  settings.gravity = Vec3(0, 0, -kGravity);
  settings.integrator = integrator;
  return settings;
}

// A dynamic body, or a static one for a mass of 0.
BodyId addBody(World& world, const std::string& name, const Shape& shape, double mass, const Vec3& position,
               bool collides) {
  BodyDef def;
  def.name = name;
  def.shape = shape;
  if (mass > 0.0) def.mass = mass;
  def.isStatic = mass == 0.0;
  def.position = position;
  def.collides = collides;
  const Expected<BodyId> id = world.createBody(def);
  EXPECT_TRUE(id.ok()) << id.error().message;
  return id.ok() ? *id : BodyId{};
}

BodyId addGround(World& world) { return addBody(world, "ground", PlaneShape{}, 0.0, Vec3::Zero(), true); }

// A hinge along y that lets its bodies collide (collide_connected), so that
// only a body's own flag keeps it out of contact with the other.
JointId addHinge(World& world, BodyId a, BodyId b, const Vec3& anchor, const JointLimit& limit = {}) {
  JointDef def;
  def.name = "hinge";
  def.type = JointType::Revolute;
  def.bodyA = a;
  def.bodyB = b;
  def.anchor = anchor;
  def.axis = Vec3::UnitY();
  def.limit = limit;
  def.collideConnected = true;
  const Expected<JointId> id = world.createJoint(def);
  EXPECT_TRUE(id.ok()) << id.error().message;
  return id.ok() ? *id : JointId{};
}

// Whether any of the last step's contacts involves the body.
bool inAnyContact(const World& world, BodyId id) {
  const int32_t serial = world.body(id).serial();
  for (const SolvedManifold& m : world.contacts())
    if (m.serialA == serial || m.serialB == serial) return true;
  return false;
}

// The height after n steps of h from rest at z0 under gravity, as each
// integrator computes it: explicit Euler moves on the velocity before the
// step, z0 − g h² n(n−1)/2; semi-implicit Euler on the one after it,
// z0 − g h² n(n+1)/2; RK4 is exact for a constant force, z0 − g t²/2.
double freeFallHeight(IntegratorKind integrator, double z0, double h, int n) {
  const double steps = n;
  switch (integrator) {
    case IntegratorKind::ExplicitEuler: return z0 - 0.5 * kGravity * h * h * steps * (steps - 1.0);
    case IntegratorKind::SemiImplicitEuler: return z0 - 0.5 * kGravity * h * h * steps * (steps + 1.0);
    case IntegratorKind::Rk4: return z0 - 0.5 * kGravity * (h * steps) * (h * steps);
  }
  return NAN;
}

TEST(NonCollidingBodies, ABoxFallsThroughTheGroundInFreeFallWhileACollidingOneRestsBesideIt) {
  for (const IntegratorKind integrator :
       {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4}) {
    for (const double dt : {1e-3, 2e-3}) {
      SCOPED_TRACE(::testing::Message() << integratorName(integrator) << ", dt " << dt);
      // Both boxes start at rest touching the ground.
      World world(settingsFor(integrator, dt));
      addGround(world);
      const Vec3 half(0.1, 0.1, 0.1);
      const BodyId solid = addBody(world, "solid", BoxShape{half}, 1.0, Vec3(0, 0, 0.1), true);
      const BodyId ghost = addBody(world, "ghost", BoxShape{half}, 1.0, Vec3(1, 0, 0.1), false);
      EXPECT_FALSE(world.body(ghost).description().collides);
      EXPECT_EQ(world.body(ghost).description().collider, nullptr);
      const int steps = static_cast<int>(std::lround(1.0 / dt));
      for (int n = 1; n <= steps; ++n) {
        world.step();
        ASSERT_NEAR(world.body(ghost).position().z(), freeFallHeight(integrator, 0.1, dt, n), 1e-9) << "step " << n;
        ASSERT_FALSE(inAnyContact(world, ghost)) << "step " << n;
      }
      EXPECT_NEAR(world.body(ghost).linearVelocity().z(), -kGravity * world.time(), 1e-9);
      EXPECT_NEAR(world.body(ghost).position().x(), 1.0, 1e-15) << "straight down";
      EXPECT_NEAR(world.body(solid).position().z(), 0.1, 1e-3) << "the colliding one rests on the ground";
      EXPECT_LT(world.body(solid).linearVelocity().norm(), 1e-6);
      EXPECT_TRUE(inAnyContact(world, solid));
    }
  }
}

TEST(NonCollidingBodies, OverlappingBodiesReportNoContactAndDoNotPushApart) {
  WorldSettings settings = settingsFor(IntegratorKind::SemiImplicitEuler, 1e-3);
  settings.gravity = Vec3::Zero();
  World world(settings);
  const Vec3 half(0.2, 0.2, 0.2);
  // Two ghosts on top of each other, a third inside a colliding box, and a
  // colliding pair that overlaps as the ghosts do (which must push apart).
  const BodyId ghostA = addBody(world, "ghost_a", BoxShape{half}, 1.0, Vec3(0, 0, 0), false);
  const BodyId ghostB = addBody(world, "ghost_b", BoxShape{half}, 1.0, Vec3(0.1, 0, 0), false);
  const BodyId ghostC = addBody(world, "ghost_c", BoxShape{half}, 1.0, Vec3(3, 0, 0), false);
  const BodyId host = addBody(world, "host", BoxShape{half}, 1.0, Vec3(3.1, 0, 0), true);
  const BodyId solidA = addBody(world, "solid_a", BoxShape{half}, 1.0, Vec3(6, 0, 0), true);
  const BodyId solidB = addBody(world, "solid_b", BoxShape{half}, 1.0, Vec3(6.1, 0, 0), true);
  for (int k = 0; k < 100; ++k) {
    world.step();
    for (const BodyId ghost : {ghostA, ghostB, ghostC}) ASSERT_FALSE(inAnyContact(world, ghost)) << "step " << k;
  }
  for (const BodyId ghost : {ghostA, ghostB, ghostC}) EXPECT_EQ(world.body(ghost).linearVelocity(), Vec3::Zero());
  EXPECT_EQ(world.body(ghostB).position(), Vec3(0.1, 0, 0));
  EXPECT_EQ(world.body(host).position(), Vec3(3.1, 0, 0)) << "nothing pushed the colliding host either";
  EXPECT_TRUE(inAnyContact(world, solidA) && inAnyContact(world, solidB)) << "the colliding pair is in contact";
  EXPECT_GT(world.body(solidB).position().x() - world.body(solidA).position().x(), 0.1) << "and pushed apart";
}

TEST(NonCollidingBodies, AWorldOfThemSleepsAtRestAndAWrenchWakesIt) {
  WorldSettings settings = settingsFor(IntegratorKind::SemiImplicitEuler, 1e-3);
  settings.gravity = Vec3::Zero();
  World world(settings);
  const BodyId ghost = addBody(world, "ghost", BoxShape{Vec3(0.1, 0.1, 0.1)}, 2.0, Vec3::Zero(), false);
  const int restSteps = static_cast<int>(std::lround(settings.contact.sleepTime / settings.dt));
  for (int k = 0; k < restSteps + 1; ++k) world.step();
  EXPECT_TRUE(world.body(ghost).isSleeping()) << "at rest for the sleep time";
  Wrench push;
  push.force = Vec3(4, 0, 0);  // N on 2 kg: 2 m/s² for one step
  ASSERT_TRUE(world.applyWrench(ghost, push).ok());
  world.step();
  EXPECT_FALSE(world.body(ghost).isSleeping());
  EXPECT_NEAR(world.body(ghost).linearVelocity().x(), 2.0 * settings.dt, 1e-15);
}

TEST(NonCollidingBodies, AnArmHingedToAPillarSwingsThroughItToItsLimit) {
  // A static pillar (x, y in ±0.1 m, 1 m tall) and a 1 kg ball 0.5 m from a
  // hinge along y at (0.3, 0, 1), released horizontal towards −x, limits
  // [−1, 1] rad (negative turns the ball down). The joint lets the two
  // collide (collide_connected), so only the ball's flag keeps it out of
  // contact: it swings down into the pillar and rests on its lower limit
  // there, at (0.03, 0, 0.58); a colliding ball is stopped by the pillar's
  // side near −0.45 rad.
  for (const bool collides : {false, true}) {
    SCOPED_TRACE(collides ? "a colliding ball" : "a ball that collides with nothing");
    World world(settingsFor(IntegratorKind::SemiImplicitEuler, 1e-3));
    addGround(world);
    const BodyId pillar = addBody(world, "pillar", BoxShape{Vec3(0.1, 0.1, 0.5)}, 0.0, Vec3(0, 0, 0.5), true);
    const BodyId arm = addBody(world, "ball", SphereShape{0.05}, 1.0, Vec3(-0.2, 0, 1.0), collides);
    const Vec3 anchor(0.3, 0, 1.0);
    const JointId joint = addHinge(world, pillar, arm, anchor, {true, -1.0, 1.0});
    bool touched = false;
    for (int k = 0; k < 2000; ++k) {
      world.step();
      touched = touched || inAnyContact(world, arm);
    }
    const JointState state = world.jointState(joint);
    EXPECT_LT(state.error, 1e-9);
    if (!collides) {
      EXPECT_FALSE(touched);
      EXPECT_NEAR(state.position, -1.0, 1e-9) << "at its limit";
      EXPECT_NEAR(state.rate, 0.0, 1e-9);
      EXPECT_EQ(state.atLimit, -1);
      const Vec3 expected = anchor + Quaternion::fromAxisAngle(Vec3::UnitY(), -1.0).rotate(Vec3(-0.5, 0, 0));
      EXPECT_LT((world.body(arm).position() - expected).norm(), 1e-9) << world.body(arm).position().transpose();
    } else {
      EXPECT_TRUE(touched);
      EXPECT_GT(state.position, -0.6) << "stopped by the pillar";
    }
  }
}

TEST(NonCollidingBodies, ABallHungThroughTheGroundFromABoxRestingOnItRestsWithIt) {
  // A 10 kg box resting on the ground and a 1 kg ball hung 0.5 m below a
  // hinge on it, through the ground: the ball is in no contact, the hinge
  // holds it where it hangs, and the ground carries the weight of both,
  // (10 + 1) kg · g, through the box's contacts. The box's island is in
  // contact, so the ball takes the contact path's joint step.
  World world(settingsFor(IntegratorKind::SemiImplicitEuler, 1e-3));
  addGround(world);
  const BodyId box = addBody(world, "box", BoxShape{Vec3(0.2, 0.2, 0.1)}, 10.0, Vec3(0, 0, 0.1), true);
  const BodyId weight = addBody(world, "ball", SphereShape{0.05}, 1.0, Vec3(0.3, 0, -0.3), false);
  const JointId joint = addHinge(world, box, weight, Vec3(0.3, 0, 0.2));
  const Vec3 hungAt = world.body(box).worldToBody(world.body(weight).position());
  for (int k = 0; k < 1000; ++k) {
    world.step();
    ASSERT_FALSE(inAnyContact(world, weight)) << "step " << k;
  }
  double normalImpulse = 0.0;
  for (const SolvedManifold& m : world.contacts())
    for (int p = 0; p < m.pointCount; ++p) normalImpulse += m.points[p].normalImpulse;
  EXPECT_NEAR(normalImpulse / world.settings().dt, 11.0 * kGravity, 1e-6);
  EXPECT_LT(world.jointState(joint).error, 1e-12);
  EXPECT_NEAR(world.jointState(joint).position, 0.0, 1e-8);
  EXPECT_LT((world.body(box).worldToBody(world.body(weight).position()) - hungAt).norm(), 1e-8);
  EXPECT_NEAR(world.body(box).position().z(), 0.1, 1e-6);
  EXPECT_LT(world.body(weight).position().z(), -0.2) << "still below the ground";
}

TEST(NonCollidingBodies, ACheckpointKeepsTheFlagAndTheRestoredWorldStepsBitIdentically) {
  World world(settingsFor(IntegratorKind::SemiImplicitEuler, 1e-3));
  addGround(world);
  // A ghost overlapping a colliding box: restored as colliding, the two
  // would push apart and the runs part.
  addBody(world, "solid", BoxShape{Vec3(0.1, 0.1, 0.1)}, 1.0, Vec3(0, 0, 0.5), true);
  const BodyId ghost = addBody(world, "ghost", BoxShape{Vec3(0.1, 0.1, 0.1)}, 1.0, Vec3(0.05, 0, 0.5), false);
  for (int k = 0; k < 200; ++k) world.step();
  const Expected<std::vector<uint8_t>> bytes = world.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  Expected<World> restored = World::decodeSnapshot(*bytes, world.settings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  const BodyView restoredGhost = restored->body(restored->findBody("ghost"));
  EXPECT_FALSE(restoredGhost.description().collides);
  EXPECT_EQ(restoredGhost.description().collider, nullptr);
  EXPECT_TRUE(restored->body(restored->findBody("solid")).description().collides);
  for (int k = 0; k < 1000; ++k) {
    world.step();
    restored->step();
    ASSERT_EQ(restored->stateHash(), world.stateHash()) << "step " << k;
  }
  EXPECT_LT(world.body(ghost).position().z(), -1.0) << "the ghost fell through the ground";
}

}  // namespace
}  // namespace rbsim
