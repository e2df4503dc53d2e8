// Rope (a distance joint with limits) and cone limits against closed forms.
//  - A ball on a slack rope falls freely, exactly ½ g t², until the rope is
//    taut, and then hangs at its length with the reaction m g.
//  - A ball on a slack rope off to the side: the taut rope takes the radial
//    velocity away (an inelastic catch) and leaves the tangential one,
//    |v| sin of the angle between the fall and the rope; then it swings as
//    a pendulum, keeping its energy.
//  - A ball joint's cone stops a swinging rod at the cone's angle; a rod
//    hung in a tilted cone rests on the cone's rim nearest the vertical.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::jointWorldSettings;
using testing::kGravity;

JointDef rope(BodyId body, const Vec3& anchor, const Vec3& onBody, double length) {
  JointDef def;
  def.name = "rope";
  def.type = JointType::Distance;
  def.bodyB = body;
  def.anchor = anchor;
  def.anchorB = onBody;
  def.limit = {true, 0.0, length};
  return def;
}

TEST(JointRopes, ABallFallsFreelyUntilTheRopeIsTautThenHangs) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const BodyId ball = addBody(world, "ball", SphereShape{0.05}, 1.0, Vec3(0, 0, -0.5));
    const JointId joint = addJoint(world, rope(ball, Vec3::Zero(), Vec3(0, 0, -0.5), 1.0));
    const double taut = std::sqrt(2.0 * 0.5 / kGravity);  // s: 0.5 m of free fall
    double worstFall = 0.0, longest = 0.0;
    for (int k = 0; k < static_cast<int>(std::lround(2.0 / dt)); ++k) {
      world.step();
      const double t = world.time();
      const double z = world.body(ball).position().z();
      if (t < taut - dt) worstFall = std::max(worstFall, std::abs(z - (-0.5 - 0.5 * kGravity * t * t)));
      longest = std::max(longest, -z);
    }
    EXPECT_LT(worstFall, 1e-12) << "slack: free fall";
    EXPECT_LT(longest, 1.0 + 1e-9) << "never longer than the rope";
    const JointState state = world.jointState(joint);
    EXPECT_NEAR(state.position, 1.0, 1e-9);
    EXPECT_EQ(state.atLimit, +1);
    EXPECT_NEAR(world.body(ball).linearVelocity().norm(), 0.0, 1e-9) << "caught inelastically, at rest";
    EXPECT_NEAR(state.force.z(), kGravity, 1e-9) << "the rope holds m g";
    EXPECT_NEAR(state.force.head<2>().norm(), 0.0, 1e-9);
  }
}

TEST(JointRopes, ATautRopeKeepsTheTangentialVelocityAndThenSwings) {
  const double dt = 1e-3;
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
  // At (0.6, 0, 0) on a 1 m rope from the origin: taut at z = −0.8, after a
  // fall of 0.8 m at √(2 g 0.8); the rope then points along (0.6, 0, −0.8),
  // at an angle to the fall whose sine is 0.6.
  const BodyId ball = addBody(world, "ball", SphereShape{0.02}, 1.0, Vec3(0.6, 0, 0));
  const JointId joint = addJoint(world, rope(ball, Vec3::Zero(), Vec3(0.6, 0, 0), 1.0));
  const double tangential = std::sqrt(2.0 * kGravity * 0.8) * 0.6;
  while (world.jointState(joint).atLimit == 0) world.step();
  for (int k = 0; k < 5; ++k) world.step();
  // Caught within a step: the catch is off by the fall of one step, g h
  // against a speed of 4 m/s.
  const Vec3 v = world.body(ball).linearVelocity();
  const Vec3 radial = world.body(ball).position().normalized();
  // The caught speed, and what the swing since the catch added to it.
  const double expected =
      std::sqrt(tangential * tangential + 2.0 * kGravity * (-0.8 - world.body(ball).position().z()));
  EXPECT_NEAR(v.dot(radial), 0.0, 1e-9) << "no velocity along the taut rope";
  EXPECT_NEAR(v.norm(), expected, kGravity * dt * 2.0);
  // Then a pendulum: its energy stays.
  const double energy = testing::mechanicalEnergy(world);
  double worst = 0.0;
  for (int k = 0; k < 1000; ++k) {
    world.step();
    worst = std::max(worst, std::abs(testing::mechanicalEnergy(world) - energy));
    EXPECT_LT(world.jointState(joint).position, 1.0 + 1e-9);
  }
  std::printf("rope catch: |v| %.4f m/s after it (closed form %.4f), swing energy error %.1e J over 1 s\n", v.norm(),
              expected, worst);
  EXPECT_LT(worst, 1e-4 * kGravity * 1.0) << "the swing keeps its energy, to 1e-4 of m g L";
}

