// A joint made at a nonzero coordinate (JointDef::position), as a robot
// description places its bodies at its joints' positions: the joint reads
// that position where it was made, and its limits and its drive's target are
// in the same terms. Against closed forms: a hinged arm and a slider stop at
// their bounds exactly (so a hinge made at 0.3 with limits ±0.5 turns 0.2 one
// way and 0.8 the other), a drive rests where its spring balances gravity
// about the zero pose, and a checkpoint keeps the position.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

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

Quaternion aboutY(double angle) { return Quaternion::fromAxisAngle(Vec3::UnitY(), angle); }

TEST(JointPositions, AHingeMadeAtAPositionReadsItAndStopsAtItsLimitsInTheSameTerms) {
  // An arm 0.5 m long on a hinge along +y through the origin; in its zero
  // pose it lies horizontal, along +x (side +1) or along −x (side −1). It is
  // made turned 0.3 rad from there, limits ±0.5 rad: gravity turns the +x arm
  // 0.2 further (up to +0.5), the −x arm 0.8 back (down to −0.5).
  constexpr double kStart = 0.3, kLower = -0.5, kUpper = 0.5, kLength = 0.5;
  for (const double dt : {1e-3, 5e-4}) {
    for (const int side : {+1, -1}) {
      SCOPED_TRACE(::testing::Message() << "dt " << dt << ", side " << side);
      World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
      const Vec3 zeroPose(side * kLength, 0, 0);
      const BodyId arm =
          addBody(world, "arm", SphereShape{0.05}, 1.0, aboutY(kStart).rotate(zeroPose), aboutY(kStart));
      JointDef def = hinge("shoulder", BodyId{}, arm, Vec3::Zero(), Vec3::UnitY());
      def.position = kStart;
      def.limit = {true, kLower, kUpper};
      const JointId joint = addJoint(world, def);
      EXPECT_NEAR(world.jointState(joint).position, kStart, 1e-15) << "where it was made";
      EXPECT_EQ(world.jointDefinition(joint).position, kStart);

      const double bound = side > 0 ? kUpper : kLower;
      double farthest = 0.0;  // beyond the bound, on its side
      for (int k = 0; k < static_cast<int>(std::lround(2.0 / dt)); ++k) {
        world.step();
        farthest = std::max(farthest, side * (world.jointState(joint).position - bound));
      }
      const JointState state = world.jointState(joint);
      EXPECT_LT(farthest, 1e-9) << "never beyond the bound";
      EXPECT_NEAR(state.position, bound, 1e-9) << "at rest against it";
      EXPECT_NEAR(state.rate, 0.0, 1e-9);
      EXPECT_EQ(state.atLimit, side);
      EXPECT_LT(state.error, 1e-11);
      // The bound is measured from the zero pose, not from where it was made.
      EXPECT_LT((world.body(arm).position() - aboutY(bound).rotate(zeroPose)).norm(), 1e-9)
          << world.body(arm).position().transpose();
    }
  }
}

TEST(JointPositions, ASliderMadeAtAPositionStopsWhereItsLimitSays) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    // A 3 kg box on a vertical slider made at 0.1 m, limits [−0.2, 0.5] m:
    // it falls 0.3 m and rests on the lower stop with a reaction of m g.
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const double mass = 3.0;
    const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, mass, Vec3(0, 0, 1));
    JointDef lift = slider("lift", BodyId{}, box, Vec3(0, 0, 1), Vec3::UnitZ());
    lift.position = 0.1;
    lift.limit = {true, -0.2, 0.5};
    const JointId joint = addJoint(world, lift);
    EXPECT_NEAR(world.jointState(joint).position, 0.1, 1e-15);
    for (int k = 0; k < static_cast<int>(std::lround(1.0 / dt)); ++k) world.step();
    const JointState state = world.jointState(joint);
    EXPECT_NEAR(state.position, -0.2, 1e-9);
    EXPECT_NEAR(state.rate, 0.0, 1e-9);
    EXPECT_EQ(state.atLimit, -1);
    EXPECT_LT((state.force - Vec3(0, 0, mass * kGravity)).norm(), 1e-9) << state.force.transpose();
    EXPECT_NEAR(world.body(box).position().z(), 1.0 - 0.3, 1e-9);

    // Made on its lower stop (allowed: a stop is within the limits), it
    // rests there from the first step.
    World onStop(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const BodyId resting = addBody(onStop, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, mass, Vec3(0, 0, 1));
    lift.bodyB = resting;
    lift.position = -0.2;
    const JointId held = addJoint(onStop, lift);
    for (int k = 0; k < 100; ++k) onStop.step();
    EXPECT_NEAR(onStop.jointState(held).position, -0.2, 1e-9);
    EXPECT_NEAR(onStop.body(resting).position().z(), 1.0, 1e-9);
  }
}

