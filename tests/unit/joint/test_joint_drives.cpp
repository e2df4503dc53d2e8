// Drives, joint damping and joint friction against their closed forms.
//  - The axis laws alone (joint/axis_actuation.h): each law's root by hand.
//  - A position drive's step response: the damped oscillator
//    I θ'' + c θ' + k (θ − θ*) = 0 from rest, to the first order in h of
//    its implicit step (the error halves with the step), and a drive given
//    as a frequency and damping ratio moves any inertia the same way.
//  - A drive holding a pendulum against gravity settles where
//    k (θ* − θ) = m g l sin θ.
//  - Joint damping slows a free wheel exactly as its two implicit half
//    steps a step say, ω_n = ω₀ (1 + h c / 2I)⁻²ⁿ, within O(h) of
//    ω₀ e^(−c t / I).
//  - Joint friction holds a wheel still below its torque and lets it
//    accelerate at (τ − f) / I above it; it stops a spinning wheel at
//    t = I ω₀ / f and keeps it stopped.
//  - A motor against friction spins up at (cap − f) / I and then holds its
//    rate with an effort of f.
//  - A drive following a ramp θ* = v t: with the target rate v its error
//    obeys I e'' + c e' + k e = 0 and vanishes; without it the joint lags
//    by c v / k, the closed form's steady state.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "joint/joint_test_worlds.h"
#include "physics/joint/axis_actuation.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::hinge;
using testing::jointWorldSettings;

constexpr double kPi = std::numbers::pi;

TEST(AxisLaw, EachLawsRootByHand) {
  const double h = 1e-3, a = 25.0;  // the step, the axis's inverse inertia (I = 0.04)
  AxisLaw motor;
  motor.h = h;
  motor.motor = true;
  motor.motorTarget = 5.0;
  motor.motorCap = 0.5 * h;
  // Far from its target: the cap, exactly.
  AxisImpulse out = solveAxisLaw(motor, 1.0, a);
  EXPECT_EQ(out.total, motor.motorCap);
  EXPECT_EQ(out.actuation, motor.motorCap);
  EXPECT_DOUBLE_EQ(out.rate, 1.0 + a * motor.motorCap);
  // Within reach: the target, exactly.
  out = solveAxisLaw(motor, 4.99, a);
  EXPECT_EQ(out.rate, 5.0);
  EXPECT_NEAR(out.total, 0.01 / a, 1e-15);

  AxisLaw friction;
  friction.h = h;
  friction.frictionCap = 0.1 * h;
  out = solveAxisLaw(friction, 0.001, a);  // stopped: 0.001 needs 4e-5 N·m·s < 1e-4
  EXPECT_EQ(out.rate, 0.0);
  EXPECT_NEAR(out.total, -0.001 / a, 1e-18);
  EXPECT_EQ(out.actuation, 0.0) << "friction is not actuation";
  out = solveAxisLaw(friction, -1.0, a);  // sliding: the whole cap against the motion
  EXPECT_EQ(out.total, friction.frictionCap);
  EXPECT_DOUBLE_EQ(out.rate, -1.0 + a * friction.frictionCap);

  AxisLaw damping;
  damping.h = h;
  damping.damping = 2.0;
  out = solveAxisLaw(damping, 3.0, a);  // w = 3 − a h c w
  EXPECT_NEAR(out.rate, 3.0 / (1.0 + a * h * 2.0), 1e-15);

  AxisLaw drive;
  drive.h = h;
  drive.drive = true;
  drive.driveError = -0.5;
  drive.driveStiffness = 200.0;
  drive.driveDamping = 20.0;
  drive.driveLookahead = h;
  // w = w₀ + a Λ, Λ = −h (k (e + h w) + c w)
  const double w0 = 0.3;
  const double expected = (w0 - a * h * 200.0 * -0.5) / (1.0 + a * h * (200.0 * h + 20.0));
  out = solveAxisLaw(drive, w0, a);
  EXPECT_NEAR(out.rate, expected, 1e-14);
  EXPECT_NEAR(out.actuation, out.total, 1e-18);
  drive.driveCap = 1e-3 * h;  // capped at 1 mN·m
  out = solveAxisLaw(drive, w0, a);
  EXPECT_EQ(out.total, drive.driveCap);

  // A motor at rest against friction: friction takes what it can hold, the
  // motor the rest (here nothing: the target is rest).
  AxisLaw both = motor;
  both.motorTarget = 0.0;
  both.frictionCap = friction.frictionCap;
  out = solveAxisLaw(both, 0.001, a);
  EXPECT_EQ(out.rate, 0.0);
  EXPECT_NEAR(out.total, -0.001 / a, 1e-18);
  EXPECT_EQ(out.actuation, 0.0);
  out = solveAxisLaw(both, 0.01, a);  // more than friction holds: the motor gives the rest
  EXPECT_EQ(out.rate, 0.0);
  EXPECT_NEAR(out.actuation, -0.01 / a + friction.frictionCap, 1e-18);
}

