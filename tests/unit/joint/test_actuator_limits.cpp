// A joint's actuator limits (JointDef::actuatorLimits, URDF's <limit effort
// velocity>) against closed forms: whatever the joint is commanded, the
// motor, the drive and the direct effort give at most the effort limit (a
// wheel spins up at exactly limit / I), the motor's target is cut to the
// rate limit, and a stiff drive lifting a box slews at exactly the rate
// limit, pushing its weight, then settles where its spring balances it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::creationError;
using testing::hinge;
using testing::jointWorldSettings;
using testing::kGravity;
using testing::slider;

// A wheel (a cylinder along z, r = 0.2 m, 2 kg: I = m r² / 2 = 0.04 kg·m²)
// on a vertical hinge through its centre, gravity along the axis.
constexpr double kWheelInertia = 0.5 * 2.0 * 0.2 * 0.2;

struct Wheel {
  World world;
  JointId joint;
};

Wheel makeWheel(double dt, const JointActuatorLimits& limits) {
  Wheel wheel{World(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt)), {}};
  const BodyId body = addBody(wheel.world, "wheel", CylinderShape{0.2, 0.05}, 2.0, Vec3(0, 0, 1));
  JointDef def = hinge("axle", BodyId{}, body, Vec3(0, 0, 1), Vec3::UnitZ());
  def.actuatorLimits = limits;
  wheel.joint = addJoint(wheel.world, def);
  return wheel;
}

void stepFor(World& world, double seconds) {
  const auto steps = std::lround(seconds / world.settings().dt);
  for (long k = 0; k < steps; ++k) world.step();
}

constexpr double kNone = std::numeric_limits<double>::infinity();

TEST(ActuatorLimits, TheEffortLimitCapsAMotorWhateverItsOwnCap) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    Wheel wheel = makeWheel(dt, {0.2, kNone});
    ASSERT_TRUE(wheel.world.setJointMotor(wheel.joint, {true, 50.0, 5.0}).ok());  // asks for 5 N·m
    stepFor(wheel.world, 0.5);
    const JointState state = wheel.world.jointState(wheel.joint);
    EXPECT_NEAR(state.rate, 0.2 / kWheelInertia * wheel.world.time(), 1e-9) << "α = limit / I";
    EXPECT_NEAR(state.axisEffort, 0.2, 1e-9);
  }
}

TEST(ActuatorLimits, TheEffortLimitCapsADirectEffortBothWays) {
  for (const double commanded : {1.0, -1.0}) {
    Wheel wheel = makeWheel(1e-3, {0.3, kNone});
    ASSERT_TRUE(wheel.world.setJointEffort(wheel.joint, commanded).ok());
    stepFor(wheel.world, 0.4);
    const JointState state = wheel.world.jointState(wheel.joint);
    EXPECT_NEAR(state.rate, std::copysign(0.3, commanded) / kWheelInertia * wheel.world.time(), 1e-9);
    EXPECT_NEAR(state.axisEffort, std::copysign(0.3, commanded), 1e-12);
  }
}

TEST(ActuatorLimits, TheRateLimitCutsAMotorsTarget) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    Wheel wheel = makeWheel(dt, {kNone, 2.0});
    ASSERT_TRUE(wheel.world.setJointMotor(wheel.joint, {true, -5.0, 1.0}).ok());
    stepFor(wheel.world, 0.04);  // α = 25 rad/s²: 2 rad/s at 0.08 s
    EXPECT_NEAR(wheel.world.jointState(wheel.joint).rate, -25.0 * wheel.world.time(), 1e-9);
    stepFor(wheel.world, 0.5);
    EXPECT_NEAR(wheel.world.jointState(wheel.joint).rate, -2.0, 1e-9) << "the limit, not the target";
    EXPECT_NEAR(wheel.world.jointState(wheel.joint).axisEffort, 0.0, 1e-9);
  }
}

