// The project's example robots (config/robots) and the example world of the
// arm (config/worlds/robot_arm.yaml).
//
// The arm world: the seven-joint arm of arm7.urdf on a fixed base, read
// through the world file, is the bodies and joints the URDF describes
// (names, masses and inertias of the cylinder closed forms, joint frames,
// limits), and held by position drives it stays on its joints for a second.
// The arm's revolute joints alternate between a roll about the link (z in
// the zero pose) and a pitch about y. The world file bends it with pitches
// only (joint2 0.6, joint4 1.2, joint6 0.8 rad), so the whole arm stays in
// the x–z plane: after pitches adding up to φ a link points along
// d(φ) = (sin φ, 0, cos φ).
//
// The humanoid of humanoid30.urdf: 30 links on 29 revolute joints and a
// floating pelvis; dropped, it falls as one body (every link accelerates
// alike, so the joints carry nothing and stay where they started).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <variant>

#include "config/config_loader.h"
#include "rbsim/physics/world.h"
#include "robot/urdf_robot.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

const std::string kWorldFile =
    std::string(rbsim::test_support::kTestDataDir) + "/../../config/worlds/robot_arm.yaml";

constexpr double kGravity = 9.81;

// The links as arm7.urdf gives them: solid cylinders along z, each from
// the joint that moves it to the next one.
struct Link {
  const char* name;
  double mass;    // kg
  double radius;  // m
  double length;  // m
};
constexpr std::array<Link, 7> kLinks = {{{"link1", 3.8, 0.065, 0.20},
                                         {"link2", 3.6, 0.065, 0.20},
                                         {"link3", 2.8, 0.06, 0.20},
                                         {"link4", 2.6, 0.055, 0.20},
                                         {"link5", 2.0, 0.05, 0.20},
                                         {"link6", 1.5, 0.045, 0.10},
                                         {"link7", 1.0, 0.04, 0.06}}};
constexpr double kBaseHeight = 0.12;  // m: joint1 above the base's frame

// Joint k (0-based) moves link k; even ones roll, odd ones pitch.
struct JointData {
  double limit;   // rad: the range is ±limit
  double effort;  // N·m
  double rate;    // rad/s
  double damping, friction;
  double position;  // rad, as the world file places it
};
constexpr std::array<JointData, 7> kJoints = {{{2.96, 176, 1.71, 0.5, 0.3, 0.0},
                                               {2.09, 176, 1.71, 0.5, 0.3, 0.6},
                                               {2.96, 110, 1.75, 0.3, 0.2, 0.0},
                                               {2.09, 110, 2.27, 0.3, 0.2, 1.2},
                                               {2.96, 110, 2.44, 0.2, 0.1, 0.0},
                                               {2.09, 40, 3.14, 0.1, 0.05, 0.8},
                                               {3.05, 40, 3.14, 0.1, 0.05, 0.0}}};

bool pitches(int joint) {
  return joint % 2 == 1;
}

Vec3 along(double pitch) {
  return {std::sin(pitch), 0.0, std::cos(pitch)};
}

// Where joint k is and its axis, in the world, by the closed form of the
// planar chain.
struct JointFrame {
  Vec3 anchor;
  Vec3 axis;
};
std::array<JointFrame, 7> expectedJointFrames() {
  std::array<JointFrame, 7> frames;
  Vec3 anchor(0.0, 0.0, kBaseHeight);
  double pitch = 0.0;
  for (int k = 0; k < 7; ++k) {
    frames[k] = {anchor, pitches(k) ? Vec3::UnitY() : along(pitch)};
    pitch += kJoints[k].position;  // rolls are at 0: only pitches bend
    anchor += kLinks[k].length * along(pitch);
  }
  return frames;
}

const NamedJointDef* findJoint(const WorldDef& world, const std::string& name) {
  for (const NamedJointDef& joint : world.joints)
    if (joint.def.name == name) return &joint;
  return nullptr;
}

const BodyDef* findBody(const WorldDef& world, const std::string& name) {
  for (const BodyDef& body : world.bodies)
    if (body.name == name) return &body;
  return nullptr;
}

