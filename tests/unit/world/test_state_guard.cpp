// The numerical guard: a body whose state goes non-finite or too fast is
// frozen at its last good pose, reported once, and taken out of stepping and
// collision detection, while the rest of the world steps on bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "rbsim/physics/world.h"
#include "rbsim/physics/world.h"

namespace rbsim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kHuge = 1e308;  // finite; two of them add up to infinity

BodyDef sphereAt(const std::string& name, const Vec3& position, const Vec3& velocity = Vec3::Zero()) {
  BodyDef def;
  def.name = name;
  def.shape = SphereShape{0.1};
  def.position = position;
  def.linearVelocity = velocity;
  def.angularVelocity = Vec3(0.5, -1.0, 2.0);
  return def;
}

BodyDef boxAt(const std::string& name, const Vec3& position) {
  BodyDef def;
  def.name = name;
  def.shape = BoxShape{Vec3(0.2, 0.2, 0.2)};
  def.position = position;
  return def;
}

BodyDef ground() {
  BodyDef def;
  def.name = "ground";
  def.isStatic = true;
  def.shape = PlaneShape{Vec3::UnitZ(), 0.0};
  return def;
}

// Free bodies in flight (no contact), with the victim optionally among them.
World flyingWorld(bool withVictim) {
  World world;
  world.createBody(sphereAt("a", Vec3(0, 0, 5), Vec3(1, 0, 3))).value();
  if (withVictim) world.createBody(sphereAt("victim", Vec3(3, 0, 5), Vec3(0, 1, 0))).value();
  world.createBody(sphereAt("b", Vec3(-3, 0, 5), Vec3(0, -1, 2))).value();
  return world;
}

// A stack of two boxes on the ground (resting contact, islands, sleeping)
// and a ball far off that may be the victim.
World stackWorld(bool withVictim, const WorldSettings& settings = {}) {
  World world(settings);
  world.createBody(ground()).value();
  world.createBody(boxAt("bottom", Vec3(0, 0, 0.2))).value();
  if (withVictim) world.createBody(sphereAt("victim", Vec3(10, 0, 3))).value();
  world.createBody(boxAt("top", Vec3(0.05, 0, 0.6))).value();
  return world;
}

bool bitEqual(const RigidState& x, const RigidState& y) {
  const auto same = [](double p, double q) { return std::memcmp(&p, &q, sizeof p) == 0; };
  for (int i = 0; i < 3; ++i) {
    if (!same(x.position[i], y.position[i]) || !same(x.linearMomentum[i], y.linearMomentum[i]) ||
        !same(x.angularMomentum[i], y.angularMomentum[i]))
      return false;
  }
  return same(x.orientation.w, y.orientation.w) && same(x.orientation.x, y.orientation.x) &&
         same(x.orientation.y, y.orientation.y) && same(x.orientation.z, y.orientation.z);
}

// Steps both worlds `steps` times and requires every body of `reference` to
// have the bit-identical state in `guarded` after each step.
void expectOthersUnaffected(World& guarded, World& reference, int steps) {
  for (int s = 0; s < steps; ++s) {
    guarded.step();
    reference.step();
    for (const BodyView body : reference.bodies()) {
      const BodyId id = guarded.findBody(body.name());
      ASSERT_FALSE(id.isNull());
      ASSERT_TRUE(bitEqual(guarded.body(id).state(), body.state()))
          << body.name() << " differs after step " << guarded.stepCount();
    }
  }
}

void expectHeldStill(BodyView body, const Vec3& position, const Quaternion& orientation) {
  EXPECT_TRUE(body.isFrozen());
  EXPECT_EQ(body.position(), position);
  EXPECT_EQ(body.orientation().w, orientation.w);
  EXPECT_EQ(body.orientation().x, orientation.x);
  EXPECT_EQ(body.linearVelocity(), Vec3::Zero());
  EXPECT_EQ(body.angularVelocity(), Vec3::Zero());
}

