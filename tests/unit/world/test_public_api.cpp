// The public API's promises (rbsim/physics/world.h): an id that names no body
// of this world is an error in every build, not only an assert; changes go
// through World and act as documented.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "rbsim/physics/world.h"
#include "support/torque_free_world.h"

namespace rbsim {
namespace {

WorldSettings weightless() { return testing::torqueFreeSettings(IntegratorKind::SemiImplicitEuler, 0.001); }

BodyDef boxDef(const std::string& name, const Vec3& position = Vec3::Zero()) {
  BodyDef def;
  def.name = name;
  def.shape = BoxShape{Vec3(0.1, 0.2, 0.3)};
  def.mass = 2.0;
  def.position = position;
  return def;
}

// The message of the invalid_argument that body(id) throws ("" if none).
std::string bodyError(const World& world, BodyId id) {
  try {
    (void)world.body(id);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PublicApi, StaleIdIsAnErrorAndNeverReachesTheBodyInItsSlot) {
  World world(weightless());
  const BodyId removed = *world.createBody(boxDef("removed"));
  ASSERT_TRUE(world.removeBody(removed));
  const BodyId heir = *world.createBody(boxDef("heir"));
  ASSERT_EQ(heir.index, removed.index) << "the slot is reused";

  EXPECT_NE(bodyError(world, removed).find("stale"), std::string::npos) << bodyError(world, removed);
  const auto pushed = world.applyWrench(removed, {Vec3(1, 0, 0), Vec3::Zero(), Vec3::Zero()});
  ASSERT_FALSE(pushed.ok());
  EXPECT_NE(pushed.error().message.find("stale"), std::string::npos) << pushed.error().message;
  EXPECT_FALSE(world.setBodyVelocities(removed, Vec3(1, 0, 0), Vec3::Zero()).ok());
  EXPECT_FALSE(world.setBodyState(removed, RigidState{}).ok());
  EXPECT_FALSE(world.setBodyDamping(removed, 1.0, 1.0).ok());
  EXPECT_FALSE(world.wakeUp(removed).ok());
  EXPECT_FALSE(world.freezeBody(removed).ok());
  EXPECT_FALSE(world.removeBody(removed).ok());

  world.step();
  EXPECT_EQ(world.body(heir).linearMomentum(), Vec3::Zero()) << "nothing reached the heir";
  EXPECT_EQ(world.bodyCount(), 1);
}

TEST(PublicApi, IdOfAnotherWorldIsAnErrorAndACopyKeepsItsIds) {
  WorldDef def;
  def.settings = weightless();
  def.bodies = {boxDef("a"), boxDef("b", Vec3(1, 0, 0))};
  World first = *World::fromDef(def);
  World second = *World::fromDef(def);
  const BodyId a = first.findBody("a");
  ASSERT_EQ(second.findBody("a").index, a.index) << "the same slot in both";

  EXPECT_FALSE(second.isValid(a));
  EXPECT_NE(bodyError(second, a).find("another world"), std::string::npos) << bodyError(second, a);
  const auto pushed = second.applyWrench(a, {Vec3(1, 0, 0), Vec3::Zero(), Vec3::Zero()});
  ASSERT_FALSE(pushed.ok());
  EXPECT_NE(pushed.error().message.find("another world"), std::string::npos);

  // A copy is the same world at another moment: the ids hold in both.
  World copy = first;
  EXPECT_TRUE(copy.isValid(a));
  EXPECT_EQ(copy.body(a).name(), "a");
}

TEST(PublicApi, NullIdIsAnError) {
  World world(weightless());
  (void)*world.createBody(boxDef("a"));
  EXPECT_NE(bodyError(world, BodyId{}).find("null"), std::string::npos);
  EXPECT_FALSE(world.applyWrench(BodyId{}, Wrench{}).ok());
  EXPECT_TRUE(world.findBody("nobody").isNull());
}

// Δp = F dt and ΔL = (τ + r × F) dt over one step, for each of the three
// frames a wrench may be given in, on a weightless free box turned 90° about z.
TEST(PublicApi, WrenchFramesThroughTheWorld) {
  const Vec3 force(3, -1, 2), torque(0.5, 0, -0.25), point(0.05, 0.1, -0.2);
  const Quaternion turn = Quaternion::fromAxisAngle(Vec3::UnitZ(), M_PI / 2);
  for (const IntegratorKind integrator :
       {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4}) {
    for (const Wrench::Frame frame : {Wrench::Frame::World, Wrench::Frame::WorldAtBodyPoint, Wrench::Frame::Body}) {
      WorldSettings settings = weightless();
      settings.integrator = integrator;
      World world(settings);
      BodyDef def = boxDef("box", Vec3(1, 2, 3));
      def.orientation = turn;
      const BodyId box = *world.createBody(def);
      const Mat3 rotation = world.body(box).rotation();
      ASSERT_TRUE(world.applyWrench(box, {force, torque, point, frame}));
      world.step();
      const double dt = settings.dt;
      // The wrench in world terms at the step's start.
      Vec3 worldForce = force, worldTorque = torque, lever = point - Vec3(1, 2, 3);
      if (frame == Wrench::Frame::WorldAtBodyPoint) lever = rotation * point;
      if (frame == Wrench::Frame::Body) {
        worldForce = rotation * force;
        worldTorque = rotation * torque;
        lever = rotation * point;
      }
      const BodyView after = world.body(box);
      // A body-frame force turns with the body: RK4 sees it turn within the
      // step (|ω| dt ~ 1e-5 here), the Euler methods at the start only.
      const double linearTolerance =
          frame == Wrench::Frame::Body && integrator == IntegratorKind::Rk4 ? 1e-5 * force.norm() * dt : 1e-15;
      EXPECT_NEAR((after.linearMomentum() - worldForce * dt).norm(), 0.0, linearTolerance);
      // The point turns with the body during the step: first order in dt.
      EXPECT_NEAR((after.angularMomentum() - (worldTorque + lever.cross(worldForce)) * dt).norm(), 0.0, 1e-6);
      const Vec3 momentumAfterPush = after.linearMomentum();
      world.step();
      EXPECT_EQ(world.body(box).linearMomentum(), momentumAfterPush) << "a wrench acts for one step";
    }
  }
}

TEST(PublicApi, StaticBodiesTakeNoWrenchAndBadStatesAreRefused) {
  World world(weightless());
  BodyDef floor;
  floor.name = "floor";
  floor.shape = PlaneShape{};
  floor.isStatic = true;
  const BodyId ground = *world.createBody(floor);
  const BodyId box = *world.createBody(boxDef("box", Vec3(0, 0, 1)));
  EXPECT_TRUE(world.applyWrench(ground, {Vec3(1e3, 0, 0), Vec3::Zero(), Vec3::Zero()}));
  EXPECT_FALSE(world.body(ground).isPushed());

  RigidState bad = world.body(box).state();
  bad.position.x() = std::nan("");
  const auto refused = world.setBodyState(box, bad);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("'box'"), std::string::npos) << refused.error().message;
  EXPECT_EQ(world.body(box).position(), Vec3(0, 0, 1));
  EXPECT_FALSE(world.setBodyDamping(box, -1.0, 0.0).ok());
  EXPECT_FALSE(world.setBodyVelocities(box, Vec3(INFINITY, 0, 0), Vec3::Zero()).ok());

  ASSERT_TRUE(world.setBodyVelocities(box, Vec3(0.5, 0, 0), Vec3(0, 0, 2)));
  EXPECT_NEAR((world.body(box).linearVelocity() - Vec3(0.5, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((world.body(box).angularVelocity() - Vec3(0, 0, 2)).norm(), 0.0, 1e-14);
}

}  // namespace
}  // namespace rbsim

namespace rbsim {
namespace {

// A quaternion with finite entries whose norm overflows (1e200² = inf) is no
// rotation: refused for a body and for a compound's part, never normalised
// into NaNs (a fuzzed checkpoint reached libccd that way).
TEST(PublicApi, QuaternionsWithoutARotationAreRefused) {
  World world;
  BodyDef body = boxDef("box");
  body.orientation = Quaternion{1e200, 0.0, 0.0, 0.0};
  const auto refused = world.createBody(body);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("finite norm"), std::string::npos) << refused.error().message;

  BodyDef compound;
  compound.name = "compound";
  CompoundPart part;
  part.shape = SphereShape{0.1};
  part.orientation = Quaternion{0.0, 1e200, 1e200, 0.0};
  compound.shape = CompoundShape{{part}};
  const auto refusedPart = world.createBody(compound);
  ASSERT_FALSE(refusedPart.ok());
  EXPECT_NE(refusedPart.error().message.find("compound part 0"), std::string::npos)
      << refusedPart.error().message;

  body.orientation = Quaternion{2.0, 0.0, 0.0, 0.0};  // not unit, but a rotation: normalised
  ASSERT_TRUE(world.createBody(body).ok());
  EXPECT_EQ(world.body(world.findBody("box")).orientation().w, 1.0);
}

}  // namespace
}  // namespace rbsim
