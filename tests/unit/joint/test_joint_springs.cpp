// Distance joints with a spring (a drive along the anchors' line, rest
// length its target) against their closed forms:
//  - a mass hung on a damped spring comes to rest stretched by m g / k, the
//    joint's force m g;
//  - undamped, it oscillates at ω = sqrt(k / m) (the implicit spring's period
//    error is O((ω h)²)), and its amplitude never grows: it decays as
//    e^(−ω² h t / 4), the first half kick's implicit spring shrinking each
//    step's phase-space area by 1 / (1 + (ω h)² / 2) (docs/joints_design.md);
//  - with stops, a spring too weak for its load rests on the upper stop
//    exactly, the stop and the spring together holding m g.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::jointWorldSettings;
using testing::kGravity;

constexpr IntegratorKind kIntegrators[] = {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler,
                                           IntegratorKind::Rk4};

// A spring from the world's point `anchor` to the centre of `bob`.
JointDef spring(BodyId bob, const Vec3& anchor, const Vec3& bobPosition, double rest, double stiffness, double damping) {
  JointDef def;
  def.name = "spring";
  def.type = JointType::Distance;
  def.bodyB = bob;
  def.anchor = anchor;
  def.anchorB = bobPosition;
  def.drive.enabled = true;
  def.drive.target = rest;
  def.drive.stiffness = stiffness;
  def.drive.damping = damping;
  return def;
}

TEST(JointSprings, AHangingMassRestsStretchedByMgOverK) {
  const double mass = 2.0, stiffness = 200.0, damping = 10.0, rest = 1.0;  // ζ = 0.25
  for (const IntegratorKind integrator : kIntegrators) {
    for (const double dt : {1e-3, 5e-4}) {
      SCOPED_TRACE(::testing::Message() << "integrator " << static_cast<int>(integrator) << ", dt " << dt);
      World world(jointWorldSettings(integrator, dt));
      const BodyId bob = addBody(world, "bob", SphereShape{0.05}, mass, Vec3(0, 0, -rest));
      const JointId joint = addJoint(world, spring(bob, Vec3::Zero(), Vec3(0, 0, -rest), rest, stiffness, damping));
      for (int i = 0; i < static_cast<int>(std::lround(12.0 / dt)); ++i) world.step();  // e^(−c t / 2m) ≈ 1e-13
      const JointState state = world.jointState(joint);
      EXPECT_NEAR(state.position, rest + mass * kGravity / stiffness, 1e-9);
      EXPECT_NEAR(world.body(bob).position().z(), -(rest + mass * kGravity / stiffness), 1e-9);
      EXPECT_NEAR(std::abs(state.rate), 0.0, 1e-9);
      // The spring pulls B up towards the anchor with m g; its effort is
      // along the line from A to B, outwards positive.
      EXPECT_NEAR(state.axisEffort, -mass * kGravity, 1e-6);
      EXPECT_NEAR(state.force.z(), mass * kGravity, 1e-6);
      EXPECT_EQ(state.atLimit, 0);
    }
  }
}

// The stretch of the undamped spring over 3 s: its period and how its
// amplitude decays.
struct Oscillation {
  double period = 0.0;
  double firstAmplitude = 0.0, lastAmplitude = 0.0;  // m, of the first and the last whole half swing
  double firstPeakTime = 0.0, lastPeakTime = 0.0;     // s, when they were reached
  bool grew = false;
};

Oscillation oscillate(IntegratorKind integrator, double dt, double mass, double stiffness) {
  WorldSettings settings = jointWorldSettings(integrator, dt);
  settings.gravity = Vec3::Zero();
  World world(settings);
  const double rest = 1.0, stretch = 0.1;
  const BodyId bob = addBody(world, "bob", SphereShape{0.05}, mass, Vec3(rest + stretch, 0, 0));
  const JointId joint = addJoint(world, spring(bob, Vec3::Zero(), Vec3(rest + stretch, 0, 0), rest, stiffness, 0.0));
  std::vector<double> times, stretches;
  Oscillation out;
  double peak = stretch, peakTime = 0.0, previousPeak = INFINITY;
  for (int i = 1; i <= static_cast<int>(std::lround(3.0 / dt)); ++i) {
    world.step();
    const double x = world.jointState(joint).position - rest;
    times.push_back(i * dt);
    stretches.push_back(x);
    if (stretches.size() > 1 && (stretches[stretches.size() - 2] > 0.0) != (x > 0.0)) {
      // A half swing ended: its peak is the amplitude of that half.
      if (out.firstAmplitude == 0.0) {
        out.firstAmplitude = peak;
        out.firstPeakTime = peakTime;
      }
      if (peak > previousPeak * (1.0 + 1e-12)) out.grew = true;
      previousPeak = peak;
      out.lastAmplitude = peak;
      out.lastPeakTime = peakTime;
      peak = 0.0;
    }
    if (std::abs(x) > peak) {
      peak = std::abs(x);
      peakTime = i * dt;
    }
  }
  out.period = testing::meanPeriod(testing::zeroCrossings(times, stretches));
  return out;
}