TEST(JointPositions, ADrivesTargetIsInTheJointsOwnTerms) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    // A 1 kg ball 0.5 m below a hinge along y (the zero pose hangs), made
    // turned 0.2 rad: a drive to 0.6 rad rests where k (θ* − θ) = m g l sin θ,
    // θ from the hanging pose, wherever the ball was made.
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const double mass = 1.0, length = 0.5, start = 0.2;
    const Vec3 hanging(0, 0, -length);
    const BodyId ball = addBody(world, "ball", SphereShape{0.02}, mass, aboutY(start).rotate(hanging), aboutY(start));
    JointDef def = hinge("pivot", BodyId{}, ball, Vec3::Zero(), Vec3::UnitY());
    def.position = start;
    def.drive.enabled = true;
    def.drive.target = 0.6;
    def.drive.stiffness = 20.0;  // N·m/rad
    def.drive.damping = 2.0;     // N·m·s/rad
    const JointId joint = addJoint(world, def);
    for (int k = 0; k < static_cast<int>(std::lround(20.0 / dt)); ++k) world.step();
    double theta = 0.3;
    for (int i = 0; i < 50; ++i) {
      const double f = def.drive.stiffness * (def.drive.target - theta) - mass * kGravity * length * std::sin(theta);
      const double df = -def.drive.stiffness - mass * kGravity * length * std::cos(theta);
      theta -= f / df;
    }
    EXPECT_NEAR(world.jointState(joint).position, theta, 1e-9);
    EXPECT_NEAR(world.jointState(joint).rate, 0.0, 1e-9);
    EXPECT_LT((world.body(ball).position() - aboutY(theta).rotate(hanging)).norm(), 1e-9);

    // A 2 kg box on a vertical slider made at 0.1 m, driven to 0.3 m by a
    // 100 N/m spring: it rests at 0.3 − m g / k, 0.1 m below where it was
    // made plus what the spring stretches.
    World lift(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const double boxMass = 2.0, stiffness = 100.0;
    const BodyId box = addBody(lift, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, boxMass, Vec3(0, 0, 1));
    JointDef raised = slider("lift", BodyId{}, box, Vec3(0, 0, 1), Vec3::UnitZ());
    raised.position = 0.1;
    const JointId servo = addJoint(lift, raised);
    JointDrive drive;
    drive.enabled = true;
    drive.target = 0.3;
    drive.stiffness = stiffness;
    drive.damping = 20.0;  // N·s/m: ζ ≈ 0.7
    ASSERT_TRUE(lift.setJointDrive(servo, drive).ok());
    for (int k = 0; k < static_cast<int>(std::lround(10.0 / dt)); ++k) lift.step();
    const double rest = drive.target - boxMass * kGravity / stiffness;
    EXPECT_NEAR(lift.jointState(servo).position, rest, 1e-9);
    EXPECT_NEAR(lift.body(box).position().z(), 1.0 + (rest - 0.1), 1e-9);
  }
}

TEST(JointPositions, OnlyAnAxisTakesAFinitePosition) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, 1.0, Vec3(0, 0, 1));
  for (const JointType type : {JointType::Fixed, JointType::Spherical, JointType::Distance}) {
    JointDef def;
    def.name = jointTypeName(type);
    def.type = type;
    def.bodyB = box;
    def.anchor = Vec3(0, 0, 1.5);
    def.anchorB = Vec3(0, 0, 1);
    def.position = 0.1;
    EXPECT_NE(creationError(world, def).find("joint '" + def.name +
                                             "': only revolute and prismatic joints take a position"),
              std::string::npos)
        << def.name;
  }
  JointDef def = hinge("elbow", BodyId{}, box, Vec3(0, 0, 1), Vec3::UnitY());
  def.limit = {true, -0.5, 0.5};
  def.position = NAN;
  EXPECT_NE(creationError(world, def).find("the position is not finite"), std::string::npos);
  def.limit.enabled = false;
  def.position = INFINITY;
  EXPECT_NE(creationError(world, def).find("the position is not finite"), std::string::npos);
  EXPECT_EQ(world.jointCount(), 0) << "none of them was made";
  def.limit.enabled = true;
  def.position = 0.5;  // on a stop
  EXPECT_EQ(creationError(world, def), "");
}

TEST(JointPositions, ACheckpointKeepsTheCreationPosition) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId arm = addBody(world, "arm", SphereShape{0.05}, 1.0, aboutY(0.3).rotate(Vec3(0.5, 0, 0)), aboutY(0.3));
  JointDef def = hinge("shoulder", BodyId{}, arm, Vec3::Zero(), Vec3::UnitY());
  def.position = 0.3;
  def.limit = {true, -0.5, 0.5};
  const JointId joint = addJoint(world, def);
  for (int k = 0; k < 50; ++k) world.step();
  const Expected<std::vector<uint8_t>> bytes = world.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  Expected<World> restored = World::decodeSnapshot(*bytes, world.settings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  const JointId restoredJoint = restored->findJoint("shoulder");
  EXPECT_EQ(restored->jointDefinition(restoredJoint).position, 0.3);
  EXPECT_EQ(restored->jointState(restoredJoint).position, world.jointState(joint).position);
  for (int k = 0; k < 1000; ++k) {
    world.step();
    restored->step();
  }
  EXPECT_EQ(restored->stateHash(), world.stateHash()) << "it steps on bit-identically";
  EXPECT_EQ(restored->jointState(restoredJoint).position, world.jointState(joint).position);
  EXPECT_NEAR(world.jointState(joint).position, 0.5, 1e-9) << "and stops at the same bound";
}

}  // namespace
}  // namespace rbsim
