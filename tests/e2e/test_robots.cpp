// A robot spawned over LCM (command_t.spawn_yaml with a robots: list) is
// a world's bodies and joints like any other: the server logs its load
// report, a checkpoint holds it and a reset to the checkpoint continues
// bit-identically, and a recorded session that spawns and drives it
// replays bit for bit (the replay reads the URDF from the same spawn
// directory, the world file's).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <rbsim/command_t.hpp>
#include <string>

#include "checkpoint_commands.h"
#include "e2e_paths.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

namespace fs = std::filesystem;

// The planar two-link arm of the URDF tests (shoulder and elbow about y),
// spawned with its base welded to the world, 1 m up, its shoulder at 0.3.
constexpr const char* kSpawnArm =
    "robots:\n"
    "  - {name: arm, urdf: robots/two_link_arm.urdf, position: [0, 0, 1], fixed_base: true,\n"
    "     joint_positions: {shoulder: 0.3, elbow: -0.4}}\n";

class RobotSession : public ServerTest {
 protected:
  // A world of a ground plane in the scratch directory, beside robots/ with
  // the arm's URDF: the spawn directory is the world file's.
  std::string writeWorld() {
    const fs::path directory = scratchPath("world");
    fs::create_directories(directory / "robots");
    fs::copy_file(fs::path(kTestDataDir) / "urdf" / "two_link_arm.urdf",
                  directory / "robots" / "two_link_arm.urdf");
    const fs::path world = directory / "arm.yaml";
    std::ofstream(world) << "world: {dt: 0.001, gravity: [0, 0, -9.81]}\n"
                            "bodies:\n"
                            "  - {name: ground, shape: {type: plane}, static: true}\n";
    return world.string();
  }

  // A servo on the shoulder and a torque on the elbow: the arm moves under
  // drive, effort, gravity, its joints' damping, friction and limits.
  void driveTheArm() {
    client::JointCommand servo;
    servo.joint = "arm/shoulder";
    servo.mode = client::JointMode::Position;
    servo.target = 0.8;
    servo.stiffness = 400.0;
    servo.damping = 20.0;
    expectAccepted(client().commandJoint(servo));
    client::JointCommand push;
    push.joint = "arm/elbow";
    push.mode = client::JointMode::Effort;
    push.target = 1.5;
    expectAccepted(client().commandJoint(push));
  }
};

TEST_F(RobotSession, ASpawnedRobotIsLoggedCheckpointedAndResetToIdentically) {
  const std::string directory = scratchPath("checkpoints");
  startServer(writeWorld(), {"--paused", "--state-rate", "0", "--checkpoint-dir", directory});
  expectAccepted(client().spawn(kSpawnArm));
  waitFor("the world with the arm", [&] {
    const auto& world = client().world();
    return world && world->total_bodies == 4 && world->total_joints == 2;
  });
  // The load report is in the server's log, as a world file's is at start.
  waitFor("the arm's load report in the log", [&] {
    return server().output().find("robots: robot 'arm' from ") != std::string::npos;
  });
  EXPECT_NE(server().output().find("arm/shoulder"), std::string::npos) << server().output();

  driveTheArm();
  stepAndWait(200);
  expectAccepted(sendPathCommand(client(), rbsim::command_t::SAVE_CHECKPOINT, "arm.rbck"));
  stepAndWait(300);
  const rbsim::world_state_t first = history().at(500);
  // The arm moved between the checkpoint and step 500 (the servo and the
  // torque did work), so the comparison below compares motion.
  ASSERT_EQ(first.bodies.size(), 4u);
  const rbsim::world_state_t atCheckpoint = history().at(200);
  ASSERT_EQ(atCheckpoint.bodies.size(), 4u);
  for (std::size_t i = 0; i < first.bodies.size(); ++i) {
    if (first.bodies[i].name != "arm/fore") continue;
    double moved = 0.0;
    for (int k = 0; k < 3; ++k)
      moved += std::abs(first.bodies[i].position[k] - atCheckpoint.bodies[i].position[k]);
    EXPECT_GT(moved, 1e-3) << "the arm's fore link did not move after the checkpoint";
  }

  expectAccepted(sendPathCommand(client(), rbsim::command_t::RESET, "arm.rbck"));
  waitFor("the state of step 200 after the reset", [&] {
    return client().latestState() && client().latestState()->step == 200;
  });
  stepAndWait(300);
  EXPECT_TRUE(sameBodies(first, history().at(500))) << "the run from the checkpoint differs from the first run";
}

TEST_F(RobotSession, ASessionThatSpawnsAndDrivesARobotReplaysBitIdentically) {
  const std::string world = writeWorld();
  const std::string record = scratchPath("arm.lcmlog");
  startServer(world, {"--record", record, "--paused", "--state-rate", "0"});
  stepAndWait(20);
  expectAccepted(client().spawn(kSpawnArm));
  stepAndWait(30);
  driveTheArm();
  stepAndWait(150);
  client::JointCommand off;
  off.joint = "arm/shoulder";
  off.mode = client::JointMode::Off;
  expectAccepted(client().commandJoint(off));
  stepAndWait(100);
  const auto status = stopServer(10s);
  ASSERT_TRUE(status.has_value());
  ASSERT_EQ(*status, 0);

  const ProcessResult replay =
      runProcess({kRbserver, "--config", world, "--replay", record, "--verify"}, scratchPath("verify.log"), 60s);
  ASSERT_TRUE(replay.status.has_value());
  EXPECT_EQ(*replay.status, 0) << replay.output;
  long long statePages = 0, jointPages = 0;
  const std::size_t at = replay.output.find("replay identical to the log: ");
  ASSERT_NE(at, std::string::npos) << replay.output;
  ASSERT_EQ(std::sscanf(replay.output.c_str() + at, "replay identical to the log: %lld state pages and %lld joint pages",
                        &statePages, &jointPages),
            2)
      << replay.output;
  // The arm's joints were there for the 280 steps after the spawn.
  EXPECT_GE(jointPages, 280) << replay.output;
}

}  // namespace
}  // namespace rbsim::e2e
