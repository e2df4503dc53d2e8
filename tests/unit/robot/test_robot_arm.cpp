// The two-link arm of tests/data/urdf/two_link_arm.urdf, stepped: held at
// a pose by position drives, the drives' efforts are the gravity torques
// of the closed form; with the drives off it falls as a double pendulum and
// keeps its energy. Its joints' own damping, friction and stops are taken
// off, and nothing collides, so that the closed forms hold exactly.
//
// The arm swings in the x–z plane about y: a joint angle q turns a link's x
// axis to (cos q, 0, −sin q). Upper link: m₁ = 2 kg, centre of mass
// c₁ = 0.25 m out, length l₁ = 0.5 m; fore link: m₂ = 1 kg, c₂ = 0.25 m.
// Gravity's torque about y of a mass m at offset a from a joint is m g a_x,
// so holding the arm still takes, on B about each axis,
//   τ_shoulder = −g (m₁ c₁ cos q₁ + m₂ (l₁ cos q₁ + c₂ cos(q₁ + q₂))),
//   τ_elbow    = −g m₂ c₂ cos(q₁ + q₂).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <string>

#include "rbsim/physics/joint_space_dynamics.h"
#include "rbsim/physics/world.h"
#include "robot/urdf_robot.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

constexpr double kGravity = 9.81;
constexpr double kMassUpper = 2.0, kMassFore = 1.0;
constexpr double kCentreUpper = 0.25, kLengthUpper = 0.5, kCentreFore = 0.25;

World loadArm(double dt, double shoulder, double elbow, bool drives) {
  RobotPlacement placement;
  placement.name = "arm";
  placement.fixedBase = true;
  placement.jointPositions = {{"shoulder", shoulder}, {"elbow", elbow}};
  RobotFiles files;
  files.sourceName = "two_link_arm.urdf";
  Expected<RobotModel> robot =
      loadRobot(std::string(rbsim::test_support::kTestDataDir) + "/urdf/two_link_arm.urdf", placement, files);
  EXPECT_TRUE(robot.ok()) << robot.error().message;
  WorldDef def;
  def.settings.dt = dt;
  def.settings.gravity = Vec3(0, 0, -kGravity);
  def.settings.contact.sleeping = false;
  if (!robot.ok()) return World(def.settings);
  def.bodies = robot->bodies;
  for (BodyDef& body : def.bodies) body.collides = false;
  def.joints = robot->joints;
  for (NamedJointDef& joint : def.joints) {
    JointDef& j = joint.def;
    j.damping = 0.0;
    j.friction = 0.0;
    j.limit.enabled = false;
    j.actuatorLimits = {};
    // Stiff PD servos on the pose it starts in (well damped for both links).
    if (drives) j.drive = {true, j.position, 2000.0, 100.0, 0.0, 0.0, std::numeric_limits<double>::infinity()};
  }
  Expected<World> world = World::fromDef(def);
  EXPECT_TRUE(world.ok()) << world.error().message;
  return world.ok() ? std::move(*world) : World(def.settings);
}

double energy(const World& world) {
  double sum = 0.0;
  for (BodyView body : world.bodies()) {
    if (body.isStatic()) continue;
    sum += body.kineticEnergy() + body.mass() * kGravity * body.position().z();
  }
  return sum;
}

