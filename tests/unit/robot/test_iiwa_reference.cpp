// The KUKA iiwa of bench/robots (its URDF as published: seven links with
// unequal principal moments, joint damping 0.5 N·m·s/rad), base fixed,
// released from rest at a bent pose with nothing driving it and its stops
// taken off: every link's centre of mass over 0.5 s against the arm's
// equations of motion in joint coordinates (unit/joint/serial_chain_
// reference.h, RK4 at 1e-5 s), at dt = 1, 0.5 and 0.25 ms, with its joint
// damping and without. The joint step is second order: the error falls by
// four with each halving of dt. (With two implicit halves of joint damping
// it was 1.0e-4 m at 1 ms, halving with dt; now 1.0e-5 m.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rbsim/physics/world.h"
#include "robot/urdf_robot.h"
#include "support/test_data_dir.h"
#include "unit/joint/serial_chain_reference.h"

namespace rbsim {
namespace {

using testing::ChainLink;
using testing::SerialChainReference;

struct Iiwa {
  WorldDef def;
  std::vector<ChainLink> chain;
  std::vector<std::string> links;  // the moving bodies, base outwards
};

Iiwa loadIiwa(double dt, bool damping) {
  RobotPlacement placement;
  placement.name = "iiwa";
  placement.fixedBase = true;
  const double pose[7] = {0.4, 0.7, -0.5, -1.3, 0.6, 0.9, -0.3};  // rad: bent in 3-D, no link along gravity
  for (int k = 0; k < 7; ++k) placement.jointPositions["lbr_iiwa_joint_" + std::to_string(k + 1)] = pose[k];
  RobotFiles files;
  files.sourceName = "model.urdf";
  const Expected<RobotModel> robot = loadRobot(
      std::string(rbsim::test_support::kTestDataDir) + "/../../bench/robots/data/kuka_iiwa/model.urdf", placement, files);
  Iiwa iiwa;
  EXPECT_TRUE(robot.ok()) << robot.error().message;
  if (!robot.ok()) return iiwa;
  iiwa.def.settings.dt = dt;
  iiwa.def.settings.gravity = Vec3(0, 0, -9.81);
  iiwa.def.settings.contact.sleeping = false;
  iiwa.def.bodies = robot->bodies;
  for (BodyDef& body : iiwa.def.bodies) body.collides = false;  // the links' meshes may touch: joints alone here
  iiwa.def.joints = robot->joints;
  std::string parent;
  for (NamedJointDef& joint : iiwa.def.joints) {
    joint.def.limit.enabled = false;
    if (!damping) joint.def.damping = 0.0;
    // A serial chain, base outwards.
    if (!parent.empty()) EXPECT_EQ(joint.bodyA, parent);
    parent = joint.bodyB;
    const auto child = std::find_if(iiwa.def.bodies.begin(), iiwa.def.bodies.end(),
                                    [&](const BodyDef& b) { return b.name == joint.bodyB; });
    EXPECT_NE(child, iiwa.def.bodies.end());
    if (child == iiwa.def.bodies.end()) continue;
    EXPECT_TRUE(child->inertia.has_value()) << "the URDF gives every moving link's inertia";
    iiwa.chain.push_back(testing::chainLinkOf(*child, joint.def));
    iiwa.links.push_back(joint.bodyB);
  }
  EXPECT_EQ(iiwa.chain.size(), 7u);
  return iiwa;
}

// The reference's centres of mass at `samples` equal times over `seconds`.
std::vector<std::vector<Vec3>> referenceCentres(const Iiwa& iiwa, double seconds, int samples) {
  return SerialChainReference(iiwa.chain, iiwa.def.settings.gravity).centresReleasedFromRest(seconds, samples);
}

// The largest distance of a link's centre of mass from the reference's at
// its samples over `seconds`, and (in jointError) the largest joint error seen.
double worstError(const Iiwa& iiwa, const std::vector<std::vector<Vec3>>& reference, double seconds,
                  double& jointError) {
  Expected<World> made = World::fromDef(iiwa.def);
  EXPECT_TRUE(made.ok()) << made.error().message;
  if (!made.ok()) return INFINITY;
  World& world = *made;
  const auto samples = static_cast<int>(reference.size());
  const long perSample = std::lround(seconds / samples / world.settings().dt);
  double worst = 0.0;
  jointError = 0.0;
  for (int s = 0; s < samples; ++s) {
    for (long k = 0; k < perSample; ++k) world.step();
    for (std::size_t i = 0; i < iiwa.links.size(); ++i)
      worst = std::max(worst, (world.body(world.findBody(iiwa.links[i])).position() - reference[static_cast<std::size_t>(s)][i]).norm());
    for (int j = 0; j < world.jointCount(); ++j) jointError = std::max(jointError, world.jointStateAt(j).error);
  }
  return worst;
}

TEST(IiwaReference, TheIiwaFollowsItsEquationsOfMotionAtSecondOrder) {
  const double seconds = 0.5;
  for (const bool damping : {true, false}) {
    SCOPED_TRACE(damping ? "with its joint damping" : "without joint damping");
    const std::vector<std::vector<Vec3>> reference = referenceCentres(loadIiwa(1e-3, damping), seconds, 10);
    double errors[3];
    for (int k = 0; k < 3; ++k) {
      double jointError = 0.0;
      errors[k] = worstError(loadIiwa(1e-3 / (1 << k), damping), reference, seconds, jointError);
      EXPECT_LT(jointError, 1e-9);
    }
    const double first = std::log2(errors[0] / errors[1]), second = std::log2(errors[1] / errors[2]);
    std::printf("iiwa %s vs its equations of motion, 0.5 s: %.3g m (1 ms), %.3g (0.5 ms), %.3g (0.25 ms); order %.2f, %.2f\n",
                damping ? "with damping" : "undamped", errors[0], errors[1], errors[2], first, second);
    // Undamped it swings faster, and RATTLE's own second-order error is
    // larger (measured 4.15e-5 m at 1 ms; 4.2e-5 m with the free rotation
    // integrated exactly, so not the rotation's).
    EXPECT_LT(errors[0], damping ? 2e-5 : 5e-5) << "m at dt = 1 ms";
    EXPECT_GE(first, 1.9) << "from 1 to 0.5 ms";
    EXPECT_GE(second, 1.9) << "from 0.5 to 0.25 ms";
  }
}

}  // namespace
}  // namespace rbsim