TEST(StateGuard, NanForceFreezesTheBodyAndLeavesTheOthersBitIdentical) {
  World guarded = flyingWorld(true);
  World reference = flyingWorld(false);
  expectOthersUnaffected(guarded, reference, 20);
  const BodyId victim = guarded.findBody("victim");
  const Vec3 poseBefore = guarded.body(victim).position();
  const Quaternion turnBefore = guarded.body(victim).orientation();

  // The physics API takes any value (the server's wrench validation is the
  // first line of defence; this is the second).
  guarded.applyWrench(victim, {Vec3(kNaN, 0, 0), Vec3::Zero(), poseBefore, Wrench::Frame::World});
  guarded.step();
  reference.step();

  ASSERT_EQ(guarded.freezeEvents().size(), 1u);
  const FreezeEvent& event = guarded.freezeEvents().front();
  EXPECT_EQ(event.name, "victim");
  EXPECT_EQ(event.id, victim);
  EXPECT_EQ(event.step, 21);
  EXPECT_EQ(event.verdict.reason, FreezeReason::NonFiniteState);
  EXPECT_NE(describeFreeze(event).find("body 'victim' frozen at step 21: its state became non-finite"),
            std::string::npos)
      << describeFreeze(event);
  EXPECT_EQ(guarded.frozenBodyCount(), 1);
  expectHeldStill(guarded.body(victim), poseBefore, turnBefore);

  // Gravity and pushes no longer move it, and it is reported only once.
  guarded.applyWrench(victim, {Vec3(1, 2, 3), Vec3::Zero(), poseBefore, Wrench::Frame::World});
  expectOthersUnaffected(guarded, reference, 50);
  EXPECT_TRUE(guarded.freezeEvents().empty());
  expectHeldStill(guarded.body(victim), poseBefore, turnBefore);
  EXPECT_EQ(guarded.frozenBodyCount(), 1);
}

TEST(StateGuard, FiniteForcesThatOverflowFreezeTheBody) {
  // Two finite forces of 1e308 N sum to infinity in the accumulated load.
  World world = flyingWorld(true);
  const BodyId victim = world.findBody("victim");
  const Vec3 at = world.body(victim).position();
  world.applyWrench(victim, {Vec3(kHuge, 0, 0), Vec3::Zero(), at, Wrench::Frame::World});
  world.applyWrench(victim, {Vec3(kHuge, 0, 0), Vec3::Zero(), at, Wrench::Frame::World});
  world.step();
  ASSERT_EQ(world.freezeEvents().size(), 1u);
  EXPECT_EQ(world.freezeEvents()[0].verdict.reason, FreezeReason::NonFiniteState);
  EXPECT_EQ(world.body(victim).position(), at);

  // A finite force at a long lever arm: its moment overflows.
  World lever = flyingWorld(true);
  const BodyId other = lever.findBody("victim");
  lever.applyWrench(other, {Vec3(0, kHuge, 0), Vec3::Zero(), lever.body(other).position() + Vec3(10, 0, 0), Wrench::Frame::World});
  lever.step();
  ASSERT_EQ(lever.freezeEvents().size(), 1u);
  EXPECT_EQ(lever.freezeEvents()[0].verdict.reason, FreezeReason::NonFiniteState);
}

TEST(StateGuard, EveryIntegratorAndContactModelFreezesAndHolds) {
  for (const IntegratorKind integrator :
       {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4}) {
    for (const int mode : {0, 1, 2}) {  // impulse, penalty, backtracking
      SCOPED_TRACE(std::string(integratorName(integrator)) + " mode " + std::to_string(mode));
      WorldSettings settings;
      settings.integrator = integrator;
      settings.contact.model = mode == 1 ? ContactModel::Penalty : ContactModel::Impulse;
      settings.contact.backtracking = mode == 2;
      World world = stackWorld(true, settings);
      World reference = stackWorld(false, settings);
      expectOthersUnaffected(world, reference, 10);
      const BodyId victim = world.findBody("victim");
      const Vec3 at = world.body(victim).position();
      const Quaternion turn = world.body(victim).orientation();
      world.applyWrench(victim, {Vec3(0, 0, kNaN), Vec3::Zero(), Vec3::Zero(), Wrench::Frame::Body});
      expectOthersUnaffected(world, reference, 200);
      expectHeldStill(world.body(victim), at, turn);
      EXPECT_FALSE(world.body(victim).isSleeping());
      EXPECT_EQ(world.frozenBodyCount(), 1);
    }
  }
}

