// The example worlds of public robots (config/worlds/panda.yaml, ur5e.yaml,
// a1.yaml, their robots in config/robots/): each loads, holds its pose from
// the first step for a second of simulated time, and its visuals come with
// mesh URLs under the directory the viewer serves (server.viewer_mesh_directory
// `..`: config/, so URLs are world/robots/...).
//
// The arms are on fixed bases, held by position drives where joint_positions
// places them: every joint stays on its constraints (errors below 1e-6),
// settles within a few mrad of its target (each sags by the torque it
// carries over its stiffness) and no link touches anything. The Panda's
// second finger follows the first (the URDF's <mimic>): the two stay equal,
// and moving the leader's drive target moves both. The A1 floats: on its
// four feet its trunk stays within a few cm of where it starts and level.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/config_loader.h"
#include "robot/urdf_robot.h"
#include "rbsim/physics/world.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

const std::string kConfigDir = std::string(rbsim::test_support::kTestDataDir) + "/../../config";

std::string worldFile(const std::string& name) {
  return kConfigDir + "/worlds/" + name;
}

World loadWorld(const std::string& name) {
  const Expected<WorldDef> def = loadWorldConfig(worldFile(name));
  if (!def) throw std::runtime_error(def.error().message);
  Expected<World> world = World::fromDef(*def);
  if (!world) throw std::runtime_error(world.error().message);
  return std::move(*world);
}

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

// A second of simulated time; what the joints and contacts did meanwhile.
struct Held {
  double worstError = 0.0;  // m or rad, of every joint at every step
  std::vector<std::string> touching;  // the robot's bodies that touched something, once each
};