TEST(JointSprings, AnUndampedSpringOscillatesAtSqrtKOverM) {
  const double mass = 1.0, stiffness = 100.0;  // ω = 10 rad/s
  const double omega = std::sqrt(stiffness / mass), period = 2.0 * std::numbers::pi / omega;
  for (const IntegratorKind integrator : kIntegrators) {
    for (const double dt : {1e-3, 5e-4}) {
      SCOPED_TRACE(::testing::Message() << "integrator " << static_cast<int>(integrator) << ", dt " << dt);
      const Oscillation o = oscillate(integrator, dt, mass, stiffness);
      std::printf("spring dt %.1e: period %.6f s (closed form %.6f), amplitude %.5f -> %.5f m over 3 s\n", dt,
                  o.period, period, o.firstAmplitude, o.lastAmplitude);
      EXPECT_NEAR(o.period / period, 1.0, 2.0 * (omega * dt) * (omega * dt));
      EXPECT_FALSE(o.grew) << "an implicit spring never adds energy";
      // Decay e^(−ω² h t / 4) between the first and the last peak.
      const double expected = std::exp(-0.25 * omega * omega * dt * (o.lastPeakTime - o.firstPeakTime));
      std::printf("  decay %.6f, e^(-w^2 h t / 4) %.6f\n", o.lastAmplitude / o.firstAmplitude, expected);
      EXPECT_NEAR(o.lastAmplitude / o.firstAmplitude, expected, 0.01 * (1.0 - expected));
    }
  }
}

TEST(JointSprings, ASpringTooWeakForItsLoadRestsOnItsStop) {
  const double mass = 2.0, stiffness = 10.0, damping = 8.0, rest = 1.0, upper = 1.5;  // m g / k = 1.96 m > 0.5 m
  double effortError[2] = {0.0, 0.0};
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const BodyId bob = addBody(world, "bob", SphereShape{0.05}, mass, Vec3(0, 0, -rest));
    JointDef def = spring(bob, Vec3::Zero(), Vec3(0, 0, -rest), rest, stiffness, damping);
    def.limit = {true, 0.5, upper};
    const JointId joint = addJoint(world, def);
    for (int i = 0; i < static_cast<int>(std::lround(5.0 / dt)); ++i) world.step();
    const JointState state = world.jointState(joint);
    EXPECT_NEAR(state.position, upper, 1e-9);
    EXPECT_EQ(state.atLimit, 1);
    // The spring's own pull k (upper − rest), the stop taking the rest; to
    // first order in dt: in the first half kick the damper meets the rate
    // gravity's kick gives before the stop holds it (at most g h / 2).
    effortError[dt == 1e-3 ? 0 : 1] = std::abs(state.axisEffort + stiffness * (upper - rest));
    EXPECT_LT(std::abs(state.axisEffort + stiffness * (upper - rest)), 0.5 * damping * kGravity * dt);
    EXPECT_NEAR(state.force.z(), mass * kGravity, 1e-6) << "the spring and the stop together";
  }
  std::printf("spring at its stop: effort error %.2e N (dt 1 ms), %.2e N (dt 0.5 ms) of %.1f N\n", effortError[0],
              effortError[1], stiffness * (upper - rest));
  EXPECT_NEAR(effortError[0] / effortError[1], 2.0, 0.2) << "first order: the error halves with the step";
}

