// Limits, motors and efforts against their closed forms: a motor with a
// torque cap spins a wheel up at exactly α = τ / I and then holds the rate;
// a direct effort accelerates a wheel and a slider exactly; a slider at its
// limit holds a box with a reaction of m g; a hinge stops at its limit and
// rests there; a motor at rate zero holds an arm against gravity.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::hinge;
using testing::jointWorldSettings;

constexpr double kPi = std::numbers::pi;

// A wheel (a cylinder along z, r = 0.2 m, 2 kg: I = m r² / 2 = 0.04 kg·m²)
// on a vertical hinge through its centre, gravity along the axis.
struct Wheel {
  World world;
  BodyId body;
  JointId joint;
  double inertia = 0.5 * 2.0 * 0.2 * 0.2;
};

Wheel makeWheel(double dt) {
  Wheel wheel{World(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt)), {}, {}};
  wheel.body = addBody(wheel.world, "wheel", CylinderShape{0.2, 0.05}, 2.0, Vec3(0, 0, 1));
  wheel.joint = addJoint(wheel.world, hinge("axle", BodyId{}, wheel.body, Vec3(0, 0, 1), Vec3::UnitZ()));
  return wheel;
}

TEST(JointActuation, AMotorSpinsAWheelUpAtTorqueOverInertiaThenHoldsTheRate) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    Wheel wheel = makeWheel(dt);
    const double torque = 0.5, target = 5.0;  // N·m, rad/s: α = 12.5 rad/s², the target at 0.4 s
    ASSERT_TRUE(wheel.world.setJointMotor(wheel.joint, {true, target, torque}).ok());
    const double alpha = torque / wheel.inertia;
    for (int k = 0; k < static_cast<int>(std::lround(0.2 / dt)); ++k) wheel.world.step();
    JointState state = wheel.world.jointState(wheel.joint);
    EXPECT_NEAR(state.rate, alpha * wheel.world.time(), 1e-9) << "capped: exactly τ / I";
    EXPECT_NEAR(state.axisEffort, torque, 1e-9);
    EXPECT_NEAR(state.position, 0.5 * alpha * wheel.world.time() * wheel.world.time(), alpha * dt * 0.2)
        << "the angle, to the staggering of a step";
    for (int k = 0; k < static_cast<int>(std::lround(0.6 / dt)); ++k) wheel.world.step();
    state = wheel.world.jointState(wheel.joint);
    EXPECT_NEAR(state.rate, target, 1e-9) << "then it holds the target";
    EXPECT_NEAR(state.axisEffort, 0.0, 1e-9) << "with no torque left to give";
    EXPECT_LT(state.error, 1e-11);
  }
}

TEST(JointActuation, ADirectEffortAcceleratesAWheelAndASliderExactly) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    Wheel wheel = makeWheel(dt);
    ASSERT_TRUE(wheel.world.setJointEffort(wheel.joint, 0.2).ok());
    const int steps = static_cast<int>(std::lround(1.0 / dt));
    const double alpha = 0.2 / wheel.inertia;
    // Leapfrog's angle is ½ α t² exactly, less what the pose update's turn
    // (body/integrator.h: q + ½ h [0, ω] q, normalised) gives short of h ω
    // each step: h ω − 2 atan(h ω / 2), with ω the drift's rate α (k + ½) h.
    double shortfall = 0.0;
    for (int k = 0; k < steps; ++k) {
      wheel.world.step();
      const double turn = dt * alpha * (k + 0.5) * dt;
      shortfall += turn - 2.0 * std::atan(0.5 * turn);
    }
    const double t = wheel.world.time();
    EXPECT_NEAR(wheel.world.jointState(wheel.joint).rate, alpha * t, 1e-9);
    EXPECT_NEAR(wheel.world.jointState(wheel.joint).position, 0.5 * alpha * t * t - shortfall, 1e-9);

    // A 2 kg box on a horizontal slider pushed with 3 N: x = ½ (F/m) t².
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, 2.0, Vec3(0, 0, 1));
    JointDef slider;
    slider.name = "slider";
    slider.type = JointType::Prismatic;
    slider.bodyB = box;
    slider.anchor = Vec3(0, 0, 1);
    slider.axis = Vec3(1, 1, 0);
    slider.effort = 3.0;
    const JointId joint = addJoint(world, slider);
    for (int k = 0; k < steps; ++k) world.step();
    EXPECT_NEAR(world.jointState(joint).position, 0.5 * 1.5 * t * t, 1e-9);
    EXPECT_NEAR(world.jointState(joint).rate, 1.5 * t, 1e-9);
  }
}