// A wheel (a cylinder along z, r = 0.2 m, 2 kg: I = m r² / 2 = 0.04 kg·m²)
// on a vertical hinge through its centre: gravity along the axis does no
// work on the joint.
struct Wheel {
  World world;
  BodyId body;
  JointId joint;
  double inertia = 0.5 * 2.0 * 0.2 * 0.2;
};

Wheel makeWheel(double dt, double mass = 2.0, IntegratorKind integrator = IntegratorKind::SemiImplicitEuler) {
  Wheel wheel{World(jointWorldSettings(integrator, dt)), {}, {}, 0.5 * mass * 0.2 * 0.2};
  wheel.body = addBody(wheel.world, "wheel", CylinderShape{0.2, 0.05}, mass, Vec3(0, 0, 1));
  wheel.joint = addJoint(wheel.world, hinge("axle", BodyId{}, wheel.body, Vec3(0, 0, 1), Vec3::UnitZ()));
  return wheel;
}

// θ(t) of I θ'' + c θ' + k (θ − θ*) = 0 from θ = 0 at rest, underdamped.
double stepResponse(double t, double target, double omega, double zeta) {
  const double damped = omega * std::sqrt(1.0 - zeta * zeta);
  return target * (1.0 - std::exp(-zeta * omega * t) *
                             (std::cos(damped * t) + zeta * omega / damped * std::sin(damped * t)));
}

// The largest |θ − closed form| over 2 s of a drive's step response.
double driveResponseError(double dt, const JointDrive& drive, double omega, double zeta, double mass = 2.0) {
  Wheel wheel = makeWheel(dt, mass);
  EXPECT_TRUE(wheel.world.setJointDrive(wheel.joint, drive).ok());
  double worst = 0.0;
  for (int k = 0; k < static_cast<int>(std::lround(2.0 / dt)); ++k) {
    wheel.world.step();
    const double theta = wheel.world.jointState(wheel.joint).position;
    worst = std::max(worst, std::abs(theta - stepResponse(wheel.world.time(), drive.target, omega, zeta)));
  }
  return worst;
}

TEST(JointDrives, AStepResponseIsTheDampedOscillatorsToFirstOrderInTheStep) {
  const double inertia = 0.04, stiffness = 0.25, damping = 0.024;  // ω = 2.5 rad/s, ζ = 0.12
  const double omega = std::sqrt(stiffness / inertia), zeta = damping / (2.0 * std::sqrt(stiffness * inertia));
  JointDrive drive;
  drive.enabled = true;
  drive.target = 0.8;
  drive.stiffness = stiffness;
  drive.damping = damping;
  const double coarse = driveResponseError(2e-3, drive, omega, zeta);
  const double fine = driveResponseError(1e-3, drive, omega, zeta);
  std::printf("drive step response over 2 s: largest error %.2e rad (dt 2 ms), %.2e rad (dt 1 ms) of %.1f rad\n", coarse,
              fine, drive.target);
  // The implicit spring damps by about ζ' = ω h / 2 more than ζ: over
  // T = 2 s the envelope is off by at most amplitude · ζ' ω T.
  EXPECT_LT(coarse, drive.target * 0.5 * omega * 2e-3 * omega * 2.0);
  EXPECT_LT(fine, drive.target * 0.5 * omega * 1e-3 * omega * 2.0);
  EXPECT_NEAR(coarse / fine, 2.0, 0.2) << "first order: the error is the step's, halving with it";
}

