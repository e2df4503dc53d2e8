// The `robots:` list of a world file (config/robot_config.h): a URDF
// pendulum steps bit-identically to the same bodies and joint written in
// YAML, a world's own joints can join a robot's bodies, and mistakes point
// at the world file's line and key.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "config/config_loader.h"
#include "rbsim/physics/world.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

const std::string kUrdfDir = std::string(rbsim::test_support::kTestDataDir) + "/urdf";

Expected<WorldDef> parse(const std::string& yaml) { return parseWorldConfig(yaml, "w.yaml", kUrdfDir); }

std::string errorOf(const std::string& yaml) {
  const Expected<WorldDef> world = parse(yaml);
  if (world.ok()) {
    ADD_FAILURE() << "accepted:\n" << yaml;
    return "";
  }
  return world.error().message;
}

bool sameBits(const RigidState& a, const RigidState& b) {
  return std::memcmp(a.position.data(), b.position.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(&a.orientation, &b.orientation, sizeof(Quaternion)) == 0 &&
         std::memcmp(a.linearMomentum.data(), b.linearMomentum.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(a.angularMomentum.data(), b.angularMomentum.data(), sizeof(double) * 3) == 0;
}

TEST(RobotConfig, AUrdfPendulumStepsBitIdenticallyToTheSameBodiesInYaml) {
  const Expected<WorldDef> fromUrdf = parse(
      "world: {dt: 0.001}\n"
      "robots:\n"
      "  - {name: pendulum, urdf: pendulum.urdf, position: [0, 0, 2]}\n");
  ASSERT_TRUE(fromUrdf.ok()) << fromUrdf.error().message;
  const Expected<WorldDef> fromYaml = parse(
      "world: {dt: 0.001}\n"
      "bodies:\n"
      "  - {name: pendulum/base, static: true, position: [0, 0, 2],\n"
      "     shape: {type: box, half_extents: [0.05, 0.05, 0.05]}}\n"
      "  - name: pendulum/bob\n"
      "    position: [0, 0, 2]\n"
      "    shape: {type: compound, shapes: [{shape: {type: sphere, radius: 0.05}, position: [1, 0, 0]}]}\n"
      "    mass: 1\n"
      "    center_of_mass: [1, 0, 0]\n"
      "    inertia: [0.001, 0.001, 0.001]\n"
      "joints:\n"
      "  - {name: pendulum/swing, type: revolute, body_a: pendulum/base, body_b: pendulum/bob,\n"
      "     anchor: [0, 0, 2], axis: [0, 1, 0]}\n");
  ASSERT_TRUE(fromYaml.ok()) << fromYaml.error().message;
  Expected<World> a = World::fromDef(*fromUrdf);
  Expected<World> b = World::fromDef(*fromYaml);
  ASSERT_TRUE(a.ok()) << a.error().message;
  ASSERT_TRUE(b.ok()) << b.error().message;
  const BodyId bobA = a->findBody("pendulum/bob"), bobB = b->findBody("pendulum/bob");
  for (int step = 0; step < 2000; ++step) {
    a->step();
    b->step();
    ASSERT_TRUE(sameBits(a->body(bobA).state(), b->body(bobB).state())) << "step " << step;
  }
  // And it swung: released from the horizontal, the bob is below it now.
  EXPECT_LT(a->body(bobA).position().z(), 1.5);
}

TEST(RobotConfig, AWorldsJointsMayJoinARobotsBodies) {
  const Expected<WorldDef> world = parse(
      "bodies:\n"
      "  - {name: tool, shape: {type: box, half_extents: [0.05, 0.05, 0.05]}, mass: 0.5, position: [1.0, 0, 0.1]}\n"
      "robots:\n"
      "  - {name: arm, urdf: two_link_arm.urdf, fixed_base: true}\n"
      "joints:\n"
      "  - {name: flange, type: fixed, body_a: arm/fore, body_b: tool, anchor: [1.0, 0, 0.1]}\n");
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_EQ(world->bodies.size(), 4u);
  EXPECT_EQ(world->joints.size(), 3u);
  Expected<World> built = World::fromDef(*world);
  ASSERT_TRUE(built.ok()) << built.error().message;
  for (int step = 0; step < 100; ++step) built->step();
  EXPECT_LT(built->jointState(built->findJoint("flange")).error, 1e-9);
}

TEST(RobotConfig, AnArmStartsAtItsJointPositionsAndItsJointsReadThem) {
  const Expected<WorldDef> def = parse(
      "robots:\n"
      "  - {name: arm, urdf: two_link_arm.urdf, fixed_base: true, joint_positions: {shoulder: 0.3, elbow: -0.5}}\n");
  ASSERT_TRUE(def.ok()) << def.error().message;
  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_NEAR(world->jointState(world->findJoint("arm/shoulder")).position, 0.3, 1e-12);
  EXPECT_NEAR(world->jointState(world->findJoint("arm/elbow")).position, -0.5, 1e-12);
  EXPECT_LT(world->jointState(world->findJoint("arm/elbow")).error, 1e-12) << "placed where the joints close";
}

TEST(RobotConfig, ALinkWithoutCollisionsCollidesWithNothing) {
  const Expected<WorldDef> def = parse("robots:\n  - {name: p, urdf: pendulum.urdf}\n");
  ASSERT_TRUE(def.ok()) << def.error().message;
  EXPECT_TRUE(def->bodies[1].collides) << "the bob has a sphere";
  const std::string yaml =
      "robots:\n  - {name: g, urdf: sensor_only.urdf}\n";
  const Expected<WorldDef> sensor = parse(yaml);
  ASSERT_TRUE(sensor.ok()) << sensor.error().message;
  ASSERT_EQ(sensor->bodies.size(), 1u);
  EXPECT_FALSE(sensor->bodies[0].collides);
  EXPECT_EQ(*sensor->bodies[0].mass, 0.2);
}

TEST(RobotConfig, TheLoadReportComesWithTheConfig) {
  const Expected<Config> config =
      parseConfig("robots:\n  - {name: arm, urdf: two_link_arm.urdf}\n", kUrdfDir + "/w.yaml", kUrdfDir);
  ASSERT_TRUE(config.ok()) << config.error().message;
  ASSERT_FALSE(config->robotReport.empty());
  EXPECT_NE(config->robotReport.front().find("robot 'arm' from two_link_arm.urdf"), std::string::npos)
      << config->robotReport.front();
}

// server.viewer_mesh_directory: the directory the viewer's bridge serves
// the world's visual meshes from (rbview --meshes), relative to the world
// file; mesh URLs are relative to it. By default the world file's own
// directory; a mesh outside the named one gets no URL (drawn from its
// collision shape); a bad value is the world file's error.
TEST(RobotConfig, ViewerMeshDirectoryIsWhereTheVisualsMeshUrlsAreRelativeTo) {
  const std::string robot = "robots:\n  - {name: v, urdf: visual_arm.urdf, package_paths: [packages]}\n";
  const auto urlOf = [](const Expected<Config>& config) -> std::string {
    if (!config.ok()) return "error: " + config.error().message;
    return config->visuals.at("v/arm").at(0).meshUrl;
  };
  EXPECT_EQ(urlOf(parseConfig(robot, kUrdfDir + "/w.yaml", kUrdfDir)),
            "world/packages/rbsim_test_parts/meshes/tetrahedron.stl");
  // One up: tests/data, which holds urdf/ (as config/ holds worlds/ and robots/).
  EXPECT_EQ(urlOf(parseConfig(robot + "server: {viewer_mesh_directory: ..}\n", kUrdfDir + "/w.yaml", kUrdfDir)),
            "world/urdf/packages/rbsim_test_parts/meshes/tetrahedron.stl");
  EXPECT_EQ(urlOf(parseConfig(robot + "server: {viewer_mesh_directory: " + kUrdfDir + "/packages}\n",
                              kUrdfDir + "/w.yaml", kUrdfDir)),
            "world/rbsim_test_parts/meshes/tetrahedron.stl")
      << "an absolute directory";
  EXPECT_EQ(urlOf(parseConfig(robot + "server: {viewer_mesh_directory: packages/rbsim_test_parts/elsewhere}\n",
                              kUrdfDir + "/w.yaml", kUrdfDir)),
            "")
      << "the mesh lies outside it";
  // The world alone (loadWorldConfig's way) reads it too: the robots' visuals
  // are made there.
  EXPECT_TRUE(parseWorldConfig(robot + "server: {viewer_mesh_directory: ..}\n", "w.yaml", kUrdfDir).ok());
  for (const std::string& bad : {std::string("server: {viewer_mesh_directory: ''}\n"),
                                 std::string("server: {viewer_mesh_directory: [a]}\n")}) {
    for (const std::string& world : {robot, std::string("world: {dt: 0.001}\n")}) {
      const Expected<Config> config = parseConfig(world + bad, kUrdfDir + "/w.yaml", kUrdfDir);
      ASSERT_FALSE(config.ok()) << world + bad;
      EXPECT_NE(config.error().message.find("server.viewer_mesh_directory"), std::string::npos)
          << config.error().message;
    }
  }
}

// hull_tolerance and hull_max_vertices: how far a collision mesh's hull is
// simplified. The open box's hull is a cube of 8 vertices; a budget of 5
// keeps 5, and the report says how far the cube lies outside them.
TEST(RobotConfig, HullKeysBoundTheCollisionHullAndAreChecked) {
  const std::string robot = "robots:\n  - name: bin\n    urdf: packaged_meshes.urdf\n    package_paths: [packages]\n";
  const Expected<Config> cooked =
      parseConfig(robot + "    hull_tolerance: 0\n    hull_max_vertices: 5\n", kUrdfDir + "/w.yaml", kUrdfDir);
  ASSERT_TRUE(cooked.ok()) << cooked.error().message;
  std::string report;
  for (const std::string& line : cooked->robotReport) report += line + "\n";
  EXPECT_NE(report.find("open_box.obj' (10 triangles, open:"), std::string::npos) << report;
  EXPECT_NE(report.find("collides as its convex hull (8 vertices, simplified to 5 vertices, the full hull within"),
            std::string::npos)
      << report;
  const Expected<Config> plain = parseConfig(robot, kUrdfDir + "/w.yaml", kUrdfDir);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  std::string plainReport;
  for (const std::string& line : plain->robotReport) plainReport += line + "\n";
  EXPECT_NE(plainReport.find("collides as its convex hull (8 vertices)"), std::string::npos) << plainReport;

  const std::string few = errorOf(robot + "    hull_max_vertices: 3\n");
  EXPECT_NE(few.find("w.yaml:5:24: robots[0].hull_max_vertices: hull_max_vertices must be at least 4"),
            std::string::npos)
      << few;
  const std::string negative = errorOf(robot + "    hull_tolerance: -0.001\n");
  EXPECT_NE(negative.find("w.yaml:5:21: robots[0].hull_tolerance"), std::string::npos) << negative;
}

// joint_drives: a URDF has no drives, so a world file gives them, and a
// robot holds its pose from the first step. Held against gravity, each
// servo rests where its spring's effort balances the closed-form gravity
// torque (test_robot_arm.cpp), to within what the joint's dry friction
// holds (URDF <dynamics friction>: 0.05 N·m on the shoulder, none on the
// elbow).
TEST(RobotConfig, JointDrivesHoldARobotWhereItIsPlacedOrAtTheirTargets) {
  const Expected<WorldDef> def = parse(
      "world: {dt: 0.001, gravity: [0, 0, -9.81]}\n"
      "contact: {sleeping: false}\n"
      "robots:\n"
      "  - name: arm\n"
      "    urdf: two_link_arm.urdf\n"
      "    fixed_base: true\n"
      "    joint_positions: {shoulder: 0.3, elbow: 0.5}\n"
      "    joint_drives:\n"
      "      shoulder: {stiffness: 2000, damping: 100}\n"
      "      elbow: {target: 0.6, stiffness: 2000, damping: 100, max_effort: 40}\n");
  ASSERT_TRUE(def.ok()) << def.error().message;
  ASSERT_EQ(def->joints.size(), 2u);
  const JointDef& shoulderDef = def->joints[0].def;
  const JointDef& elbowDef = def->joints[1].def;
  ASSERT_EQ(shoulderDef.name, "arm/shoulder");
  EXPECT_TRUE(shoulderDef.drive.enabled);
  EXPECT_EQ(shoulderDef.drive.target, 0.3) << "no target: where the joint is placed";
  EXPECT_EQ(shoulderDef.drive.stiffness, 2000.0);
  EXPECT_EQ(shoulderDef.drive.damping, 100.0);
  EXPECT_EQ(elbowDef.drive.target, 0.6);
  EXPECT_EQ(elbowDef.drive.maxEffort, 40.0);

  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  for (int k = 0; k < 4000; ++k) world->step();
  const JointState s = world->jointState(world->findJoint("arm/shoulder"));
  const JointState e = world->jointState(world->findJoint("arm/elbow"));
  EXPECT_LT(std::abs(s.rate) + std::abs(e.rate), 1e-9) << "settled";
  // The two-link arm: m1 = 2 kg at 0.25 m, l1 = 0.5 m, m2 = 1 kg at 0.25 m;
  // the efforts that hold it where it is.
  constexpr double g = 9.81;
  const double a1 = s.position, a12 = s.position + e.position;
  const double elbowHold = -g * 1.0 * 0.25 * std::cos(a12);
  const double shoulderHold = -g * (2.0 * 0.25 * std::cos(a1) + 1.0 * (0.5 * std::cos(a1) + 0.25 * std::cos(a12)));
  EXPECT_LE(std::abs(s.position - (0.3 - shoulderHold / 2000.0)), 0.05 / 2000.0 + 1e-9);
  EXPECT_NEAR(e.position, 0.6 - elbowHold / 2000.0, 1e-9);
  EXPECT_GT(std::abs(shoulderHold / 2000.0), 1e-3) << "the sag is measurable, so the drive is what holds the arm";
}

TEST(RobotConfig, TheLoadReportSaysWhichDrivesTheWorldFileGave) {
  const Expected<Config> config = parseConfig(
      "robots:\n  - name: arm\n    urdf: two_link_arm.urdf\n    joint_positions: {shoulder: 0.3}\n"
      "    joint_drives: {shoulder: {stiffness: 2000, damping: 100}, elbow: {target: 0.5, frequency: 4, max_effort: 9}}\n",
      kUrdfDir + "/w.yaml", kUrdfDir);
  ASSERT_TRUE(config.ok()) << config.error().message;
  const auto said = [&](const std::string& line) {
    return std::find(config->robotReport.begin(), config->robotReport.end(), line) != config->robotReport.end();
  };
  EXPECT_TRUE(said("joint 'arm/shoulder': position drive (joint_drives), target 0.3 rad, stiffness 2000, damping 100"));
  EXPECT_TRUE(said("joint 'arm/elbow': position drive (joint_drives), target 0.5 rad, frequency 4 Hz, damping ratio 1, "
                   "max effort 9 N·m"));
}

// gravity_compensation, state_rate and state_dynamics on a robot: the
// first reaches every axis joint's drive (its own and those commands turn
// on later), the other two say how its robot_state_t goes out.
TEST(RobotConfig, ARobotsGravityCompensationAndStatePublishing) {
  const Expected<Config> config = parseConfig(
      "robots:\n  - name: arm\n    urdf: two_link_arm.urdf\n    gravity_compensation: true\n"
      "    state_rate: 1000\n    state_dynamics: true\n    joint_drives: {shoulder: {stiffness: 20}}\n"
      "  - {name: other, urdf: two_link_arm.urdf, position: [2, 0, 0]}\n",
      kUrdfDir + "/w.yaml", kUrdfDir);
  ASSERT_TRUE(config.ok()) << config.error().message;
  for (const NamedJointDef& joint : config->world.joints) {
    const bool ours = joint.def.name.rfind("arm/", 0) == 0;
    EXPECT_EQ(joint.def.drive.gravityCompensation, ours) << joint.def.name;
  }
  EXPECT_TRUE(config->world.joints[0].def.drive.enabled);
  EXPECT_FALSE(config->world.joints[1].def.drive.enabled) << "set, for when a command turns the drive on";
  ASSERT_EQ(config->robotPublishing.count("arm"), 1u);
  EXPECT_EQ(config->robotPublishing.at("arm").stateRate, 1000.0);
  EXPECT_TRUE(config->robotPublishing.at("arm").dynamics);
  ASSERT_EQ(config->robotPublishing.count("other"), 1u);
  EXPECT_EQ(config->robotPublishing.at("other").stateRate, 0.0) << "with the world state";
  EXPECT_FALSE(config->robotPublishing.at("other").dynamics);
  EXPECT_NE(std::find(config->robotReport.begin(), config->robotReport.end(),
                      "gravity compensation on every joint's drive (gravity_compensation)"),
            config->robotReport.end());

  const std::string rate = errorOf("robots:\n  - {name: arm, urdf: two_link_arm.urdf, state_rate: 0}\n");
  EXPECT_NE(rate.find("robots[0].state_rate"), std::string::npos) << rate;
  const std::string flag = errorOf("robots:\n  - {name: arm, urdf: two_link_arm.urdf, state_dynamics: 1}\n");
  EXPECT_NE(flag.find("robots[0].state_dynamics"), std::string::npos) << flag;
}

TEST(RobotConfig, JointDrivesNameTheRobotsAxisJoints) {
  const std::string unknown = errorOf(
      "robots:\n  - name: arm\n    urdf: two_link_arm.urdf\n    joint_drives:\n      wrist: {stiffness: 1}\n");
  EXPECT_NE(unknown.find("w.yaml:5:7: robots[0].joint_drives.wrist: the robot has no joint named \"wrist\""),
            std::string::npos)
      << unknown;
  const std::string noGain = errorOf(
      "robots:\n  - name: arm\n    urdf: two_link_arm.urdf\n    joint_drives:\n      elbow: {target: 1}\n");
  EXPECT_NE(noGain.find("robots[0].joint_drives.elbow"), std::string::npos) << noGain;
  EXPECT_NE(noGain.find("stiffness"), std::string::npos) << noGain;
  const std::string notAMap =
      errorOf("robots:\n  - name: arm\n    urdf: two_link_arm.urdf\n    joint_drives: [elbow]\n");
  EXPECT_NE(notAMap.find("robots[0].joint_drives"), std::string::npos) << notAMap;

  // A fixed joint between two links with mass stays a joint, without an axis.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "rbsim_joint_drives_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "welded.urdf")
      << "<robot name=\"w\">\n"
         "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" "
         "iyz=\"0\" izz=\"0.1\"/></inertial></link>\n"
         "<link name=\"b\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" "
         "iyz=\"0\" izz=\"0.1\"/></inertial></link>\n"
         "<joint name=\"weld\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
         "</robot>\n";
  const Expected<WorldDef> welded = parseWorldConfig(
      "robots:\n  - name: w\n    urdf: welded.urdf\n    joint_drives: {weld: {stiffness: 1}}\n", "w.yaml",
      dir.string());
  std::filesystem::remove_all(dir);
  ASSERT_FALSE(welded.ok());
  EXPECT_NE(welded.error().message.find("robots[0].joint_drives.weld: joint \"weld\" has no axis for a drive"),
            std::string::npos)
      << welded.error().message;
}

TEST(RobotConfig, MistakesPointAtTheWorldFilesLineAndKey) {
  EXPECT_NE(errorOf("robots:\n  - {name: arm}\n").find("w.yaml:2:5: robots[0].urdf: missing required key"),
            std::string::npos)
      << errorOf("robots:\n  - {name: arm}\n");
  EXPECT_NE(errorOf("robots:\n  - {name: a/b, urdf: pendulum.urdf}\n").find("w.yaml:2:12: robots[0].name: a robot's name is 1 to 128 characters without '/'"),
            std::string::npos);
  EXPECT_NE(errorOf("robots:\n  - {name: p, urdf: pendulum.urdf}\n  - {name: p, urdf: pendulum.urdf}\n")
                .find("w.yaml:3:12: robots[1].name: duplicate robot name \"p\""),
            std::string::npos);
  EXPECT_NE(errorOf("robots:\n  - {name: p, urdf: pendulum.urdf, colour: red}\n").find("robots[0]"), std::string::npos);
  EXPECT_NE(errorOf("bodies:\n  - {name: p/bob, shape: {type: sphere, radius: 1}}\n"
                    "robots:\n  - {name: p, urdf: pendulum.urdf}\n")
                .find("robot \"p\" makes a body named \"p/bob\", which the world already has"),
            std::string::npos);
  EXPECT_NE(errorOf("robots:\n  - {name: p, urdf: missing.urdf}\n").find("w.yaml:2:21: robots[0].urdf: missing.urdf: cannot read"),
            std::string::npos)
      << errorOf("robots:\n  - {name: p, urdf: missing.urdf}\n");
  const std::string follower =
      errorOf("robots:\n  - name: g\n    urdf: gripper_mimic.urdf\n    joint_drives: {right_slide: {stiffness: 10}}\n");
  EXPECT_NE(follower.find("w.yaml:4:20: robots[0].joint_drives.right_slide: joint \"right_slide\" follows joint "
                          "'g/left_slide' (mimic) and takes no drive of its own"),
            std::string::npos)
      << follower;
  const std::string outside = errorOf("robots:\n  - name: arm\n    urdf: two_link_arm.urdf\n"
                                      "    joint_positions: {elbow: 9}\n");
  EXPECT_NE(outside.find("w.yaml:4:22: robots[0].joint_positions: joint 'elbow' at 9 is outside its limits"),
            std::string::npos)
      << outside;
  EXPECT_NE(errorOf("robots:\n  - {name: p, urdf: pendulum.urdf, fixed_base: 1}\n").find("robots[0].fixed_base"),
            std::string::npos);
}

}  // namespace
}  // namespace rbsim