TEST(ExampleRobots, TheArmWorldFileMakesTheArmsBodiesAsTheUrdfDescribesThem) {
  const Expected<WorldDef> world = loadWorldConfig(kWorldFile);
  ASSERT_TRUE(world.ok()) << world.error().message;
  // The ground, two boxes, the base and seven links (tool0 has no mass:
  // merged into link7).
  EXPECT_EQ(world->bodies.size(), 11u);
  for (const char* name : {"ground", "left_box", "right_box"})
    EXPECT_NE(findBody(*world, name), nullptr) << name;
  const BodyDef* base = findBody(*world, "arm/base_link");
  ASSERT_NE(base, nullptr);
  EXPECT_TRUE(base->isStatic) << "fixed_base";
  EXPECT_EQ(findBody(*world, "arm/tool0"), nullptr) << "merged";

  const std::array<JointFrame, 7> frames = expectedJointFrames();
  for (int k = 0; k < 7; ++k) {
    const Link& link = kLinks[k];
    SCOPED_TRACE(link.name);
    const BodyDef* body = findBody(*world, std::string("arm/") + link.name);
    ASSERT_NE(body, nullptr);
    EXPECT_FALSE(body->isStatic);
    ASSERT_TRUE(body->mass && body->inertia && body->centerOfMass);
    EXPECT_EQ(*body->mass, link.mass);
    // A solid cylinder about its centre, to the URDF's rounding (nine
    // significant digits: half a unit in the last is at most 5e-9 of it).
    const double across =
        link.mass * (3 * link.radius * link.radius + link.length * link.length) / 12;
    const double about = link.mass * link.radius * link.radius / 2;
    EXPECT_NEAR((*body->inertia)(0, 0), across, 5e-9 * across);
    EXPECT_NEAR((*body->inertia)(1, 1), across, 5e-9 * across);
    EXPECT_NEAR((*body->inertia)(2, 2), about, 5e-9 * about);
    EXPECT_EQ((*body->inertia)(0, 1), 0.0);
    EXPECT_TRUE(body->centerOfMass->isApprox(Vec3(0, 0, link.length / 2), 1e-15));
    // The link's frame is at the joint that moves it.
    EXPECT_LT((body->position - frames[k].anchor).norm(), 1e-12);
    // It collides as its cylinder, placed from the joint up (a compound of
    // one part, since the part is off the frame's origin).
    const CompoundShape* shape = std::get_if<CompoundShape>(&body->shape);
    ASSERT_NE(shape, nullptr);
    ASSERT_EQ(shape->parts.size(), 1u);
    const CylinderShape* cylinder = std::get_if<CylinderShape>(&shape->parts[0].shape);
    ASSERT_NE(cylinder, nullptr);
    EXPECT_EQ(cylinder->radius, link.radius);
    EXPECT_EQ(cylinder->halfLength, link.length / 2);
    EXPECT_TRUE(shape->parts[0].position.isApprox(Vec3(0, 0, link.length / 2), 1e-15));
  }
}

TEST(ExampleRobots, TheArmWorldFileMakesTheArmsJointsWithTheUrdfsFramesAndLimits) {
  const Expected<WorldDef> world = loadWorldConfig(kWorldFile);
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_EQ(world->joints.size(), 7u) << "the fixed tool0 joint is merged away";
  const std::array<JointFrame, 7> frames = expectedJointFrames();
  for (int k = 0; k < 7; ++k) {
    const std::string name = "arm/joint" + std::to_string(k + 1);
    SCOPED_TRACE(name);
    const NamedJointDef* joint = findJoint(*world, name);
    ASSERT_NE(joint, nullptr);
    EXPECT_EQ(joint->bodyA,
              k == 0 ? std::string("arm/base_link") : std::string("arm/") + kLinks[k - 1].name);
    EXPECT_EQ(joint->bodyB, std::string("arm/") + kLinks[k].name);
    const JointDef& def = joint->def;
    const JointData& data = kJoints[k];
    EXPECT_EQ(def.type, JointType::Revolute);
    EXPECT_LT((def.anchor - frames[k].anchor).norm(), 1e-12);
    EXPECT_LT((def.axis - frames[k].axis).norm(), 1e-12);
    EXPECT_EQ(def.position, data.position);
    EXPECT_TRUE(def.limit.enabled);
    EXPECT_EQ(def.limit.lower, -data.limit);
    EXPECT_EQ(def.limit.upper, data.limit);
    EXPECT_EQ(def.actuatorLimits.effort, data.effort);
    EXPECT_EQ(def.actuatorLimits.rate, data.rate);
    EXPECT_EQ(def.damping, data.damping);
    EXPECT_EQ(def.friction, data.friction);
    // joint_drives: a servo on every joint, holding it where it is placed.
    EXPECT_TRUE(def.drive.enabled);
    EXPECT_EQ(def.drive.target, data.position);
    EXPECT_EQ(def.drive.stiffness, 2000.0);
    EXPECT_EQ(def.drive.damping, 100.0);
  }
}