// A checkpoint taken mid-swing holds the spring (its gains, rest length and
// stops): the restored world steps on bit-identically.
TEST(JointSprings, ACheckpointKeepsASpring) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId bob = addBody(world, "bob", SphereShape{0.05}, 1.5, Vec3(0.3, 0, -1));
  JointDef def = spring(bob, Vec3::Zero(), Vec3(0.3, 0, -1), 0.9, 80.0, 0.5);
  def.limit = {true, 0.2, 1.3};
  addJoint(world, def);
  for (int i = 0; i < 700; ++i) world.step();
  const Expected<std::vector<uint8_t>> snapshot = world.encodeSnapshot();
  ASSERT_TRUE(snapshot.ok()) << snapshot.error().message;
  Expected<World> restored = World::decodeSnapshot(*snapshot, world.settings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  for (int i = 0; i < 700; ++i) {
    world.step();
    restored->step();
  }
  EXPECT_EQ(world.stateHash(), restored->stateHash());
  EXPECT_TRUE(restored->jointDefinitionAt(0).drive.enabled);
  EXPECT_EQ(restored->jointDefinitionAt(0).drive.target, 0.9);
}

// A new rest length and new gains set while the spring runs (as a joint
// command does) move where the mass comes to rest: rest + m g / k, the
// new ones; a spring cannot be turned off, nor given a negative length.
TEST(JointSprings, ANewRestLengthAndStiffnessMoveWhereTheMassRests) {
  const double mass = 2.0;
  for (const IntegratorKind integrator : kIntegrators) {
    for (const double dt : {1e-3, 5e-4}) {
      SCOPED_TRACE(::testing::Message() << "integrator " << static_cast<int>(integrator) << ", dt " << dt);
      World world(jointWorldSettings(integrator, dt));
      const BodyId bob = addBody(world, "bob", SphereShape{0.05}, mass, Vec3(0, 0, -1));
      const JointId joint = addJoint(world, spring(bob, Vec3::Zero(), Vec3(0, 0, -1), 1.0, 200.0, 10.0));
      const int steps = static_cast<int>(std::lround(12.0 / dt));
      for (int i = 0; i < steps; ++i) world.step();
      EXPECT_NEAR(world.jointState(joint).position, 1.0 + mass * kGravity / 200.0, 1e-9);
      JointDrive drive = world.jointDefinition(joint).drive;
      drive.target = 1.5;
      drive.stiffness = 400.0;
      drive.damping = 20.0;  // ζ = 0.25 again
      ASSERT_TRUE(world.setJointDrive(joint, drive).ok());
      EXPECT_EQ(world.jointDefinition(joint).length, 1.5);
      for (int i = 0; i < steps; ++i) world.step();
      EXPECT_NEAR(world.jointState(joint).position, 1.5 + mass * kGravity / 400.0, 1e-9);
      EXPECT_NEAR(world.jointState(joint).axisEffort, -mass * kGravity, 1e-6);
    }
  }
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId bob = addBody(world, "bob", SphereShape{0.05}, 1.0, Vec3(0, 0, -1));
  const JointId joint = addJoint(world, spring(bob, Vec3::Zero(), Vec3(0, 0, -1), 1.0, 10.0, 1.0));
  JointDrive off;
  EXPECT_EQ(world.setJointDrive(joint, off).error().message,
            "joint 'spring': a spring cannot be turned off (its drive is the spring)");
  JointDrive negative = world.jointDefinition(joint).drive;
  negative.target = -0.25;
  EXPECT_EQ(world.setJointDrive(joint, negative).error().message,
            "joint 'spring': the spring's rest length must not be negative (got -0.250000)");
  EXPECT_EQ(world.jointDefinition(joint).drive.target, 1.0) << "a refused drive changes nothing";
}

TEST(JointSprings, ASpringsRestLengthMustNotBeNegative) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId bob = addBody(world, "bob", SphereShape{0.05}, 1.0, Vec3(0, 0, -1));
  const Expected<JointId> made = world.createJoint(spring(bob, Vec3::Zero(), Vec3(0, 0, -1), -0.5, 10.0, 0.0));
  ASSERT_FALSE(made.ok());
  EXPECT_EQ(made.error().message, "joint 'spring': the spring's rest length must not be negative (got -0.500000)");
}

}  // namespace
}  // namespace rbsim