TEST(JointActuation, ASliderMotorDrivesABoxToItsTargetSpeed) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, 2.0, Vec3(0, 0, 1));
  JointDef slider;
  slider.name = "conveyor";
  slider.type = JointType::Prismatic;
  slider.bodyB = box;
  slider.anchor = Vec3(0, 0, 1);
  slider.axis = Vec3::UnitX();
  slider.motor = {true, 1.0, 2.0};  // 1 m/s with at most 2 N: a = 1 m/s², there at 1 s
  const JointId joint = addJoint(world, slider);
  for (int k = 0; k < 500; ++k) world.step();
  EXPECT_NEAR(world.jointState(joint).rate, 0.5, 1e-9);
  for (int k = 0; k < 1000; ++k) world.step();
  EXPECT_NEAR(world.jointState(joint).rate, 1.0, 1e-9);
  EXPECT_NEAR(world.body(box).linearVelocity().x(), 1.0, 1e-9);
}

TEST(JointActuation, ASliderAtItsLimitHoldsABoxWithAReactionOfItsWeight) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const double mass = 3.0;
    const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, mass, Vec3(0, 0, 1));
    JointDef slider;
    slider.name = "lift";
    slider.type = JointType::Prismatic;
    slider.bodyB = box;
    slider.anchor = Vec3(0, 0, 1);
    slider.axis = Vec3::UnitZ();
    slider.limit = {true, -0.2, 0.5};
    const JointId joint = addJoint(world, slider);
    for (int k = 0; k < static_cast<int>(std::lround(1.0 / dt)); ++k) world.step();
    const JointState state = world.jointState(joint);
    EXPECT_NEAR(state.position, -0.2, 1e-9) << "it fell 0.2 m and stopped";
    EXPECT_NEAR(state.rate, 0.0, 1e-9);
    EXPECT_EQ(state.atLimit, -1);
    EXPECT_LT((state.force - Vec3(0, 0, mass * testing::kGravity)).norm(), 1e-9) << state.force.transpose();
    EXPECT_NEAR(world.body(box).position().z(), 0.8, 1e-9);
  }
}

TEST(JointActuation, AHingeStopsAtItsLimitAndRestsThere) {
  // An arm released horizontal, allowed to swing down only to 40° below
  // the horizontal (the hinge's coordinate runs about +y, so downwards
  // from +x is positive).
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId arm = addBody(world, "arm", SphereShape{0.05}, 1.0, Vec3(0.5, 0, 0));
  JointDef def = hinge("elbow", BodyId{}, arm, Vec3::Zero(), Vec3::UnitY());
  def.limit = {true, -1.0, 40.0 * kPi / 180.0};
  const JointId joint = addJoint(world, def);
  double largest = 0.0;
  for (int k = 0; k < 2000; ++k) {
    world.step();
    largest = std::max(largest, world.jointState(joint).position);
  }
  const JointState state = world.jointState(joint);
  EXPECT_LT(largest, 40.0 * kPi / 180.0 + 1e-9) << "never beyond the limit";
  EXPECT_NEAR(state.position, 40.0 * kPi / 180.0, 1e-9) << "at rest against it";
  EXPECT_NEAR(state.rate, 0.0, 1e-9);
  EXPECT_EQ(state.atLimit, 1);
  EXPECT_LT(state.error, 1e-11);
}

TEST(JointActuation, AMotorAtRateZeroHoldsAnArmAgainstGravity) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId arm = addBody(world, "arm", SphereShape{0.05}, 1.0, Vec3(0.5, 0, 0));
  JointDef def = hinge("shoulder", BodyId{}, arm, Vec3::Zero(), Vec3::UnitY());
  def.motor = {true, 0.0, 10.0};  // m g d = 4.9 N·m needed
  const JointId joint = addJoint(world, def);
  for (int k = 0; k < 1000; ++k) world.step();
  const JointState state = world.jointState(joint);
  EXPECT_NEAR(state.position, 0.0, 1e-9);
  EXPECT_NEAR(state.axisEffort, -testing::kGravity * 0.5, 1e-6) << "the motor gives the arm's weight moment";
  // A cap below the weight's moment cannot hold it: the arm falls.
  ASSERT_TRUE(world.setJointMotor(joint, {true, 0.0, 2.0}).ok());
  for (int k = 0; k < 200; ++k) world.step();
  EXPECT_GT(world.jointState(joint).position, 0.01);
  EXPECT_FALSE(world.setJointMotor(joint, {true, 0.0, -1.0}).ok()) << "a negative cap is refused";
}

}  // namespace
}  // namespace rbsim
