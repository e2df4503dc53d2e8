// Hardening seen from a client: a body the numerical guard froze is counted
// on RBSIM_STATUS, named in the log, refuses wrenches and comes back with
// RESET; a spawned body may not load a mesh from outside the config
// directory.

#include <gtest/gtest.h>

#include <rbsim/command_t.hpp>

#include "rbsim/client/lookup.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

using Hardening = ServerTest;

client::Wrench push(const std::string& body, double force, double duration) {
  client::Wrench wrench;
  wrench.body = body;
  wrench.force = {force, 0.0, 0.0};
  wrench.frame = client::Frame::Body;  // through the centre of mass
  wrench.mode = client::WrenchMode::Duration;
  wrench.duration = duration;
  return wrench;
}

const rbsim::body_state_t& stateOf(const rbsim::world_state_t& state, const std::string& name) {
  for (const auto& body : state.bodies)
    if (body.name == name) return body;
  throw std::runtime_error("no body " + name + " in the state");
}

TEST_F(Hardening, AnOverSpeedBodyIsFrozenCountedOnStatusAndClearedByReset) {
  startServer("speed_limited.yaml", {"--paused", "--state-rate", "0"});
  waitFor("a first status", [&] { return client().latestStatus().has_value(); });
  EXPECT_EQ(client().latestStatus()->num_frozen_bodies, 0);

  // 99 N on 1 kg: 4.95 m/s after 50 steps, 5.05 m/s (over the limit) after 51.
  expectAccepted(client().applyWrench(push("runner", 99.0, 0.08)));
  const int64_t start = currentStep();
  stepAndWait(100);
  const rbsim::world_state_t after = *client().latestState();
  ASSERT_EQ(after.step, start + 100);
  const auto& runner = stateOf(after, "runner");
  for (int i = 0; i < 3; ++i) EXPECT_EQ(runner.linear_velocity[i], 0.0) << "held still";
  // Held at its pose after step 50: Σ 0.099 i · 1 ms over i = 1..50 = 0.126 m.
  EXPECT_NEAR(runner.position[0], 0.126, 0.001);
  EXPECT_GT(stateOf(after, "bystander").position[0], 0.0) << "the other body steps on";
  // The wire says which body froze and why, in the state and the description.
  EXPECT_EQ(runner.frozen, "linear_speed");
  EXPECT_EQ(stateOf(after, "bystander").frozen, "");
  waitFor("a world description naming the frozen body", [&] {
    const auto& world = client().world();
    if (!world) return false;
    for (const auto& body : world->bodies)
      if (body.name == "runner") return body.frozen == "linear_speed";
    return false;
  });

  waitFor("a status counting the frozen body",
          [&] { return client().latestStatus()->step == after.step && client().latestStatus()->num_frozen_bodies == 1; });
  spinFor(50ms);
  const std::string log = server().output();
  EXPECT_NE(log.find("body 'runner' frozen at step " + std::to_string(start + 51)), std::string::npos) << log;
  EXPECT_NE(log.find("linear speed"), std::string::npos) << log;

  const rbsim::ack_t refused = expectRejected(client().applyWrench(push("runner", 1.0, 0.01)));
  EXPECT_NE(refused.reason.find("frozen"), std::string::npos) << refused.reason;

  expectAccepted(client().reset());
  waitFor("a status with nothing frozen", [&] {
    const auto& status = client().latestStatus();
    return status->step == 0 && status->num_frozen_bodies == 0;
  });
  expectAccepted(client().applyWrench(push("runner", 1.0, 0.01)));
  waitFor("a state where nothing is frozen", [&] {
    return client().latestState() && client().latestState()->step == 0 &&
           stateOf(*client().latestState(), "runner").frozen.empty();
  });
}

TEST_F(Hardening, SpawnedMeshesMustComeFromTheConfigDirectory) {
  startServer("speed_limited.yaml", {"--paused", "--state-rate", "0"});
  const rbsim::ack_t absolute = expectRejected(
      client().spawn("{name: intruder, shape: {type: mesh, file: /etc/passwd}}"));
  EXPECT_NE(absolute.reason.find("absolute paths are not allowed"), std::string::npos) << absolute.reason;
  const rbsim::ack_t escaping = expectRejected(
      client().spawn("{name: intruder, shape: {type: mesh, file: ../../data/meshes/cube.obj}}"));
  EXPECT_NE(escaping.reason.find("'..' is not allowed"), std::string::npos) << escaping.reason;
  const rbsim::ack_t missing = expectRejected(
      client().spawn("{name: intruder, shape: {type: mesh, file: nothing_here.obj}}"));
  EXPECT_NE(missing.reason.find("no such file"), std::string::npos) << missing.reason;
}

}  // namespace
}  // namespace rbsim::e2e