TEST(JointDrives, AFrequencyAndRatioMoveAnyInertiaTheSameWay) {
  JointDrive drive;
  drive.enabled = true;
  drive.target = -0.5;
  drive.frequency = 0.5;
  drive.dampingRatio = 0.3;
  const double omega = 2.0 * kPi * 0.5;
  const double light = driveResponseError(1e-3, drive, omega, 0.3, 2.0);
  const double heavy = driveResponseError(1e-3, drive, omega, 0.3, 50.0);
  EXPECT_LT(light, omega * 1e-3 * 0.5);
  EXPECT_NEAR(light, heavy, 1e-12) << "the gains scale with the inertia the axis moves";
}

TEST(JointDrives, ADriveHoldsAPendulumWhereItsSpringBalancesGravity) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    // A small 1 kg ball 0.5 m below a hinge along y: turned by θ about y,
    // gravity's torque about the hinge is −m g l sin θ.
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const double mass = 1.0, length = 0.5, radius = 0.02;
    const BodyId ball = addBody(world, "ball", SphereShape{radius}, mass, Vec3(0, 0, -length));
    const JointId joint = addJoint(world, hinge("pivot", BodyId{}, ball, Vec3::Zero(), Vec3::UnitY()));
    JointDrive drive;
    drive.enabled = true;
    drive.target = 0.6;
    drive.stiffness = 20.0;  // N·m/rad
    drive.damping = 2.0;     // N·m·s/rad: ζ ≈ 0.45 about the pivot's inertia of 0.25 kg·m²
    ASSERT_TRUE(world.setJointDrive(joint, drive).ok());
    for (int k = 0; k < static_cast<int>(std::lround(20.0 / dt)); ++k) world.step();
    // Equilibrium: k (θ* − θ) = m g l sin θ, by Newton.
    double theta = 0.3;
    for (int i = 0; i < 50; ++i) {
      const double f = drive.stiffness * (drive.target - theta) - mass * testing::kGravity * length * std::sin(theta);
      const double df = -drive.stiffness - mass * testing::kGravity * length * std::cos(theta);
      theta -= f / df;
    }
    const JointState state = world.jointState(joint);
    EXPECT_NEAR(state.position, theta, 1e-9);
    EXPECT_NEAR(state.rate, 0.0, 1e-9);
    EXPECT_NEAR(state.axisEffort, drive.stiffness * (drive.target - theta), 1e-6)
        << "the drive's effort is the spring's";
  }
}

TEST(JointDrives, ACappedDriveGivesNoMoreThanItsCap) {
  Wheel wheel = makeWheel(1e-3);
  JointDrive drive;
  drive.enabled = true;
  drive.target = 3.0;  // rad, less than half a turn: a wheel's drive takes the short way round
  drive.stiffness = 100.0;
  drive.maxEffort = 0.2;  // N·m: the spring would give about 250
  ASSERT_TRUE(wheel.world.setJointDrive(wheel.joint, drive).ok());
  for (int k = 0; k < 500; ++k) wheel.world.step();
  const JointState state = wheel.world.jointState(wheel.joint);
  EXPECT_NEAR(state.axisEffort, 0.2, 1e-12);
  EXPECT_NEAR(state.rate, 0.2 / wheel.inertia * wheel.world.time(), 1e-9) << "α = cap / I";
}

TEST(JointDrives, ATargetRateLetsADriveFollowARampWithoutLag) {
  const double stiffness = 4.0, damping = 0.8, rate = 0.5;  // ω = 10 rad/s, ζ = 1 on I = 0.04 kg·m²
  for (const double dt : {1e-3, 5e-4}) {
    for (const bool withRate : {true, false}) {
      SCOPED_TRACE(::testing::Message() << "dt " << dt << (withRate ? ", with" : ", without") << " target rate");
      Wheel wheel = makeWheel(dt);
      JointDrive drive;
      drive.enabled = true;
      drive.stiffness = stiffness;
      drive.damping = damping;
      drive.targetRate = withRate ? rate : 0.0;
      double lag = 0.0;
      for (int k = 0; k < static_cast<int>(std::lround(3.0 / dt)); ++k) {
        // The target where the step ends, as a controller sets it each step.
        drive.target = rate * (wheel.world.time() + dt);
        ASSERT_TRUE(wheel.world.setJointDrive(wheel.joint, drive).ok());
        wheel.world.step();
        lag = rate * wheel.world.time() - wheel.world.jointState(wheel.joint).position;
      }
      // e(0) = 0, e'(0) = v, critically damped: e = v t e^(−ω t), 1.5e-13 rad
      // at 3 s. What stays is the step's own, second order in it (measured:
      // 2.1e-9 rad and 1.0e-8 rad/s at 1 ms, a quarter of that at 0.5 ms).
      const double positionBound = 4e-3 * dt * dt, rateBound = 2e-2 * dt * dt;
      if (withRate) EXPECT_NEAR(lag, 0.0, positionBound);
      else EXPECT_NEAR(lag, damping * rate / stiffness, positionBound) << "the damper's pull on v, c v / k";
      EXPECT_NEAR(wheel.world.jointState(wheel.joint).rate, rate, rateBound);
    }
  }
}