Held runOneSecond(World& world, const std::string& robot, const std::function<void()>& afterStep = {}) {
  Held held;
  const int steps = static_cast<int>(std::lround(1.0 / world.settings().dt));
  for (int step = 0; step < steps; ++step) {
    world.step();
    for (int k = 0; k < world.jointCount(); ++k)
      held.worstError = std::max(held.worstError, world.jointStateAt(k).error);
    for (const SolvedManifold& contact : world.contacts()) {
      for (const int body : {contact.bodyA, contact.bodyB}) {
        const std::string& name = world.bodyAt(body).name();
        if (startsWith(name, robot + "/") &&
            std::find(held.touching.begin(), held.touching.end(), name) == held.touching.end())
          held.touching.push_back(name);
      }
    }
    if (afterStep) afterStep();
  }
  return held;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// Each of the robot's driven joints is within `tolerance` of its drive's
// target (it sags by the torque it carries over the drive's stiffness) and,
// with `atRest`, settled.
void expectOnTargets(const World& world, double tolerance, bool atRest) {
  for (int k = 0; k < world.jointCount(); ++k) {
    const JointDef& def = world.jointDefinitionAt(k);
    if (!def.drive.enabled) continue;
    const JointState state = world.jointStateAt(k);
    EXPECT_NEAR(state.position, def.drive.target, tolerance) << state.name;
    if (atRest) {
      EXPECT_LT(std::abs(state.rate), 1e-3) << state.name << ": settled";
    }
  }
}

// Every visual mesh of the world's robots has a URL under the world route,
// relative to config/ (server.viewer_mesh_directory: ..), naming a file that
// is there; returns how many there are.
int expectMeshUrlsUnder(const std::string& file, const std::string& prefix, const std::string& extension) {
  const Expected<Config> config = loadConfig(worldFile(file));
  EXPECT_TRUE(config.ok()) << config.error().message;
  if (!config) return 0;
  int meshes = 0;
  for (const auto& [body, visuals] : config->visuals) {
    for (const Visual& visual : visuals) {
      if (visual.kind != Visual::Kind::Mesh) continue;
      ++meshes;
      EXPECT_TRUE(startsWith(visual.meshUrl, prefix)) << body << ": " << visual.meshFile << " as '" << visual.meshUrl << "'";
      EXPECT_TRUE(visual.meshUrl.ends_with(extension)) << visual.meshUrl;
      const std::string relative = visual.meshUrl.substr(std::string("world/").size());
      EXPECT_TRUE(std::filesystem::is_regular_file(kConfigDir + "/" + relative)) << visual.meshUrl;
    }
  }
  return meshes;
}

TEST(ExampleWorlds, ThePandaHoldsItsPoseWithItsHandOpen) {
  World world = loadWorld("panda.yaml");
  const JointId leader = world.findJoint("panda/panda_finger_joint1");
  const JointId follower = world.findJoint("panda/panda_finger_joint2");
  ASSERT_FALSE(leader.isNull());
  ASSERT_FALSE(follower.isNull());
  const JointDef& mimic = world.jointDefinition(follower);
  EXPECT_TRUE(mimic.mimic.enabled);
  EXPECT_EQ(mimic.mimic.leader, "panda/panda_finger_joint1");
  EXPECT_FALSE(mimic.drive.enabled) << "a follower takes no drive: the leader's moves both";
  EXPECT_EQ(world.jointCount(), 9);
  for (int k = 1; k <= 7; ++k)
    EXPECT_TRUE(world.jointDefinition(world.findJoint("panda/panda_joint" + std::to_string(k))).drive.enabled) << k;

  double worstApart = 0.0;
  const Held held = runOneSecond(world, "panda", [&] {
    worstApart = std::max(worstApart, std::abs(world.jointState(leader).position - world.jointState(follower).position));
  });
  EXPECT_LT(held.worstError, 1e-6) << "m or rad";
  EXPECT_TRUE(held.touching.empty()) << "the arm touches nothing: " << joined(held.touching);
  expectOnTargets(world, 1e-2, true);  // joint4 carries the most: 7 mrad
  EXPECT_LT(worstApart, 1e-9) << "m: the fingers are coupled";
  EXPECT_NEAR(world.jointState(leader).position, 0.02, 1e-4) << "m: open";
}

TEST(ExampleWorlds, ThePandasFingersMoveTogetherWhenTheLeadersTargetChanges) {
  World world = loadWorld("panda.yaml");
  const JointId leader = world.findJoint("panda/panda_finger_joint1");
  const JointId follower = world.findJoint("panda/panda_finger_joint2");
  JointDrive drive = world.jointDefinition(leader).drive;
  drive.target = 0.035;  // m: wider
  ASSERT_TRUE(world.setJointDrive(leader, drive).ok());
  double worstApart = 0.0;
  const Held held = runOneSecond(world, "panda", [&] {
    worstApart = std::max(worstApart, std::abs(world.jointState(leader).position - world.jointState(follower).position));
  });
  EXPECT_LT(held.worstError, 1e-6);
  EXPECT_LT(worstApart, 1e-9) << "m";
  EXPECT_NEAR(world.jointState(leader).position, 0.035, 1e-4);
  EXPECT_NEAR(world.jointState(follower).position, 0.035, 1e-4);
  // The fingers move apart along opposite axes (the URDF's y and −y of the hand).
  const JointState left = world.jointState(leader), right = world.jointState(follower);
  EXPECT_LT(left.axis.dot(right.axis), -0.999);
  EXPECT_TRUE(held.touching.empty()) << joined(held.touching);
}

TEST(ExampleWorlds, TheUr5eHoldsItsPose) {
  World world = loadWorld("ur5e.yaml");
  EXPECT_EQ(world.jointCount(), 6);
  const Held held = runOneSecond(world, "ur5e");
  EXPECT_LT(held.worstError, 1e-6) << "m or rad";
  EXPECT_TRUE(held.touching.empty()) << "the arm touches nothing: " << joined(held.touching);
  expectOnTargets(world, 1e-2, true);
  EXPECT_NEAR(world.jointState(world.findJoint("ur5e/shoulder_lift_joint")).position, -1.2, 1e-2);
}

// Standing from 1 cm above the ground: its feet land, its legs carry the
// trunk (12.5 kg), and it stays there, level.
TEST(ExampleWorlds, TheA1StandsOnItsFourFeet) {
  World world = loadWorld("a1.yaml");
  EXPECT_EQ(world.jointCount(), 12);
  const BodyId trunk = world.findBody("a1/trunk");
  ASSERT_FALSE(trunk.isNull());
  const double startHeight = world.body(trunk).position().z();
  // The world's up in the trunk's body frame at the start (level then):
  // how far it turns away from up is how far the trunk tips.
  const Vec3 up = world.body(trunk).orientation().inverseRotate(Vec3::UnitZ());
  double lowest = startHeight, highest = startHeight, leastUp = 1.0;
  const Held held = runOneSecond(world, "a1", [&] {
    const BodyView body = world.body(trunk);
    lowest = std::min(lowest, body.position().z());
    highest = std::max(highest, body.position().z());
    leastUp = std::min(leastUp, body.orientation().rotate(up).z());
  });
  EXPECT_LT(held.worstError, 1e-6) << "m or rad";
  EXPECT_GT(lowest, startHeight - 0.04) << "m: the legs carry it";
  EXPECT_LT(highest, startHeight + 0.005) << "m: nothing throws it up";
  EXPECT_GT(leastUp, std::cos(0.05)) << "the trunk tips less than 0.05 rad";
  const Vec3 drift = world.body(trunk).position();
  EXPECT_LT(std::hypot(drift.x(), drift.y()), 0.02) << "m: it stays where it stood";
  // Only the feet (the spheres merged into the calves) touch the ground.
  std::vector<std::string> expected = {"a1/FL_lower", "a1/FR_lower", "a1/RL_lower", "a1/RR_lower"};
  std::vector<std::string> touching = held.touching;
  std::sort(touching.begin(), touching.end());
  EXPECT_EQ(touching, expected) << joined(touching);
  // The calves carry the most (their drives' 20 Hz on the small inertia
  // of a calf: 0.06 rad). Their rates are checked once it has settled
  // (below): the trunk's weight on the ground sways slowly on springs
  // tuned for the legs' inertia.
  expectOnTargets(world, 0.1, false);
}

// The A1 as published: its zero pose has every calf 0.916 rad above its
// upper limit ([-2.696534, -0.916298]). Hung from a fixed base with no
// drives, the description loads, the report names each calf and by how
// much, and the limits bring the calves back within 10 steps (0.1 rad a
// step) with no velocity from it: nothing moves faster than gravity could
// make it in that time.
TEST(ExampleWorlds, TheA1sZeroPoseBeyondItsCalvesLimitsIsBroughtBack) {
  RobotPlacement placement;
  placement.name = "a1";
  placement.fixedBase = true;
  placement.position = Vec3(0, 0, 1);
  RobotFiles files;
  files.sourceName = "a1.urdf";
  Expected<RobotModel> robot = loadRobot(kConfigDir + "/robots/a1/a1.urdf", placement, files);
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  const char* legs[] = {"FR", "FL", "RR", "RL"};
  for (const char* leg : legs) {
    const std::string line = std::string("joint 'a1/") + leg +
                             "_lower_joint' starts at 0, 0.916298 rad above its upper limit -0.916298";
    EXPECT_TRUE(std::any_of(robot->report.begin(), robot->report.end(),
                            [&](const std::string& l) { return l.find(line) != std::string::npos; }))
        << line;
  }
  WorldDef def;
  def.settings.dt = 0.001;
  def.settings.gravity = Vec3(0, 0, -9.81);
  def.bodies = robot->bodies;
  def.joints = robot->joints;
  Expected<World> world = World::fromDef(def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  double fastest = 0.0;
  for (int step = 1; step <= 30; ++step) {
    world->step();
    for (BodyView body : world->bodies()) fastest = std::max(fastest, body.linearVelocity().norm());
    if (step < 10) continue;
    for (const char* leg : legs) {
      const JointId id = world->findJoint(std::string("a1/") + leg + "_lower_joint");
      EXPECT_LE(world->jointState(id).position - world->jointDefinition(id).limit.upper, 1e-9)
          << leg << " at step " << step;
    }
  }
  // 30 ms of gravity gives 0.29 m/s; a leg swung back by its limit through
  // velocity would move at 0.9 rad in 1 ms, tens of m/s at the feet.
  EXPECT_LT(fastest, 1.0) << "m/s";
}

// Standing, it comes to rest: after 4 s every joint's rate and every body's
// speed is below 1e-3 (the drives act before the contact solve, which
// answers them; when they acted after it, on legs as if in the air, each
// step left the calves turning at 0.74 rad/s and the feet pressing into
// the ground at 0.08 m/s, taken back by the next step's contacts and
// split impulses, while nothing moved).
TEST(ExampleWorlds, TheStandingA1ComesToRest) {
  World world = loadWorld("a1.yaml");
  for (int step = 0; step < 4000; ++step) world.step();
  for (int k = 0; k < world.jointCount(); ++k) {
    const JointState state = world.jointStateAt(k);
    EXPECT_LT(std::abs(state.rate), 1e-3) << state.name << ": rad/s";
  }
  for (const BodyView body : world.bodies()) {
    if (!startsWith(body.name(), "a1/")) continue;
    EXPECT_LT(body.linearVelocity().norm(), 1e-3) << body.name() << ": m/s";
    EXPECT_LT(body.angularVelocity().norm(), 1e-2) << body.name() << ": rad/s";
  }
  const double height = world.body(world.findBody("a1/trunk")).position().z();
  EXPECT_NEAR(height, 0.288, 0.005) << "m";
}

TEST(ExampleWorlds, VisualsComeWithMeshUrlsUnderTheServedConfigDirectory) {
  // The Panda: eight visual OBJs and link0's and link7's collision OBJs.
  EXPECT_EQ(expectMeshUrlsUnder("panda.yaml", "world/robots/franka_panda/meshes/", ".obj"), 11);
  // The UR5e: its seven COLLADA files.
  EXPECT_EQ(expectMeshUrlsUnder("ur5e.yaml", "world/robots/ur5e/meshes/visual/", ".dae"), 7);
  // The A1: the trunk and each leg's hip, thigh and calf.
  EXPECT_EQ(expectMeshUrlsUnder("a1.yaml", "world/robots/a1/meshes/", ".obj"), 13);
}

}  // namespace
}  // namespace rbsim