TEST(RobotArm, PositionDrivesHoldThePoseWithTheGravityTorques) {
  for (const double dt : {1e-3, 5e-4}) {
    for (const auto& [q1, q2] : {std::pair{0.3, 0.5}, std::pair{-0.7, 1.2}, std::pair{1.0, -2.0}}) {
      SCOPED_TRACE(::testing::Message() << "dt " << dt << ", pose " << q1 << ", " << q2);
      World world = loadArm(dt, q1, q2, true);
      const JointId shoulder = world.findJoint("arm/shoulder");
      const JointId elbow = world.findJoint("arm/elbow");
      ASSERT_FALSE(shoulder.isNull());
      ASSERT_FALSE(elbow.isNull());
      for (int k = 0; k < static_cast<int>(std::lround(4.0 / dt)); ++k) world.step();
      const JointState s = world.jointState(shoulder);
      const JointState e = world.jointState(elbow);
      EXPECT_LT(std::abs(s.rate) + std::abs(e.rate), 1e-10) << "settled";
      // The springs hold the weight a little off the pose (the drive's
      // effort is −k (q − target)): the closed form is taken where the arm is.
      const double a1 = s.position, a12 = s.position + e.position;
      const double elbowTorque = -kGravity * kMassFore * kCentreFore * std::cos(a12);
      const double shoulderTorque =
          -kGravity * (kMassUpper * kCentreUpper * std::cos(a1) +
                       kMassFore * (kLengthUpper * std::cos(a1) + kCentreFore * std::cos(a12)));
      // To what the servos' last motion leaves in their dampers (c w, with
      // w below 1e-10 rad/s).
      EXPECT_NEAR(s.axisEffort, shoulderTorque, 1e-8);
      EXPECT_NEAR(e.axisEffort, elbowTorque, 1e-8);
      EXPECT_NEAR(s.position, q1 - shoulderTorque / 2000.0, 1e-9) << "the spring's sag";
      EXPECT_NEAR(e.position, q2 - elbowTorque / 2000.0, 1e-9);
      EXPECT_LT(std::max(s.error, e.error), 1e-11);
    }
  }
}

// The scale of the energies in play: lifting both links' centres through
// the arm's whole reach.
constexpr double kEnergyScale =
    2.0 * kGravity * (kMassUpper * kCentreUpper + kMassFore * (kLengthUpper + kCentreFore));

TEST(RobotArm, WithoutDrivesItFallsAsADoublePendulumAndKeepsItsEnergy) {
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    World world = loadArm(dt, 0.3, 0.5, false);
    const double start = energy(world);
    double worst = 0.0, lowestElbow = 0.0;
    const BodyId fore = world.findBody("arm/fore");
    for (int k = 0; k < static_cast<int>(std::lround(5.0 / dt)); ++k) {
      world.step();
      worst = std::max(worst, std::abs(energy(world) - start));
      lowestElbow = std::min(lowestElbow, world.body(fore).position().z());
    }
    EXPECT_LT(worst, 1e-3 * kEnergyScale) << "energy drift, J (scale " << kEnergyScale << " J)";
    EXPECT_LT(lowestElbow, -0.3) << "it fell: the elbow swung down below the shoulder";
    const double error = std::max(world.jointState(world.findJoint("arm/shoulder")).error,
                                  world.jointState(world.findJoint("arm/elbow")).error);
    EXPECT_LT(error, 1e-10) << "the joints held";
  }
}