// A 1 kg rod 1 m long (a thin box) hanging from a ball joint at its top
// end; the cone's axis and angle as given.
struct ConeRod {
  World world;
  BodyId rod;
  JointId joint;
};

ConeRod makeConeRod(double dt, const Vec3& coneAxis, double coneAngle, const Quaternion& orientation) {
  ConeRod out{World(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt)), {}, {}};
  const Vec3 centre = orientation.toRotationMatrix() * Vec3(0, 0, -0.5);
  out.rod = addBody(out.world, "rod", BoxShape{Vec3(0.01, 0.01, 0.5)}, 1.0, centre, orientation);
  JointDef def;
  def.name = "shoulder";
  def.type = JointType::Spherical;
  def.bodyB = out.rod;
  def.anchor = Vec3::Zero();
  def.axis = coneAxis;
  def.coneAngle = coneAngle;
  out.joint = addJoint(out.world, def);
  return out;
}

TEST(JointCones, AConeStopsASwingingRodAtItsAngle) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    // Hanging along the cone's axis, swung at 3 rad/s: free, it would rise
    // to 0.80 rad (½ I ω² = m g d (1 − cos θ), I = m L² / 3); the cone stops it at 0.5.
    ConeRod cone = makeConeRod(dt, Vec3(0, 0, -1), 0.5, Quaternion::identity());
    ASSERT_TRUE(cone.world.setBodyVelocities(cone.rod, Vec3(0, 1.5, 0), Vec3(3.0, 0, 0)).ok());
    double widest = 0.0, worstAnchor = 0.0;
    bool reached = false;
    for (int k = 0; k < static_cast<int>(std::lround(1.0 / dt)); ++k) {
      cone.world.step();
      const JointState state = cone.world.jointState(cone.joint);
      widest = std::max(widest, state.position);
      worstAnchor = std::max(worstAnchor, (state.anchorA - state.anchorB).norm());
      reached = reached || state.atLimit == +1;
    }
    EXPECT_TRUE(reached);
    EXPECT_LT(widest, 0.5 + 1e-9) << "never past the cone";
    EXPECT_GT(widest, 0.5 - 1e-9) << "and it got there";
    EXPECT_LT(worstAnchor, 1e-9);
  }
}

TEST(JointCones, ARodInATiltedConeRestsOnTheRimNearestTheVertical) {
  // The cone's axis 0.6 rad from the downward vertical towards +x, its
  // angle 0.3: the rod starts along the axis, falls towards the vertical
  // and stops on the rim 0.3 rad from it, in the plane of the tilt.
  const double tilt = 0.6;
  const Vec3 axis(std::sin(tilt), 0, -std::cos(tilt));
  const Quaternion along = Quaternion::fromAxisAngle(Vec3::UnitY(), -tilt);  // (0, 0, −1) turned onto the axis
  ASSERT_NEAR((along.toRotationMatrix() * Vec3(0, 0, -1) - axis).norm(), 0.0, 1e-15);
  ConeRod cone = makeConeRod(1e-3, axis, 0.3, along);
  for (int k = 0; k < 3000; ++k) cone.world.step();
  const JointState state = cone.world.jointState(cone.joint);
  EXPECT_NEAR(state.position, 0.3, 1e-9) << "on the rim";
  const Vec3 down = (cone.world.body(cone.rod).position() - state.anchorA).normalized();
  EXPECT_NEAR(std::acos(-down.z()), tilt - 0.3, 1e-9) << "nearest the vertical";
  EXPECT_NEAR(down.y(), 0.0, 1e-12) << "in the plane of the tilt";
  EXPECT_LT(cone.world.body(cone.rod).angularVelocity().norm(), 1e-9) << "at rest";
}

}  // namespace
}  // namespace rbsim
