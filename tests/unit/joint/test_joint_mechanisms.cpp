// Mechanisms against what must hold exactly: a weld moves as the compound
// body of its two parts; a slider follows the closed form of constant
// acceleration; long chains with a tip 100 times heavier than a link hold
// every joint; a four-bar linkage (redundant hinges) closes its loop and
// keeps its energy; a chain dropped on the floor comes to rest in one piece.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::hinge;
using testing::jointWorldSettings;

constexpr double kPi = std::numbers::pi;

double largestJointError(const World& world) {
  double worst = 0.0;
  for (int j = 0; j < world.jointCount(); ++j) worst = std::max(worst, world.jointStateAt(j).error);
  return worst;
}

// The angular momentum of the dynamic bodies about their common centre of mass.
Vec3 angularMomentumAboutCentre(const World& world) {
  double mass = 0.0;
  Vec3 centre = Vec3::Zero();
  for (BodyView b : world.bodies()) {
    mass += b.mass();
    centre += b.mass() * b.position();
  }
  centre /= mass;
  Vec3 total = Vec3::Zero();
  for (BodyView b : world.bodies()) total += b.angularMomentum() + (b.position() - centre).cross(b.linearMomentum());
  return total;
}

const BoxShape kHalfBar{Vec3(0.1, 0.05, 0.05)};  // 0.2 × 0.1 × 0.1 m, 2 kg at water's density

TEST(JointMechanisms, AWeldMovesAsOneRigidBody) {
  // Thrown and spinning about a principal axis of the whole: a rigid body
  // turns uniformly about its centre of mass, which flies the parabola. The
  // welded pair's centre flies it exactly (the joint step's leapfrog is
  // exact for a constant force); its turn is right to second order, as the
  // compound body's is with its integrator: a phase error below
  // (hω)² ωt per the scheme's order, falling four times per halving of h.
  const Vec3 velocity(1.0, 0.0, 2.0), spin(0.0, 0.0, 3.0);
  double phaseError[2];
  for (int d = 0; d < 2; ++d) {
    const double dt = d == 0 ? 1e-3 : 5e-4;
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    World welded(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const BodyId left = addBody(welded, "left", kHalfBar, 2.0, Vec3(-0.1, 0, 0));
    const BodyId right = addBody(welded, "right", kHalfBar, 2.0, Vec3(0.1, 0, 0));
    JointDef weld;
    weld.name = "weld";
    weld.type = JointType::Fixed;
    weld.bodyA = left;
    weld.bodyB = right;
    addJoint(welded, weld);
    for (const BodyId id : {left, right}) {
      const Vec3 arm = welded.body(id).position();
      ASSERT_TRUE(welded.setBodyVelocities(id, velocity + spin.cross(arm), spin).ok());
    }
    const int steps = static_cast<int>(std::lround(1.0 / dt));
    for (int k = 0; k < steps; ++k) welded.step();
    const double t = welded.time();
    const Vec3 centre = 0.5 * (welded.body(left).position() + welded.body(right).position());
    EXPECT_LT((centre - (velocity * t + 0.5 * t * t * welded.settings().gravity)).norm(), 1e-11);
    const Mat3 turn = Quaternion::fromAxisAngle(Vec3::UnitZ(), spin.z() * t).toRotationMatrix();
    const Vec3 arm = turn * Vec3(0.1, 0, 0);
    phaseError[d] = (welded.body(right).position() - (centre + arm)).norm() / 0.1;
    const double bound = std::pow(dt * spin.norm(), 2) * spin.norm() * t;
    std::printf("weld, dt %g: phase error %.2e rad (order bound %.1e)\n", dt, phaseError[d], bound);
    EXPECT_LT(phaseError[d], bound);
    EXPECT_LT((welded.body(left).position() - (centre - arm)).norm(), 0.1 * bound);
    EXPECT_LT((welded.body(left).angularVelocity() - spin).norm(), 1e-9) << "it turns at a steady rate";
    EXPECT_LT((welded.body(right).angularVelocity() - spin).norm(), 1e-9);
    EXPECT_LT(largestJointError(welded), 1e-11);
  }
  EXPECT_LT(phaseError[1], 0.3 * phaseError[0]) << "second order";
}

TEST(JointMechanisms, ATumblingWeldConservesMomentaExactly) {
  // Spinning about no principal axis (torque free but for gravity, which
  // acts at the centre of mass): the joint's impulses are internal, so the
  // total momentum follows M g t and the angular momentum about the centre
  // of mass stays, to rounding.
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    const BodyId a = addBody(world, "a", kHalfBar, 2.0, Vec3(-0.1, 0, 0));
    const BodyId b = addBody(world, "b", BoxShape{Vec3(0.1, 0.15, 0.05)}, 3.0, Vec3(0.1, 0.1, 0));
    JointDef weld;
    weld.name = "weld";
    weld.type = JointType::Fixed;
    weld.bodyA = a;
    weld.bodyB = b;
    weld.anchor = Vec3(0.0, 0.02, 0.0);
    addJoint(world, weld);
    const Vec3 spin(2.0, -1.0, 4.0);
    for (const BodyId id : {a, b})
      ASSERT_TRUE(world.setBodyVelocities(id, Vec3(0.5, 0, 1) + spin.cross(world.body(id).position()), spin).ok());
    const Vec3 startMomentum = world.totalLinearMomentum();
    const Vec3 startAngular = angularMomentumAboutCentre(world);
    const int steps = static_cast<int>(std::lround(3.0 / dt));
    double worstJoint = 0.0;
    for (int k = 0; k < steps; ++k) {
      world.step();
      worstJoint = std::max(worstJoint, largestJointError(world));
    }
    const Vec3 expectedMomentum = startMomentum + 5.0 * world.time() * world.settings().gravity;
    EXPECT_LT((world.totalLinearMomentum() - expectedMomentum).norm(), 1e-11 * expectedMomentum.norm());
    EXPECT_LT((angularMomentumAboutCentre(world) - startAngular).norm(), 1e-9 * startAngular.norm());
    EXPECT_LT(worstJoint, 1e-11);
  }
}