TEST(StateGuard, OverSpeedFreezesWithTheSpeedInTheReport) {
  World world;
  StateLimits limits;
  limits.maxLinearSpeed = 10.0;
  limits.maxAngularSpeed = 50.0;
  world.setStateLimits(limits);
  world.setGravity(Vec3::Zero());
  const BodyId fast = world.createBody(sphereAt("fast", Vec3::Zero(), Vec3(9.99, 0, 0))).value();
  const BodyId spinner = world.createBody(sphereAt("spinner", Vec3(5, 0, 0))).value();
  const BodyId calm = world.createBody(sphereAt("calm", Vec3(-5, 0, 0), Vec3(1, 0, 0))).value();
  world.step();
  EXPECT_TRUE(world.freezeEvents().empty());

  // 1 N for 1 ms on a 4.19 kg ball is far too little; 1e5 N is 24 m/s.
  const Vec3 before = world.body(fast).position();
  world.applyWrench(fast, {Vec3(1e5, 0, 0), Vec3::Zero(), before, Wrench::Frame::World});
  world.applyWrench(spinner, {Vec3::Zero(), Vec3(0, 0, 1e3), Vec3::Zero(), Wrench::Frame::Body});
  world.step();
  ASSERT_EQ(world.freezeEvents().size(), 2u);
  const FreezeEvent& linear = world.freezeEvents()[0];
  EXPECT_EQ(linear.id, fast);
  EXPECT_EQ(linear.verdict.reason, FreezeReason::LinearSpeed);
  EXPECT_GT(linear.verdict.measured, 10.0);
  EXPECT_EQ(linear.verdict.limit, 10.0);
  EXPECT_NE(describeFreeze(linear).find("linear speed"), std::string::npos);
  EXPECT_NE(describeFreeze(linear).find("limits.max_linear_speed (10 m/s)"), std::string::npos)
      << describeFreeze(linear);
  const FreezeEvent& angular = world.freezeEvents()[1];
  EXPECT_EQ(angular.id, spinner);
  EXPECT_EQ(angular.verdict.reason, FreezeReason::AngularSpeed);
  EXPECT_GT(angular.verdict.measured, 50.0);
  // Back to the pose before the bad step, still.
  EXPECT_EQ(world.body(fast).position(), before);
  EXPECT_EQ(world.body(fast).linearVelocity(), Vec3::Zero());
  EXPECT_FALSE(world.body(calm).isFrozen());
  EXPECT_EQ(world.frozenBodyCount(), 2);
}

TEST(StateGuard, ALongThinBodySpinningBelowTheLimitStaysFree) {
  // Spun about its long-inertia axis, its |L| max(I⁻¹) is 30 times its |ω|:
  // the quick bound cannot clear it, the exact check must.
  World world;
  StateLimits limits;
  limits.maxAngularSpeed = 100.0;
  world.setStateLimits(limits);
  world.setGravity(Vec3::Zero());
  BodyDef rod = boxAt("rod", Vec3::Zero());
  rod.shape = BoxShape{Vec3(0.5, 0.01, 0.01)};
  rod.angularVelocity = Vec3(0.0, 0.0, 90.0);
  const BodyId id = world.createBody(rod).value();
  for (int s = 0; s < 100; ++s) world.step();
  EXPECT_FALSE(world.body(id).isFrozen());
  EXPECT_NEAR(world.body(id).angularVelocity().norm(), 90.0, 1e-6);
  world.applyWrench(id, {Vec3::Zero(), Vec3(0, 0, 1e3), Vec3::Zero(), Wrench::Frame::Body});
  world.step();
  EXPECT_TRUE(world.body(id).isFrozen());
}

TEST(StateGuard, AContinuousCollisionBodyIsJudgedAfterItsSweep) {
  World world = stackWorld(false);
  BodyDef bullet = sphereAt("bullet", Vec3(3, 0, 2), Vec3(20, 0, 0));
  bullet.continuousCollision = true;
  const BodyId id = world.createBody(bullet).value();
  for (int s = 0; s < 3; ++s) world.step();
  const Vec3 before = world.body(id).position();
  world.applyWrench(id, {Vec3(kNaN, 0, 0), Vec3::Zero(), before, Wrench::Frame::World});
  world.step();
  ASSERT_EQ(world.freezeEvents().size(), 1u);
  EXPECT_EQ(world.body(id).position(), before);
}

TEST(StateGuard, ABodyCreatedTooFastFreezesOnItsFirstStepWhereItWasPlaced) {
  World world;
  StateLimits limits;
  limits.maxLinearSpeed = 100.0;
  world.setStateLimits(limits);
  const BodyId bullet = world.createBody(sphereAt("bullet", Vec3(1, 2, 3), Vec3(500, 0, 0))).value();
  world.step();
  ASSERT_EQ(world.freezeEvents().size(), 1u);
  EXPECT_EQ(world.freezeEvents()[0].step, 1);
  EXPECT_EQ(world.body(bullet).position(), Vec3(1, 2, 3));
}