TEST(JointDrives, JointDampingSlowsAWheelAsTheExponentialDoes) {
  // Damping's first half acts on the step's start rate, e⁻ˣ (1 + x/2) of it
  // left, its second half implicitly, 1 / (1 + x/2) (x = c h / I): a lone
  // damped axis follows the flow e^(−c t / I) exactly, at any step. (Two
  // implicit halves, (1 + x/2)⁻², were x²/4 a step off it: first order.)
  for (const double dt : {1e-3, 5e-4, 0.05}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    Wheel wheel = makeWheel(dt);
    JointDef def = hinge("axle", BodyId{}, wheel.body, Vec3(0, 0, 1), Vec3::UnitZ());
    ASSERT_TRUE(wheel.world.removeJoint(wheel.joint).ok());
    def.damping = 0.02;  // N·m·s/rad: c / I = 0.5 /s
    wheel.joint = addJoint(wheel.world, def);
    ASSERT_TRUE(wheel.world.setBodyVelocities(wheel.body, Vec3::Zero(), Vec3(0, 0, 4.0)).ok());
    const int steps = static_cast<int>(std::lround(2.0 / dt));
    for (int k = 0; k < steps; ++k) wheel.world.step();
    const double rate = wheel.world.jointState(wheel.joint).rate;
    const double decay = 0.02 / wheel.inertia;
    EXPECT_NEAR(rate, 4.0 * std::exp(-decay * 2.0), 1e-12);
    EXPECT_NEAR(wheel.world.jointState(wheel.joint).axisEffort, 0.0, 0.0) << "damping is not actuation";
  }
}

// The rate of a wheel on a hinge after 2 s from 4 rad/s, with its body's
// own angular damping (1/s) and the hinge's damping (N·m·s/rad).
double dampedWheelRate(double dt, double bodyDamping, double jointDamping, double& inertia) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
  BodyDef def;
  def.name = "wheel";
  def.shape = CylinderShape{0.2, 0.05};
  def.mass = 2.0;
  def.position = Vec3(0, 0, 1);
  def.angularDamping = bodyDamping;
  def.angularVelocity = Vec3(0, 0, 4.0);
  const Expected<BodyId> wheel = world.createBody(def);
  EXPECT_TRUE(wheel.ok());
  if (!wheel.ok()) return NAN;
  inertia = world.body(*wheel).inertiaWorld()(2, 2);
  JointDef axle = hinge("axle", BodyId{}, *wheel, Vec3(0, 0, 1), Vec3::UnitZ());
  axle.damping = jointDamping;
  const JointId joint = addJoint(world, axle);
  for (int k = 0; k < static_cast<int>(std::lround(2.0 / dt)); ++k) world.step();
  return world.jointState(joint).rate;
}

TEST(JointDrives, AHingedWheelsOwnDampingSlowsItAsTheExponentialDoes) {
  // The body's angular damping (dL/dt = −c L) in the joint step: e^(−c h)
  // (1 + c h/2) of L left by the first half, 1 / (1 + c h/2) by the
  // implicit second half: exactly e^(−c t), at any step.
  double inertia = 0.0;
  for (const double dt : {1e-3, 0.05}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    EXPECT_NEAR(dampedWheelRate(dt, 0.3, 0.0, inertia), 4.0 * std::exp(-0.3 * 2.0), 1e-12);
  }
  // With the hinge's damping as well the rates add, to second order (each
  // first half is exact alone, their sum to O((c h)³) a step).
  double errors[2];
  for (int k = 0; k < 2; ++k) {
    const double rate = dampedWheelRate(1e-3 / (1 + k), 0.3, 0.02, inertia);
    errors[k] = std::abs(rate - 4.0 * std::exp(-(0.3 + 0.02 / inertia) * 2.0));
  }
  EXPECT_LT(errors[0], 1e-7);
  EXPECT_LT(errors[1], 0.3 * errors[0]) << errors[0] << " then " << errors[1];
}