TEST(JointMechanisms, ASliderFollowsTheClosedFormOfConstantAcceleration) {
  // A box on a slider inclined 30° below the horizontal, spun at the start:
  // the slider takes the spin away at once and then s = ½ g sin30° t².
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    World world(jointWorldSettings(IntegratorKind::Rk4, dt));
    const Vec3 axis(std::cos(kPi / 6), 0.0, -std::sin(kPi / 6));
    const BodyId box = addBody(world, "box", kHalfBar, 2.0, Vec3(0, 0, 1), Quaternion::fromAxisAngle(Vec3::UnitZ(), 0.3));
    JointDef slider;
    slider.name = "slider";
    slider.type = JointType::Prismatic;
    slider.bodyB = box;
    slider.anchor = Vec3(0, 0, 1);
    slider.axis = axis;
    const JointId joint = addJoint(world, slider);
    const Quaternion start = world.body(box).orientation();
    const double t = 2.0;
    const int steps = static_cast<int>(std::lround(t / dt));
    for (int k = 0; k < steps; ++k) world.step();
    const JointState state = world.jointState(joint);
    const double acceleration = testing::kGravity * std::sin(kPi / 6);
    EXPECT_NEAR(state.position, 0.5 * acceleration * t * t, 1e-9);
    EXPECT_NEAR(state.rate, acceleration * t, 1e-9);
    EXPECT_LT((world.body(box).position() - (Vec3(0, 0, 1) + state.position * axis)).norm(), 1e-11);
    const Quaternion q = world.body(box).orientation();
    EXPECT_NEAR(std::abs(q.w * start.w + q.x * start.x + q.y * start.y + q.z * start.z), 1.0, 1e-12);
    EXPECT_LT(state.error, 1e-11);
  }
}

// A chain of `links` capsules on ball joints from the world at the origin,
// along `direction`, the last `tipRatio` times heavier than a link (0.1 kg).
World makeChain(int links, double tipRatio, double dt, const Vec3& direction) {
  WorldSettings settings = jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt);
  // The links would strike each other as a chain folds (inelastically):
  // here only the joints act, so that the energy is conserved.
  settings.contact.enabled = false;
  World world(settings);
  const double length = 0.1, linkMass = 0.1;
  // The capsule's axis (its z) along the chain.
  const Vec3 turnAxis = Vec3::UnitZ().cross(direction);
  const double angle = std::acos(std::clamp(Vec3::UnitZ().dot(direction), -1.0, 1.0));
  const Quaternion along =
      Quaternion::fromAxisAngle(turnAxis.norm() > 1e-12 ? Vec3(turnAxis.normalized()) : Vec3::UnitX(), angle);
  BodyId previous;
  for (int k = 0; k < links; ++k) {
    const double mass = k + 1 == links ? tipRatio * linkMass : linkMass;
    const BodyId link = addBody(world, "link" + std::to_string(k), CapsuleShape{0.01, 0.5 * length - 0.01}, mass,
                                (k + 0.5) * length * direction, along);
    JointDef ball;
    ball.name = "joint" + std::to_string(k);
    ball.type = JointType::Spherical;
    ball.bodyA = previous;
    ball.bodyB = link;
    ball.anchor = k * length * direction;
    addJoint(world, ball);
    previous = link;
  }
  return world;
}