// Held by the world file's position drives on the pose it starts in
// (joint_drives: stiffness 2000 N·m/rad, damping 100 N·m·s/rad), the arm stays on its
// joints for a second and settles where each drive balances the weight it
// carries: at rest, the drive's effort and gravity's torque about the axis
// of everything beyond the joint add up to what the joint's dry friction
// holds (at most its friction torque).
TEST(ExampleRobots, TheArmHeldByPositionDrivesStaysOnItsJointsAndCarriesItsWeight) {
  const Expected<WorldDef> def = loadWorldConfig(kWorldFile);
  ASSERT_TRUE(def.ok()) << def.error().message;
  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  std::array<JointId, 7> joints;
  std::array<BodyId, 7> links;
  for (int k = 0; k < 7; ++k) {
    joints[k] = world->findJoint("arm/joint" + std::to_string(k + 1));
    links[k] = world->findBody(std::string("arm/") + kLinks[k].name);
    ASSERT_FALSE(joints[k].isNull());
    ASSERT_FALSE(links[k].isNull());
  }
  double worstError = 0.0, worstGap = 0.0;
  const int steps = static_cast<int>(std::lround(1.0 / world->settings().dt));
  for (int step = 0; step < steps; ++step) {
    world->step();
    for (const JointId joint : joints) {
      const JointState state = world->jointState(joint);
      worstError = std::max(worstError, state.error);
      worstGap = std::max(worstGap, (state.anchorA - state.anchorB).norm());
    }
  }
  EXPECT_LT(worstError, 1e-6) << "m or rad";
  EXPECT_LT(worstGap, 1e-6) << "m";
  for (const SolvedManifold& contact : world->contacts()) {
    for (const int body : {contact.bodyA, contact.bodyB})
      EXPECT_EQ(world->bodyAt(body).name().rfind("arm/", 0), std::string::npos)
          << "the arm touches nothing: " << world->bodyAt(body).name();
  }
  for (int k = 0; k < 7; ++k) {
    SCOPED_TRACE("joint" + std::to_string(k + 1));
    const JointState state = world->jointState(joints[k]);
    EXPECT_LT(std::abs(state.rate), 1e-6) << "settled";
    double gravityTorque = 0.0;  // N·m about the axis, of the links beyond the joint
    for (int outer = k; outer < 7; ++outer) {
      const BodyView link = world->body(links[outer]);
      gravityTorque += (link.position() - state.anchorA)
                           .cross(Vec3(0, 0, -kGravity * link.mass()))
                           .dot(state.axis);
    }
    EXPECT_LE(std::abs(state.axisEffort + gravityTorque), kJoints[k].friction)
        << "effort " << state.axisEffort << ", gravity " << gravityTorque;
    // And so the arm is where the springs hold it: no further off the pose
    // than the weight and the friction together bend a 2000 N·m/rad spring.
    EXPECT_LE(std::abs(state.position - kJoints[k].position),
              (std::abs(gravityTorque) + kJoints[k].friction) / 2000.0);
  }
}

Expected<RobotModel> loadHumanoid(const Vec3& position) {
  RobotPlacement placement;
  placement.name = "h";
  placement.position = position;
  RobotFiles files;
  files.sourceName = "humanoid30.urdf";
  return loadRobot(std::string(rbsim::test_support::kTestDataDir) + "/../../config/robots/humanoid30.urdf",
                   placement, files);
}

