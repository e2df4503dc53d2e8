// The server's sections of a config file (lcm:, server:, limits:), read by
// the config loader in the same pass as the world: every key lands in
// ServerSettings, absent keys keep the defaults, relative directories are
// relative to the file, and each mistake is an error naming
// file:line:column and the key path.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "config/config_loader.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

const std::filesystem::path kDataDir = std::filesystem::path(rbsim::test_support::kTestDataDir) / "config";

// Raw string literals start with a newline so the YAML lines up on the page;
// dropped, so that the line after R"( is line 1.
std::string yaml(std::string_view text) {
  if (!text.empty() && text.front() == '\n') text.remove_prefix(1);
  return std::string(text);
}

Expected<Config> parse(std::string_view text) {
  return parseConfig(yaml(text), "dir/server.yaml", kDataDir.string());
}

std::string errorOf(std::string_view text) {
  const Expected<Config> config = parse(text);
  if (config.ok()) {
    ADD_FAILURE() << "accepted:\n" << yaml(text);
    return "";
  }
  return config.error().message;
}

TEST(ServerSections, EveryKeyIsRead) {
  const Expected<Config> config = parse(R"(
world: {dt: 0.002}
bodies:
  - {name: ball, shape: {type: sphere, radius: 0.5}, mass: 1}
lcm:
  url: "udpm://239.255.76.67:7667?ttl=0"
  channel_prefix: TEST_
  state_rate: 50
  status_rate: 5
  contacts_rate: 0
server:
  real_time_factor: 2.5
  duration: 12
  catch_up: reanchor
  max_burst: 7
  record: session.lcmlog
  start_paused: true
  spin_us: 100
  checkpoint_dir: checkpoints
  checkpoint_every: 1.5
  read_only: true
  spawn_mesh_directory: meshes
limits:
  max_force: 100
  max_torque: 20
  max_lever_arm: 3
  max_duration: 60
  max_steps_ahead: 1000
  max_real_time_factor: 10
  max_steps_per_command: 500
  wrench_bodies: [ball, box]
  client_rate: 50
  client_burst: 8
  max_message_bytes: 4096
  max_bodies: 30
  max_linear_speed: 40
  max_angular_speed: 90
)");
  ASSERT_TRUE(config.ok()) << config.error().message;
  // The world came from the same document.
  EXPECT_EQ(config->world.settings.dt, 0.002);
  ASSERT_EQ(config->world.bodies.size(), 1u);
  EXPECT_EQ(config->world.bodies[0].name, "ball");

  const ServerSettings& s = config->server;
  EXPECT_EQ(s.lcmUrl, "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(s.channelPrefix, "TEST_");
  EXPECT_EQ(s.stateRate, 50.0);
  EXPECT_EQ(s.statusRate, 5.0);
  EXPECT_EQ(s.contactsRate, 0.0);
  EXPECT_EQ(s.realTimeFactor, 2.5);
  ASSERT_TRUE(s.duration.has_value());
  EXPECT_EQ(*s.duration, 12.0);
  EXPECT_EQ(s.catchUp, CatchUpPolicy::Reanchor);
  EXPECT_EQ(s.maxBurst, 7);
  EXPECT_EQ(s.recordPath, "session.lcmlog");
  EXPECT_TRUE(s.startPaused);
  EXPECT_EQ(s.spinNanoseconds, 100000);
  // Relative to the config file's directory ("dir"), not to the process's.
  EXPECT_EQ(s.checkpointDirectory, (std::filesystem::path("dir") / "checkpoints").string());
  EXPECT_EQ(s.spawnMeshDirectory, (std::filesystem::path("dir") / "meshes").string());
  EXPECT_EQ(s.checkpointEvery, 1.5);
  EXPECT_TRUE(s.readOnly);
  EXPECT_EQ(s.limits.maxForce, 100.0);
  EXPECT_EQ(s.limits.maxTorque, 20.0);
  EXPECT_EQ(s.limits.maxLeverArm, 3.0);
  EXPECT_EQ(s.limits.maxDuration, 60.0);
  EXPECT_EQ(s.limits.maxStepsAhead, 1000);
  EXPECT_EQ(s.maxRealTimeFactor, 10.0);
  EXPECT_EQ(s.maxStepsPerCommand, 500);
  ASSERT_TRUE(s.wrenchBodies.has_value());
  EXPECT_EQ(*s.wrenchBodies, (std::vector<std::string>{"ball", "box"}));
  EXPECT_EQ(s.clientRate, 50.0);
  EXPECT_EQ(s.clientBurst, 8.0);
  EXPECT_EQ(s.maxMessageBytes, 4096);
  EXPECT_EQ(s.maxBodies, 30);
  EXPECT_EQ(s.stateLimits.maxLinearSpeed, 40.0);
  EXPECT_EQ(s.stateLimits.maxAngularSpeed, 90.0);
}

TEST(ServerSections, AbsentSectionsAndKeysKeepTheDefaults) {
  const Expected<Config> config = parse(R"(
bodies: []
server: {real_time_factor: 3}
)");
  ASSERT_TRUE(config.ok()) << config.error().message;
  const ServerSettings defaults;
  EXPECT_EQ(config->server.realTimeFactor, 3.0);
  EXPECT_EQ(config->server.lcmUrl, defaults.lcmUrl);
  EXPECT_EQ(config->server.channelPrefix, defaults.channelPrefix);
  EXPECT_EQ(config->server.catchUp, defaults.catchUp);
  EXPECT_EQ(config->server.limits.maxForce, defaults.limits.maxForce);
  EXPECT_EQ(config->server.clientBurst, defaults.clientBurst);
  EXPECT_FALSE(config->server.duration.has_value());
  EXPECT_FALSE(config->server.wrenchBodies.has_value());
  EXPECT_TRUE(config->server.checkpointDirectory.empty());
}

TEST(ServerSections, MistakesNameFileLineAndKeyPath) {
  EXPECT_EQ(errorOf(R"(
bodies: []
limits:
  max_force: -1
)"),
            "dir/server.yaml:3:14: limits.max_force: expected a positive number, got \"-1\"");
  EXPECT_EQ(errorOf(R"(
limits:
  client_burst: 0.5
)"),
            "dir/server.yaml:2:17: limits.client_burst: expected at least 1 message, got \"0.5\"");
  EXPECT_EQ(errorOf(R"(
server:
  catch_up: sometimes
)"),
            "dir/server.yaml:2:13: server.catch_up: expected burst or reanchor, got \"sometimes\"");
  EXPECT_EQ(errorOf(R"(
lcm: {status_rate: 0.5}
)"),
            "dir/server.yaml:1:20: lcm.status_rate: expected a rate between 1 and 10 Hz");
  const std::string unknownKey = errorOf(R"(
server:
  real_time_factr: 2
)");
  EXPECT_NE(unknownKey.find("dir/server.yaml:2:3: "), std::string::npos) << unknownKey;
  EXPECT_NE(unknownKey.find("real_time_factr"), std::string::npos) << unknownKey;
}

TEST(ServerSections, TheWorldIsCheckedFirst) {
  // Both parts wrong: the first mistake in reading order of the loader (the
  // world) is the one reported, as when rbserver read the world first.
  const std::string message = errorOf(R"(
limits: {max_force: -1}
world: {dt: -0.001}
)");
  EXPECT_NE(message.find("world.dt"), std::string::npos) << message;
}

TEST(ServerSections, LoadConfigReadsBothPartsOfOneFile) {
  const std::filesystem::path file =
      std::filesystem::path(::testing::TempDir()) / "rbsim_one_pass.yaml";
  {
    std::ofstream out(file);
    out << "bodies:\n  - {name: b, shape: {type: sphere, radius: 1}, mass: 2}\n"
           "server: {checkpoint_dir: ckpt}\nlimits: {max_bodies: 4}\n";
  }
  const Expected<Config> config = loadConfig(file.string());
  ASSERT_TRUE(config.ok()) << config.error().message;
  ASSERT_EQ(config->world.bodies.size(), 1u);
  EXPECT_EQ(config->server.maxBodies, 4);
  EXPECT_EQ(config->server.checkpointDirectory, (file.parent_path() / "ckpt").string());

  // A mistake in a server section is the loader's error now (file:line), not
  // something a second reader finds later.
  {
    std::ofstream out(file);
    out << "bodies: []\nlimits:\n  max_bodies: 0\n";
  }
  const Expected<Config> bad = loadConfig(file.string());
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message,
            file.string() + ":3:15: limits.max_bodies: expected a positive number, got \"0\"");
  std::filesystem::remove(file);
}

TEST(ServerSections, FullWorldFileHasItsServerSections) {
  const Expected<Config> config = loadConfig((kDataDir / "full_world.yaml").string());
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_EQ(config->server.lcmUrl, "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(config->server.realTimeFactor, 2.0);
  EXPECT_EQ(config->server.limits.maxForce, 100.0);
  EXPECT_EQ(config->world.bodies.size(), 6u);
}

}  // namespace
}  // namespace rbsim