// How far the chain's far end is from where its links put it: each link's
// centre is halfway between its two anchors, so the anchors chain up from
// the origin; the last one must be the tip capsule's far end.
double chainStretch(const World& world) {
  Vec3 end = Vec3::Zero();
  for (BodyView b : world.bodies()) end = b.position() + (b.position() - end);
  const BodyView tip = world.bodyAt(world.bodyCount() - 1);
  return std::min((tip.bodyToWorld(Vec3(0, 0, 0.05)) - end).norm(), (tip.bodyToWorld(Vec3(0, 0, -0.05)) - end).norm());
}

double totalMass(const World& world) {
  double mass = 0.0;
  for (BodyView b : world.bodies()) mass += b.mass();
  return mass;
}

TEST(JointMechanisms, ChainsWithATipAHundredTimesHeavierHangStill) {
  for (const int links : {20, 50}) {
    SCOPED_TRACE(::testing::Message() << links << " links");
    World world = makeChain(links, 100.0, 1e-3, -Vec3::UnitZ());
    // A small sideways push on the tip: the chain swings a little, and the
    // swing must neither grow nor die (no dissipation, no energy pumped in).
    const BodyId tip = world.idOf(links - 1);
    ASSERT_TRUE(world.setBodyVelocities(tip, Vec3(0.01, 0, 0), Vec3::Zero()).ok());
    // The first step keeps of that velocity what the joints allow (the
    // tip cannot leave the link above it); the energy counts from there.
    world.step();
    const double start = testing::mechanicalEnergy(world);
    const double push = world.totalKineticEnergy();  // J
    double worstJoint = 0.0, worstEnergy = 0.0, worstStretch = 0.0;
    double firstSwing = 0.0, lastSwing = 0.0;  // largest |x| of the tip in the first and last 2 s
    for (int k = 0; k < 10000; ++k) {
      world.step();
      worstJoint = std::max(worstJoint, largestJointError(world));
      worstStretch = std::max(worstStretch, chainStretch(world));
      worstEnergy = std::max(worstEnergy, std::abs(testing::mechanicalEnergy(world) - start));
      const double x = std::abs(world.body(tip).position().x());
      if (k < 2000) firstSwing = std::max(firstSwing, x);
      if (k >= 8000) lastSwing = std::max(lastSwing, x);
    }
    std::printf("hanging chain of %d, tip 100x, pushed: joint error %.1e m, stretch %.1e m, energy error %.1e of the push, "
                "swing %.4f then %.4f m\n", links, worstJoint, worstStretch, worstEnergy / push, firstSwing, lastSwing);
    EXPECT_LT(worstJoint, 1e-9);
    EXPECT_LT(worstStretch, 1e-6) << "the whole chain within a micrometre (the issue asks for 1 mm)";
    EXPECT_LT(worstEnergy, 1e-3 * push) << "the swing keeps its energy";
    EXPECT_LT(lastSwing, 1.05 * firstSwing) << "no oscillation grows";
    EXPECT_GT(lastSwing, 0.5 * firstSwing) << "nor dies out";
  }
}

TEST(JointMechanisms, AChainWhippedDownFromTheHorizontalHoldsEveryJoint) {
  // Released horizontal, the heavy tip drags the chain into a whip whose
  // light links turn at hundreds of rad/s: the joint step sub-steps where a
  // step is too long for its projection, and the joints hold.
  for (const int links : {20, 50}) {
    SCOPED_TRACE(::testing::Message() << links << " links");
    World world = makeChain(links, 100.0, 1e-3, Vec3::UnitX());
    const double start = testing::mechanicalEnergy(world);
    double worstJoint = 0.0, worstStretch = 0.0, worstEnergy = 0.0;
    for (int k = 0; k < 5000; ++k) {
      world.step();
      worstJoint = std::max(worstJoint, largestJointError(world));
      worstStretch = std::max(worstStretch, chainStretch(world));
      worstEnergy = std::max(worstEnergy, std::abs(testing::mechanicalEnergy(world) - start));
    }
    const double released = totalMass(world) * testing::kGravity * links * 0.1;  // J, the scale of the fall
    std::printf("whipped chain of %d, tip 100x: joint error %.1e m, stretch %.1e m, energy error %.1e\n", links,
                worstJoint, worstStretch, worstEnergy / released);
    EXPECT_LT(worstJoint, 1e-9);
    EXPECT_LT(worstStretch, 1e-6);
    // Not an accuracy bound (the whip's fastest links turn by a tenth of a
    // radian per step): the energy stays bounded, nothing explodes.
    EXPECT_LT(worstEnergy, 0.1 * released);
  }
}