TEST(JointDrives, StrongJointDampingStopsALightWheelWithoutTurningItBack) {
  // c h / I = 100 at 1 ms: the wheel stops within a step or two, its rate
  // never changing sign (an explicit half of −c (h/2) w would send it back
  // at 0.96 of its speed, step after step).
  Wheel wheel = makeWheel(1e-3);
  JointDef def = hinge("axle", BodyId{}, wheel.body, Vec3(0, 0, 1), Vec3::UnitZ());
  ASSERT_TRUE(wheel.world.removeJoint(wheel.joint).ok());
  def.damping = 100.0 * wheel.inertia / 1e-3;
  wheel.joint = addJoint(wheel.world, def);
  ASSERT_TRUE(wheel.world.setBodyVelocities(wheel.body, Vec3::Zero(), Vec3(0, 0, 4.0)).ok());
  double previous = 4.0;
  for (int k = 0; k < 5; ++k) {
    wheel.world.step();
    const double rate = wheel.world.jointState(wheel.joint).rate;
    EXPECT_GE(rate, 0.0) << "step " << k;
    EXPECT_LE(rate, 4.0 * std::exp(-100.0 * (k + 1)) + 1e-15) << "step " << k;
    EXPECT_LE(rate, previous);
    previous = rate;
  }
}

TEST(JointDrives, FrictionHoldsBelowItsTorqueAndSlidesAboveIt) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    Wheel wheel = makeWheel(dt);
    JointDef def = hinge("axle", BodyId{}, wheel.body, Vec3(0, 0, 1), Vec3::UnitZ());
    ASSERT_TRUE(wheel.world.removeJoint(wheel.joint).ok());
    def.friction = 0.1;  // N·m
    wheel.joint = addJoint(wheel.world, def);
    ASSERT_TRUE(wheel.world.setJointEffort(wheel.joint, 0.08).ok());
    for (int k = 0; k < static_cast<int>(std::lround(0.5 / dt)); ++k) wheel.world.step();
    EXPECT_EQ(wheel.world.jointState(wheel.joint).rate, 0.0) << "static: 0.08 N·m < 0.1 N·m";
    ASSERT_TRUE(wheel.world.setJointEffort(wheel.joint, 0.3).ok());
    const double start = wheel.world.time();
    for (int k = 0; k < static_cast<int>(std::lround(0.5 / dt)); ++k) wheel.world.step();
    EXPECT_NEAR(wheel.world.jointState(wheel.joint).rate, (0.3 - 0.1) / wheel.inertia * (wheel.world.time() - start),
                1e-9)
        << "sliding: α = (τ − f) / I";
    // Let go: friction stops it at t = I ω / f and holds it there.
    ASSERT_TRUE(wheel.world.setJointEffort(wheel.joint, 0.0).ok());
    const double spin = wheel.world.jointState(wheel.joint).rate;
    const double stopAfter = wheel.inertia * spin / 0.1;
    const double letGo = wheel.world.time();
    double stopped = -1.0;
    for (int k = 0; k < static_cast<int>(std::lround((stopAfter + 0.5) / dt)); ++k) {
      wheel.world.step();
      if (stopped < 0.0 && wheel.world.jointState(wheel.joint).rate == 0.0) stopped = wheel.world.time() - letGo;
    }
    EXPECT_GE(stopped, stopAfter - 1e-9);
    EXPECT_LE(stopped, stopAfter + dt + 1e-9) << "in the step it lands in";
    EXPECT_EQ(wheel.world.jointState(wheel.joint).rate, 0.0);
  }
}