// A 2 kg box on a vertical slider, its drive (k = 1e5 N/m, c = 2000 N·s/m)
// told to lift it 1 m with a rate limit of 0.5 m/s: unlimited it would
// leap; limited it rises at exactly 0.5 m/s, the drive pushing exactly its
// weight m g, and arrives where the spring holds the weight, m g / k below
// the target.
TEST(ActuatorLimits, ADriveWithARateLimitSlewsAtItThenSettlesOnTarget) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const double mass = 2.0, stiffness = 1e5, damping = 2000.0, rate = 0.5;
    const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, mass, Vec3(0, 0, 1));
    JointDef def = slider("lift", BodyId{}, box, Vec3(0, 0, 1), Vec3::UnitZ());
    def.drive.enabled = true;
    def.drive.target = 1.0;
    def.drive.stiffness = stiffness;
    def.drive.damping = damping;
    def.actuatorLimits = {kNone, rate};
    const JointId joint = addJoint(world, def);
    stepFor(world, 1.0);
    JointState state = world.jointState(joint);
    EXPECT_NEAR(state.rate, rate, 1e-9) << "at the rate limit";
    EXPECT_NEAR(state.axisEffort, mass * kGravity, 1e-6) << "holding the rate against gravity";
    EXPECT_NEAR(state.position, rate * world.time(), 2.0 * rate * dt) << "a steady slew from the first step";
    stepFor(world, 2.0);
    state = world.jointState(joint);
    EXPECT_NEAR(state.position, 1.0 - mass * kGravity / stiffness, 1e-9) << "the spring holding the weight";
    EXPECT_NEAR(state.rate, 0.0, 1e-9);
    EXPECT_NEAR(state.axisEffort, mass * kGravity, 1e-9);
  }
}

// Above the rate limit the drive still brakes: a box falling on a slider
// whose drive holds it at its start is caught, and the fall does not
// exceed what the drive lets through.
TEST(ActuatorLimits, ADriveBeyondItsRateLimitStillBrakes) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, 1.0, Vec3(0, 0, 1));
  JointDef def = slider("lift", BodyId{}, box, Vec3(0, 0, 1), Vec3::UnitZ());
  def.drive = {true, 0.0, 1e4, 200.0, 0.0, 0.0, kNone};
  def.actuatorLimits = {kNone, 0.01};
  const JointId joint = addJoint(world, def);
  ASSERT_TRUE(world.setJointEffort(joint, -200.0).ok());  // shoves it down at 200 m/s² for a moment
  stepFor(world, 0.05);
  ASSERT_TRUE(world.setJointEffort(joint, 0.0).ok());
  // Pushed about 2 cm down (k x = 200 N), it comes back up at 1 cm/s.
  stepFor(world, 1.0);
  EXPECT_NEAR(world.jointState(joint).rate, 0.01, 1e-9) << "back up no faster than the limit";
  stepFor(world, 3.0);
  const JointState state = world.jointState(joint);
  EXPECT_NEAR(state.position, -kGravity / 1e4, 1e-4) << "caught and held near its target";
  EXPECT_LT(std::abs(state.rate), 0.01 + 1e-9);
}

TEST(ActuatorLimits, AreRefusedWhenNotPositiveOrOnAJointWithoutAnAxis) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, 1.0, Vec3(0, 0, 1));
  JointDef def = hinge("h", BodyId{}, box, Vec3(0, 0, 1), Vec3::UnitZ());
  def.actuatorLimits = {0.0, kNone};
  EXPECT_NE(creationError(world, def).find("the actuator's effort and rate limits must be positive"), std::string::npos);
  def.actuatorLimits = {kNone, std::nan("")};
  EXPECT_NE(creationError(world, def).find("must be positive"), std::string::npos);
  def.type = JointType::Spherical;
  def.actuatorLimits = {10.0, kNone};
  EXPECT_NE(creationError(world, def).find("only revolute and prismatic joints take actuator limits"),
            std::string::npos);
}

// A checkpoint holds the limits: the world decoded from a snapshot slews
// on bit-identically.
TEST(ActuatorLimits, SurviveASnapshot) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, 2.0, Vec3(0, 0, 1));
  JointDef def = slider("lift", BodyId{}, box, Vec3(0, 0, 1), Vec3::UnitZ());
  def.drive = {true, 1.0, 1e5, 2000.0, 0.0, 0.0, 30.0};
  def.actuatorLimits = {25.0, 0.5};  // 25 N lifts its 19.6 N weight: 0.5 m/s at 0.18 s
  const JointId joint = addJoint(world, def);
  stepFor(world, 0.3);
  const Expected<std::vector<uint8_t>> bytes = world.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  Expected<World> copy = World::decodeSnapshot(*bytes, world.settings());
  ASSERT_TRUE(copy.ok()) << copy.error().message;
  const JointId copied = copy->findJoint("lift");
  stepFor(world, 0.3);
  stepFor(*copy, 0.3);
  EXPECT_EQ(world.jointState(joint).position, copy->jointState(copied).position);
  EXPECT_EQ(world.jointState(joint).rate, copy->jointState(copied).rate);
  EXPECT_EQ(copy->jointState(copied).axisEffort, world.jointState(joint).axisEffort);
  EXPECT_NEAR(world.jointState(joint).rate, 0.5, 1e-9);
}

}  // namespace
}  // namespace rbsim