// Gravity compensation from the model the world simulates: the seven-joint
// arm of config/robots/arm7.urdf, bent, passive (no drives, damping,
// friction or limits), with its gravity torques g(q) from
// JointSpaceDynamics applied as the joints' efforts every step, stays
// where it is: no joint drifts 1e-6 rad in 10 s.
TEST(RobotArm, ItsGravityTorquesHoldTheSevenJointArmStill) {
  RobotPlacement placement;
  placement.name = "arm";
  placement.fixedBase = true;
  placement.jointPositions = {{"joint2", 0.6}, {"joint3", 0.4}, {"joint4", -1.2}, {"joint6", 0.8}};
  RobotFiles files;
  files.sourceName = "arm7.urdf";
  Expected<RobotModel> robot =
      loadRobot(std::string(rbsim::test_support::kTestDataDir) + "/../../config/robots/arm7.urdf", placement, files);
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  WorldDef def;
  def.settings.dt = 1e-3;
  def.settings.gravity = Vec3(0, 0, -kGravity);
  def.settings.contact.sleeping = false;
  def.bodies = robot->bodies;
  for (BodyDef& body : def.bodies) body.collides = false;
  def.joints = robot->joints;
  for (NamedJointDef& joint : def.joints) {
    joint.def.damping = 0.0;
    joint.def.friction = 0.0;
    joint.def.limit.enabled = false;
    joint.def.actuatorLimits = {};
  }
  Expected<World> world = World::fromDef(def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  const Expected<JointSpaceDynamics> start = JointSpaceDynamics::ofRobot(*world, "arm/");
  ASSERT_TRUE(start.ok()) << start.error().message;
  ASSERT_EQ(start->dofCount(), 7);
  const Eigen::VectorXd q0 = start->positions();
  EXPECT_GT(start->gravityTorques().cwiseAbs().maxCoeff(), 10.0) << "N·m: gravity has work to do";
  double drift = 0.0;
  for (int step = 0; step < 10000; ++step) {
    const Expected<JointSpaceDynamics> now = JointSpaceDynamics::ofRobot(*world, "arm/");
    ASSERT_TRUE(now.ok());
    const Eigen::VectorXd tau = now->gravityTorques();
    for (int j = 0; j < 7; ++j)
      ASSERT_TRUE(world->setJointEffort(world->findJoint(now->jointNames()[static_cast<std::size_t>(j)]), tau[j]).ok());
    world->step();
    drift = std::max(drift, (now->positions() - q0).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(drift, 1e-6) << "rad";
}

// A drive's gravity compensation (JointDrive::gravityCompensation): the
// same arm, passive but for drives with no gains that only compensate
// gravity, stays within 1e-6 rad for 10 s; servos of modest stiffness sag
// under gravity without it (more than 0.02 rad) and hold their targets to
// 1e-6 rad with it.
World bentArmWithDrives(double stiffness, double damping, bool compensate) {
  RobotPlacement placement;
  placement.name = "arm";
  placement.fixedBase = true;
  placement.jointPositions = {{"joint2", 0.6}, {"joint3", 0.4}, {"joint4", -1.2}, {"joint6", 0.8}};
  RobotFiles files;
  files.sourceName = "arm7.urdf";
  Expected<RobotModel> robot =
      loadRobot(std::string(rbsim::test_support::kTestDataDir) + "/../../config/robots/arm7.urdf", placement, files);
  EXPECT_TRUE(robot.ok()) << robot.error().message;
  WorldDef def;
  def.settings.dt = 1e-3;
  def.settings.gravity = Vec3(0, 0, -kGravity);
  def.settings.contact.sleeping = false;
  if (!robot.ok()) return World(def.settings);
  def.bodies = robot->bodies;
  for (BodyDef& body : def.bodies) body.collides = false;
  def.joints = robot->joints;
  for (NamedJointDef& joint : def.joints) {
    JointDef& j = joint.def;
    j.damping = 0.0;
    j.friction = 0.0;
    j.limit.enabled = false;
    j.actuatorLimits = {};
    if (j.type != JointType::Revolute) continue;
    j.drive.enabled = true;
    j.drive.target = j.position;
    j.drive.stiffness = stiffness;
    j.drive.damping = damping;
    j.drive.gravityCompensation = compensate;
  }
  Expected<World> world = World::fromDef(def);
  EXPECT_TRUE(world.ok()) << world.error().message;
  return world.ok() ? std::move(*world) : World(def.settings);
}

double worstDrift(World& world, int steps) {
  const auto start = JointSpaceDynamics::ofRobot(world, "arm/");
  EXPECT_TRUE(start.ok());
  double drift = 0.0;
  for (int step = 0; step < steps; ++step) {
    world.step();
    const auto now = JointSpaceDynamics::ofRobot(world, "arm/");
    drift = std::max(drift, (now->positions() - start->positions()).cwiseAbs().maxCoeff());
  }
  return drift;
}

TEST(RobotArm, DrivesWithGravityCompensationHoldTheArmWhereItIs) {
  World passive = bentArmWithDrives(0.0, 0.0, true);
  EXPECT_LT(worstDrift(passive, 10000), 1e-6) << "rad in 10 s, no gains: the compensation alone";
  for (int j = 0; j < passive.jointCount(); ++j) {
    const JointState state = passive.jointStateAt(j);
    if (state.type == JointType::Revolute && state.name == "arm/joint2")
      EXPECT_GT(std::abs(state.axisEffort), 10.0) << "N·m: the shoulder carries the arm";
  }
  World sagging = bentArmWithDrives(300.0, 60.0, false);
  const double sag = worstDrift(sagging, 2000);
  EXPECT_GT(sag, 0.02) << "rad: a soft servo sags without it";
  World held = bentArmWithDrives(300.0, 60.0, true);
  EXPECT_LT(worstDrift(held, 2000), 1e-6) << "rad; without it " << sag;
}

}  // namespace
}  // namespace rbsim