TEST(JointDrives, AMotorAgainstFrictionSpinsUpAtCapLessFrictionThenHoldsItsRate) {
  Wheel wheel = makeWheel(1e-3);
  JointDef def = hinge("axle", BodyId{}, wheel.body, Vec3(0, 0, 1), Vec3::UnitZ());
  ASSERT_TRUE(wheel.world.removeJoint(wheel.joint).ok());
  def.friction = 0.1;
  def.motor = {true, 2.0, 0.5};  // 2 rad/s, 0.5 N·m: α = 10 rad/s², the target at 0.2 s
  wheel.joint = addJoint(wheel.world, def);
  for (int k = 0; k < 100; ++k) wheel.world.step();
  EXPECT_NEAR(wheel.world.jointState(wheel.joint).rate, (0.5 - 0.1) / wheel.inertia * wheel.world.time(), 1e-9);
  EXPECT_NEAR(wheel.world.jointState(wheel.joint).axisEffort, 0.5, 1e-9);
  for (int k = 0; k < 400; ++k) wheel.world.step();
  EXPECT_NEAR(wheel.world.jointState(wheel.joint).rate, 2.0, 1e-12);
  EXPECT_NEAR(wheel.world.jointState(wheel.joint).axisEffort, 0.1, 1e-9) << "the motor pays friction's toll";
}

TEST(JointDrives, AMotorAndADriveAreOneOrTheOther) {
  Wheel wheel = makeWheel(1e-3);
  ASSERT_TRUE(wheel.world.setJointMotor(wheel.joint, {true, 1.0, 1.0}).ok());
  JointDrive drive;
  drive.enabled = true;
  drive.stiffness = 1.0;
  ASSERT_TRUE(wheel.world.setJointDrive(wheel.joint, drive).ok());
  for (int k = 0; k < 10; ++k) wheel.world.step();
  // The drive alone: the motor (1 N·m at 1 rad/s) would have spun it up
  // at 25 rad/s², the drive at k θ / I ≈ 0 from rest at its target.
  EXPECT_NEAR(wheel.world.jointState(wheel.joint).rate, 0.0, 1e-12);
  drive.stiffness = -1.0;
  const Expected<bool> bad = wheel.world.setJointDrive(wheel.joint, drive);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("joint 'axle': the drive's stiffness"), std::string::npos) << bad.error().message;
  JointDef both = hinge("both", BodyId{}, wheel.body, Vec3(0, 0, 1), Vec3::UnitZ());
  both.motor = {true, 1.0, 1.0};
  both.drive.enabled = true;
  both.drive.stiffness = 1.0;
  const Expected<JointId> created = wheel.world.createJoint(both);
  ASSERT_FALSE(created.ok());
  EXPECT_NE(created.error().message.find("a motor or a drive, not both"), std::string::npos);
}

TEST(JointDrives, ADriveKeepsItsBodyAwakeUntilItSettlesThenItSleeps) {
  WorldSettings settings = jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3);
  settings.contact.sleeping = true;
  World world(settings);
  const BodyId wheel = addBody(world, "wheel", CylinderShape{0.2, 0.05}, 2.0, Vec3(0, 0, 1));
  const JointId joint = addJoint(world, hinge("axle", BodyId{}, wheel, Vec3(0, 0, 1), Vec3::UnitZ()));
  JointDrive drive;
  drive.enabled = true;
  drive.target = 1.0;
  drive.stiffness = 0.04;  // ω = 1 rad/s
  drive.damping = 0.24;    // ζ = 3: creeps, e^(−0.17 t), below the bodies' sleep rate for many seconds
  ASSERT_TRUE(world.setJointDrive(joint, drive).ok());
  const double sleepRate = settings.contact.sleepAngularVelocity;
  double slowAt = -1.0, asleepAt = -1.0;
  for (int k = 0; k < 60000 && asleepAt < 0.0; ++k) {
    world.step();
    if (slowAt < 0.0 && world.time() > 1.0 && std::abs(world.jointState(joint).rate) < sleepRate) slowAt = world.time();
    if (world.body(wheel).isSleeping()) asleepAt = world.time();
  }
  ASSERT_GT(slowAt, 0.0);
  ASSERT_GT(asleepAt, 0.0) << "it never slept";
  EXPECT_GT(asleepAt, slowAt + 10.0) << "awake long after it went slower than a body's sleep threshold";
  EXPECT_NEAR(world.jointState(joint).position, 1.0, 1e-3) << "asleep only once at its target, at " << asleepAt << " s";
}

}  // namespace
}  // namespace rbsim