TEST(JointMechanisms, AFourBarLinkageClosesItsLoopAndKeepsItsEnergy) {
  // Ground 0.4 m (two world hinges), crank 0.1 m, coupler 0.4 m, rocker 0.3 m,
  // all hinges along y: a planar loop whose hinges constrain the out-of-plane
  // motions more than once (redundant rows).
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const Vec3 o(0, 0, 0), d(0.4, 0, 0);
  const Vec3 b(0.0, 0, 0.1);  // crank end, straight up
  // The rocker's end c = (x, 0, z) above the ground: |c − b| = 0.4 and |c − d| = 0.3.
  double x = 0.3, z = 0.2;
  for (int it = 0; it < 50; ++it) {  // Newton on the two circle equations
    const double f1 = x * x + (z - 0.1) * (z - 0.1) - 0.16, f2 = (x - 0.4) * (x - 0.4) + z * z - 0.09;
    const double a11 = 2 * x, a12 = 2 * (z - 0.1), a21 = 2 * (x - 0.4), a22 = 2 * z;
    const double det = a11 * a22 - a12 * a21;
    x -= (f1 * a22 - f2 * a12) / det;
    z -= (a11 * f2 - a21 * f1) / det;
  }
  const Vec3 c(x, 0, z);
  const auto bar = [&](const std::string& name, const Vec3& from, const Vec3& to) {
    const Vec3 along = (to - from).normalized();
    const Quaternion turn = Quaternion::fromAxisAngle(Vec3::UnitY(), std::atan2(along.x(), along.z()));
    return addBody(world, name, CapsuleShape{0.01, 0.5 * (to - from).norm()}, 0.5, 0.5 * (from + to), turn);
  };
  const BodyId crank = bar("crank", o, b), coupler = bar("coupler", b, c), rocker = bar("rocker", d, c);
  addJoint(world, hinge("ground_crank", BodyId{}, crank, o, Vec3::UnitY()));
  addJoint(world, hinge("crank_coupler", crank, coupler, b, Vec3::UnitY()));
  addJoint(world, hinge("coupler_rocker", coupler, rocker, c, Vec3::UnitY()));
  addJoint(world, hinge("rocker_ground", BodyId{}, rocker, d, Vec3::UnitY()));
  ASSERT_TRUE(world.setBodyVelocities(crank, Vec3::Zero(), Vec3::Zero()).ok());
  const double start = testing::mechanicalEnergy(world);
  const double startAngle = world.jointStateAt(0).position;
  double worstJoint = 0.0, worstEnergy = 0.0, travel = 0.0;
  for (int k = 0; k < 5000; ++k) {
    world.step();
    worstJoint = std::max(worstJoint, largestJointError(world));
    worstEnergy = std::max(worstEnergy, std::abs(testing::mechanicalEnergy(world) - start));
    travel = std::max(travel, std::abs(world.jointStateAt(0).position - startAngle));
  }
  EXPECT_LT(worstJoint, 1e-9);
  EXPECT_LT(worstEnergy / (1.5 * testing::kGravity * 0.1), 1e-3);
  EXPECT_GT(travel, 0.5) << "the linkage moves (one degree of freedom)";
}

TEST(JointMechanisms, AChainDroppedOnTheFloorComesToRestInOnePiece) {
  WorldSettings settings = jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3);
  settings.contact.sleeping = true;
  World world(settings);
  BodyDef floor;
  floor.name = "floor";
  floor.shape = PlaneShape{};
  floor.isStatic = true;
  ASSERT_TRUE(world.createBody(floor).ok());
  BodyId previous;
  const double length = 0.1;
  for (int k = 0; k < 10; ++k) {
    const BodyId link = addBody(world, "link" + std::to_string(k), CapsuleShape{0.01, 0.04}, 0.1,
                                Vec3((k + 0.5) * length, 0, 0.3 + 0.02 * k), Quaternion::fromAxisAngle(Vec3::UnitY(), kPi / 2));
    if (!previous.isNull()) {
      JointDef ball;
      ball.name = "joint" + std::to_string(k);
      ball.type = JointType::Spherical;
      ball.bodyA = previous;
      ball.bodyB = link;
      ball.anchor = 0.5 * (world.body(previous).position() + world.body(link).position());
      addJoint(world, ball);
    }
    previous = link;
  }
  double worstJoint = 0.0;
  for (int k = 0; k < 4000; ++k) {
    world.step();
    worstJoint = std::max(worstJoint, largestJointError(world));
  }
  EXPECT_LT(worstJoint, 1e-6) << "contacts push the links; the joints hold";
  EXPECT_LT(world.totalKineticEnergy(), 1e-6);
  for (BodyView b : world.bodies()) {
    if (b.isStatic()) continue;
    EXPECT_GT(b.position().z(), 0.005) << b.name() << " rests on the floor, not in it";
    EXPECT_LT(b.position().z(), 0.02) << b.name();
  }
  EXPECT_EQ(world.sleepingBodyCount(), 10) << "the chain's island falls asleep as one";
}

}  // namespace
}  // namespace rbsim