TEST(StateGuard, AFrozenBodyTakesNoPartInContacts) {
  // A ball dropped onto a frozen box falls through it exactly as if the box
  // were not there.
  const auto make = [](bool withBox) {
    World world;
    world.createBody(ground()).value();
    if (withBox) world.createBody(boxAt("box", Vec3(0, 0, 0.2))).value();
    BodyDef ball = sphereAt("ball", Vec3(0, 0, 1.0));
    ball.angularVelocity = Vec3::Zero();
    world.createBody(ball).value();
    return world;
  };
  World guarded = make(true);
  World reference = make(false);
  ASSERT_TRUE(guarded.freezeBody(guarded.findBody("box")));
  EXPECT_FALSE(guarded.freezeBody(guarded.findBody("box")));     // already frozen
  EXPECT_FALSE(guarded.freezeBody(guarded.findBody("ground")));  // static
  EXPECT_TRUE(guarded.freezeEvents().empty());  // asked for, not found by the guard
  expectOthersUnaffected(guarded, reference, 600);
  EXPECT_LT(guarded.body(guarded.findBody("ball")).position().z(), 0.2);  // through the box, onto the ground
  for (const SolvedManifold& contact : guarded.contacts())
    EXPECT_NE(guarded.bodies()[static_cast<std::size_t>(contact.bodyB)].name(), "box");
}

TEST(StateGuard, AFrozenWallDoesNotStopAContinuousCollisionBody) {
  // Continuous collision ignores a frozen body too: a bullet fired at a
  // frozen wall flies on exactly as if the wall were not there.
  const auto make = [](bool withWall) {
    World world;
    world.setGravity(Vec3::Zero());
    if (withWall) {
      BodyDef wall = boxAt("wall", Vec3(0.5, 0, 0));
      wall.shape = BoxShape{Vec3(0.0025, 0.5, 0.5)};
      world.createBody(wall).value();
    }
    BodyDef bullet = sphereAt("bullet", Vec3::Zero(), Vec3(200, 0, 0));
    bullet.shape = SphereShape{0.01};
    bullet.continuousCollision = true;
    world.createBody(bullet).value();
    return world;
  };
  World guarded = make(true);
  World reference = make(false);
  ASSERT_TRUE(guarded.freezeBody(guarded.findBody("wall")));
  expectOthersUnaffected(guarded, reference, 20);
  EXPECT_GT(guarded.body(guarded.findBody("bullet")).position().x(), 1.0) << "through the wall";
}

TEST(StateGuard, RemovingOrResettingClearsTheFrozenState) {
  World initial = flyingWorld(true);
  World world = initial;
  world.applyWrench(world.findBody("victim"), {Vec3(kNaN, 0, 0), Vec3::Zero(), Vec3::Zero(), Wrench::Frame::World});
  world.step();
  ASSERT_EQ(world.frozenBodyCount(), 1);

  // RESET is a fresh copy of the initial world: nothing frozen there.
  World reset = initial;
  EXPECT_EQ(reset.frozenBodyCount(), 0);
  EXPECT_FALSE(reset.body(reset.findBody("victim")).isFrozen());

  // Removing the body clears the count; a body spawned under its name is new.
  ASSERT_TRUE(world.removeBody(world.findBody("victim")));
  EXPECT_EQ(world.frozenBodyCount(), 0);
  const BodyId again = world.createBody(sphereAt("victim", Vec3(3, 0, 5))).value();
  world.step();
  EXPECT_FALSE(world.body(again).isFrozen());
  EXPECT_TRUE(world.freezeEvents().empty());
}

TEST(StateGuard, ACheckpointKeepsABodyFrozenAndTheRunBitIdentical) {
  World world = stackWorld(true);
  for (int s = 0; s < 5; ++s) world.step();
  world.applyWrench(world.findBody("victim"), {Vec3(kNaN, 0, 0), Vec3::Zero(), Vec3::Zero(), Wrench::Frame::World});
  world.step();
  ASSERT_EQ(world.frozenBodyCount(), 1);

  const auto bytes = world.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  auto restored = World::decodeSnapshot(*bytes, world.settings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  EXPECT_EQ(restored->frozenBodyCount(), 1);
  EXPECT_EQ(restored->body(restored->findBody("victim")).freezeReason(), FreezeReason::NonFiniteState);
  for (int s = 0; s < 100; ++s) {
    world.step();
    restored->step();
  }
  EXPECT_EQ(restored->stateHash(), world.stateHash());
  EXPECT_TRUE(restored->body(restored->findBody("victim")).isFrozen());
}

}  // namespace
}  // namespace rbsim
