// Checkpoints over the bus and on disk: SAVE_CHECKPOINT and RESET with a
// path (only inside the checkpoint directory), --checkpoint-every surviving
// kill -9, and --resume.

#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <rbsim/command_t.hpp>

#include "checkpoint_commands.h"
#include "e2e_paths.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

using Checkpoints = ServerTest;

const std::string kWorld = std::string(kWorldsDir) + "/replay_pile.yaml";

TEST_F(Checkpoints, SaveOverTheBusAndResetToItContinuesIdentically) {
  const std::string directory = scratchPath("checkpoints");
  startServer(kWorld, {"--paused", "--state-rate", "0", "--checkpoint-dir", directory});
  stepAndWait(300);
  const rbsim::ack_t saved = expectAccepted(sendPathCommand(client(), rbsim::command_t::SAVE_CHECKPOINT, "at300.rbck"));
  EXPECT_NE(saved.reason.find("at300.rbck"), std::string::npos) << saved.reason;
  ASSERT_TRUE(std::filesystem::is_regular_file(directory + "/at300.rbck"));
  stepAndWait(400);
  const rbsim::world_state_t first = history().at(700);

  // Back to the checkpoint: the same step, and the same states after it.
  expectAccepted(sendPathCommand(client(), rbsim::command_t::RESET, "at300.rbck"));
  waitFor("the state of step 300 after the reset", [&] {
    return client().latestState() && client().latestState()->step == 300;
  });
  stepAndWait(400);
  const rbsim::world_state_t second = history().at(700);
  EXPECT_TRUE(sameBodies(first, second)) << "the run from the checkpoint differs from the first run";

  // Client paths never leave the checkpoint directory.
  for (const char* bad : {"../escape.rbck", "/tmp/abs.rbck", ".hidden", "sub/dir.rbck", "a b"}) {
    const rbsim::ack_t ack = expectRejected(sendPathCommand(client(), rbsim::command_t::SAVE_CHECKPOINT, bad));
    EXPECT_NE(ack.reason.find("plain file name"), std::string::npos) << ack.reason;
    expectRejected(sendPathCommand(client(), rbsim::command_t::RESET, bad));
  }
  EXPECT_FALSE(std::filesystem::exists(scratchPath("escape.rbck")));
  // A file that is not a checkpoint, and one that is missing.
  std::ofstream(directory + "/garbage.rbck") << "not a checkpoint at all";
  const rbsim::ack_t garbage = expectRejected(sendPathCommand(client(), rbsim::command_t::RESET, "garbage.rbck"));
  EXPECT_NE(garbage.reason.find("not an rbsim checkpoint"), std::string::npos) << garbage.reason;
  expectRejected(sendPathCommand(client(), rbsim::command_t::RESET, "missing.rbck"));
}

TEST_F(Checkpoints, AWorldWithJointsIsSavedAndResetToIdentically) {
  // The example world of joints: hinges with limits, damping and friction,
  // a motor, a drive, a slider at its limit, a weld, a rope and a cone.
  const std::string directory = scratchPath("checkpoints");
  startServer(std::string(kWorldsDir) + "/../../../config/worlds/joints.yaml",
              {"--paused", "--state-rate", "0", "--checkpoint-dir", directory});
  stepAndWait(300);
  expectAccepted(sendPathCommand(client(), rbsim::command_t::SAVE_CHECKPOINT, "joints.rbck"));
  stepAndWait(500);
  const rbsim::world_state_t first = history().at(800);
  expectAccepted(sendPathCommand(client(), rbsim::command_t::RESET, "joints.rbck"));
  waitFor("the state of step 300 after the reset", [&] {
    return client().latestState() && client().latestState()->step == 300;
  });
  stepAndWait(500);
  EXPECT_TRUE(sameBodies(first, history().at(800))) << "the run from the checkpoint differs from the first run";
}

TEST_F(Checkpoints, SaveIsRejectedWithoutACheckpointDirectory) {
  startServer(kWorld, {});
  const rbsim::ack_t ack = expectRejected(sendPathCommand(client(), rbsim::command_t::SAVE_CHECKPOINT, "x.rbck"));
  EXPECT_NE(ack.reason.find("disabled"), std::string::npos) << ack.reason;
}

// kill -9 at random moments of a run that checkpoints every 20 steps: the
// periodic file is always whole, and a server resumes from it.
TEST_F(Checkpoints, LastPeriodicCheckpointSurvivesKill9AndResumes) {
  const std::string directory = scratchPath("periodic");
  const std::string periodic = directory + "/periodic.rbck";
  std::random_device entropy;
  std::mt19937 random(entropy());
  for (int round = 0; round < 3; ++round) {
    // --instance-check 0: alone in its namespace, it steps from its first
    // millisecond, so that the kill moments below fall in the run.
    ChildProcess run({kRbserver, "--config", kWorld, "--lcm-url", kUrl, "--real-time-factor", "0",
                      "--checkpoint-dir", directory, "--checkpoint-every", "0.02",
                      "--instance-check", "0"},
                     scratchPath("run" + std::to_string(round) + ".log"));
    const auto delay = std::chrono::milliseconds(150 + random() % 400);
    std::this_thread::sleep_for(delay);
    run.signal(SIGKILL);
    ASSERT_EQ(run.wait(5s), 128 + SIGKILL) << run.output();
    ASSERT_TRUE(std::filesystem::exists(periodic)) << "no checkpoint after " << delay.count() << " ms";
  }
  startServer(kWorld, {"--resume", periodic, "--paused"});
  const int64_t step = currentStep();
  EXPECT_GT(step, 0);
  EXPECT_EQ(step % 20, 0) << "a periodic checkpoint is taken every 20 steps";
  stepAndWait(10);
  EXPECT_EQ(currentStep(), step + 10);
}

}  // namespace
}  // namespace rbsim::e2e