TEST(ExampleRobots, TheHumanoidIsThirtyLinksOnTwentyNineRevoluteJointsWithAFloatingPelvis) {
  const Expected<RobotModel> robot = loadHumanoid(Vec3(0, 0, 2.0));
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  EXPECT_EQ(robot->bodies.size(), 30u);
  EXPECT_EQ(robot->joints.size(), 29u);
  double mass = 0.0;
  for (const BodyDef& body : robot->bodies) {
    EXPECT_FALSE(body.isStatic) << body.name << ": the pelvis floats, the rest moves on joints";
    ASSERT_TRUE(body.mass) << body.name;
    mass += *body.mass;
  }
  EXPECT_NEAR(mass, 68.94, 1e-12) << "kg, the links' masses as written";
  for (const NamedJointDef& joint : robot->joints) {
    EXPECT_EQ(joint.def.type, JointType::Revolute) << joint.def.name;
    EXPECT_TRUE(joint.def.limit.enabled) << joint.def.name;
    EXPECT_LE(joint.def.limit.lower, 0.0)
        << joint.def.name << ": the zero pose is within the limits";
    EXPECT_GE(joint.def.limit.upper, 0.0) << joint.def.name;
    EXPECT_NE(joint.bodyA, "h/world");
  }
  EXPECT_EQ(robot->bodies.front().name, "h/pelvis");
  EXPECT_TRUE(robot->bodies.front().position.isApprox(Vec3(0, 0, 2.0), 1e-15));
}

TEST(ExampleRobots, TheHumanoidsLinksTouchOnlyAcrossTheirJoints) {
  const Expected<RobotModel> robot = loadHumanoid(Vec3(0, 0, 2.0));
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  WorldDef def;
  def.settings.gravity = Vec3::Zero();
  def.bodies = robot->bodies;
  def.joints = robot->joints;
  Expected<World> world = World::fromDef(def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  world->step();
  EXPECT_EQ(world->contactPointCount(), 0)
      << "no two links within the contact margin but across a joint";
}

// Dropped, every link falls alike and the joints carry nothing. Contacts
// are off: speculative contacts reach as far as each body moves in a step,
// so at a few m/s the fingers (11 mm apart) pair up with each other and
// their bodies take the contact solver's step instead of the joint step.
TEST(ExampleRobots, TheHumanoidDroppedFallsAsOneBody) {
  const Expected<RobotModel> robot = loadHumanoid(Vec3(0, 0, 2.0));
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  WorldDef def;
  def.settings.dt = 1e-3;
  def.settings.gravity = Vec3(0, 0, -kGravity);
  def.settings.contact.enabled = false;
  def.bodies = robot->bodies;
  def.joints = robot->joints;
  Expected<World> world = World::fromDef(def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  ASSERT_EQ(world->bodyCount(), 30);
  ASSERT_EQ(world->jointCount(), 29);
  const auto centreOfMass = [&world] {
    Vec3 sum = Vec3::Zero();
    double mass = 0.0;
    for (BodyView body : world->bodies()) {
      sum += body.mass() * body.position();
      mass += body.mass();
    }
    return Vec3(sum / mass);
  };
  const Vec3 start = centreOfMass();
  const int steps = 500;
  double worstError = 0.0, worstPosition = 0.0;
  for (int step = 0; step < steps; ++step) {
    world->step();
    for (int k = 0; k < world->jointCount(); ++k) {
      const JointState state = world->jointStateAt(k);
      worstError = std::max(worstError, state.error);
      worstPosition = std::max(worstPosition, std::abs(state.position));
    }
  }
  EXPECT_LT(worstError, 1e-9) << "m or rad";
  EXPECT_LT(worstPosition, 1e-9) << "rad: the joints carry nothing and stay at 0";
  const double t = steps * def.settings.dt;
  const Vec3 fallen = centreOfMass() - start;
  // The joint step (RATTLE: velocity Verlet) is exact under a constant
  // acceleration, so the drop is the closed form's to rounding.
  EXPECT_NEAR(fallen.z(), -0.5 * kGravity * t * t, 1e-12);
  EXPECT_NEAR(fallen.x(), 0.0, 1e-12);
  EXPECT_NEAR(fallen.y(), 0.0, 1e-12);
}

}  // namespace
}  // namespace rbsim
