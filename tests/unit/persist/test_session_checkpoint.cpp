// Session checkpoints: wrenches and pause state round-trip, the file
// container refuses truncated, padded and corrupted files, and client
// names stay inside the checkpoint directory.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "persist/checkpoint_file.h"
#include "persist/session_checkpoint.h"

namespace rbsim {
namespace {

Session pushedSession() {
  World world;
  BodyDef def;
  def.name = "ball";
  def.shape = SphereShape{0.1};
  EXPECT_TRUE(world.createBody(def).ok());
  Session session(world, false);
  WrenchRequest persistent;
  persistent.client = "c";
  persistent.body = "ball";
  persistent.force = Vec3(1.0, 2.0, 3.0);
  persistent.mode = WrenchMode::Persistent;
  persistent.firstStep = 1;
  session.wrenches().add(persistent);
  WrenchRequest later = persistent;
  later.mode = WrenchMode::Duration;
  later.durationSteps = 7;
  later.firstStep = 40;
  session.wrenches().add(later);
  // World points: one already fixed in the body (acting), one not yet (pending).
  WrenchRequest atCorner = persistent;
  atCorner.client = "d";
  atCorner.point = Vec3(0.1, 0.0, 0.05);
  atCorner.torque = Vec3(0.0, 0.1, 0.0);
  atCorner.firstStep = 5;  // the ball has moved by then
  session.wrenches().add(atCorner);
  WrenchRequest bodyForce = atCorner;
  bodyForce.frame = WrenchFrame::ShapeFrame;
  bodyForce.mode = WrenchMode::OneStep;
  bodyForce.firstStep = 12;
  session.wrenches().add(bodyForce);
  for (int i = 0; i < 10; ++i) session.step();
  session.pause();
  session.requestSteps(3);
  return session;
}

TEST(SessionCheckpoint, JointCommandsScheduledAheadRoundTrip) {
  World world;
  BodyDef def;
  def.name = "wheel";
  def.shape = CylinderShape{0.2, 0.05};
  def.mass = 2.0;
  def.position = Vec3(0, 0, 1);
  const BodyId wheel = *world.createBody(def);
  JointDef axle;
  axle.name = "axle";
  axle.bodyB = wheel;
  axle.anchor = Vec3(0, 0, 1);
  ASSERT_TRUE(world.createJoint(axle).ok());
  Session original(world, false);
  JointCommandRequest spin;
  spin.client = "c";
  spin.seq = 7;
  spin.joint = "axle";
  spin.mode = JointCommandMode::Velocity;
  spin.target = 3.0;
  spin.maxEffort = 0.5;
  spin.firstStep = 20;
  original.jointCommands().add(spin);
  JointCommandRequest hold = spin;
  hold.seq = 8;
  hold.mode = JointCommandMode::Position;
  hold.target = 1.0;
  hold.maxEffort = std::numeric_limits<double>::infinity();  // uncapped
  hold.stiffness = 5.0;
  hold.damping = 0.5;
  hold.targetRate = 0.25;   // a robot command's entry: the drive's target rate
  hold.feedForward = -0.1;  // and its feed-forward effort
  hold.firstStep = 300;
  original.jointCommands().add(hold);
  for (int i = 0; i < 10; ++i) original.step();
  const auto payload = encodeSessionCheckpoint(original);
  ASSERT_TRUE(payload.ok()) << payload.error().message;
  auto state = decodeSessionCheckpoint(*payload, original.world().settings());
  ASSERT_TRUE(state.ok()) << state.error().message;
  ASSERT_EQ(state->jointCommands.size(), 2u);
  EXPECT_EQ(state->jointCommands[1].mode, JointCommandMode::Position);
  EXPECT_TRUE(std::isinf(state->jointCommands[1].maxEffort));
  EXPECT_EQ(state->jointCommands[1].targetRate, 0.25);
  EXPECT_EQ(state->jointCommands[1].feedForward, -0.1);
  Session restored(original.initialWorld(), false);
  restored.resumeFrom(std::move(state->world), std::move(state->wrenches), state->worldRevision, state->paused,
                      state->stepsRequested, std::move(state->jointCommands));
  for (int i = 0; i < 500; ++i) {
    original.step();
    restored.step();
    ASSERT_EQ(restored.world().stateHash(), original.world().stateHash()) << "step " << i;
  }
  EXPECT_NE(original.world().body(wheel).angularVelocity().z(), 0.0) << "the commands acted";
}

TEST(SessionCheckpoint, WrenchesAndPauseStateRoundTrip) {
  Session original = pushedSession();
  const auto payload = encodeSessionCheckpoint(original);
  ASSERT_TRUE(payload.ok());
  auto state = decodeSessionCheckpoint(*payload, original.world().settings());
  ASSERT_TRUE(state.ok()) << state.error().message;
  EXPECT_TRUE(state->paused);
  EXPECT_EQ(state->stepsRequested, 3);
  EXPECT_EQ(state->wrenches.activeCount(), 2);
  EXPECT_EQ(state->wrenches.pendingCount(), 2);
  // The acting wrench keeps the body point its world point was fixed to,
  // bit for bit; the pending one still holds its world point.
  EXPECT_EQ(state->wrenches.active()[1].pointFrame, WrenchFrame::ShapeFrame);
  EXPECT_EQ(state->wrenches.active()[1].point, original.wrenches().active()[1].point);
  EXPECT_NE(state->wrenches.active()[1].point, Vec3(0.1, 0.0, 0.05));
  EXPECT_EQ(state->wrenches.pending()[1].pointFrame, WrenchFrame::World);
  EXPECT_EQ(state->wrenches.pending()[1].frame, WrenchFrame::ShapeFrame);

  Session restored(original.initialWorld(), false);
  restored.resumeFrom(std::move(state->world), std::move(state->wrenches), state->worldRevision, state->paused,
                      state->stepsRequested);
  for (int i = 0; i < 60; ++i) {
    original.step();
    restored.step();
    ASSERT_EQ(restored.world().stateHash(), original.world().stateHash()) << "step " << i;
  }
}

TEST(SessionCheckpoint, FileContainerRefusesDamagedFiles) {
  const auto payload = encodeSessionCheckpoint(pushedSession());
  ASSERT_TRUE(payload.ok());
  const std::vector<uint8_t> file = checkpointFileBytes(*payload);
  EXPECT_TRUE(checkpointPayload(file, "f").ok());
  const auto message = [&](std::vector<uint8_t> bytes) {
    const auto result = checkpointPayload(bytes, "f");
    return result.ok() ? std::string("accepted") : result.error().message;
  };
  EXPECT_NE(message({file.begin(), file.end() - 1}).find("truncated"), std::string::npos);
  EXPECT_NE(message({file.begin(), file.begin() + 10}).find("not an rbsim checkpoint"), std::string::npos);
  auto padded = file;
  padded.push_back(0);
  EXPECT_NE(message(padded).find("trailing bytes"), std::string::npos);
  auto flipped = file;
  flipped[file.size() / 2] ^= 0x10;
  EXPECT_NE(message(flipped).find("checksum"), std::string::npos);
  auto version = file;
  version[8] = 2;
  EXPECT_NE(message(version).find("version 2"), std::string::npos);
}

TEST(SessionCheckpoint, AtomicWriteAndLoad) {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("rbsim-ckpt-" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory);
  const Session session = pushedSession();
  const std::string path = (directory / "a.rbck").string();
  ASSERT_TRUE(saveSessionCheckpoint(session, path).ok());
  ASSERT_TRUE(saveSessionCheckpoint(session, path).ok()) << "replacing an existing file";
  const auto loaded = loadSessionCheckpoint(path, session.world().settings());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->world.stateHash(), session.world().stateHash());
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(directory)) ++files;
  EXPECT_EQ(files, 1) << "no temporary file is left behind";
  std::filesystem::create_symlink(path, directory / "link.rbck");
  EXPECT_FALSE(loadSessionCheckpoint((directory / "link.rbck").string(), session.world().settings(), true).ok())
      << "names from clients do not follow symbolic links";
  std::filesystem::remove_all(directory);
}

TEST(SessionCheckpoint, ClientNamesStayInTheDirectory) {
  EXPECT_EQ(*checkpointPathIn("/var/ck", "run-1_a.rbck"), "/var/ck/run-1_a.rbck");
  for (const std::string& bad : std::vector<std::string>{"", "..", "../x", "/etc/passwd", "a/b", ".hidden", "a\\b", "x y",
                                std::string(129, 'a')})
    EXPECT_FALSE(checkpointPathIn("/var/ck", bad).ok()) << "'" << bad << "'";
  EXPECT_NE(checkpointPathIn("", "a").error().message.find("disabled"), std::string::npos);
}

}  // namespace
}  // namespace rbsim
