// Control commands end to end: pause, step N, resume, reset, spawn, remove,
// the real-time factor and PUBLISH_WORLD, each acknowledged and each with the
// effect the contract (lcmtypes/rbsim/command_t.lcm) describes.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <rbsim/command_t.hpp>

#include "rbsim/client/lookup.h"
#include "rigid_body_math.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

using Commands = ServerTest;

const char* kProbeYaml =
    "{name: probe, shape: {type: sphere, radius: 0.1}, mass: 2.0, position: [5.0, 5.0, 5.0], "
    "linear_velocity: [1.0, 0.0, 0.0]}";

int32_t largestId(const rbsim::world_t& world) {
  int32_t largest = 0;
  for (const auto& body : world.bodies) largest = std::max(largest, body.id);
  return largest;
}

TEST_F(Commands, PauseStopsSteppingAndStepTakesExactlyN) {
  startServer("free_bodies.yaml", {"--state-rate", "0"});
  waitFor("the server to step", [&] { return currentStep() >= 20; });

  const rbsim::ack_t pause = expectAccepted(client().pause());
  EXPECT_EQ(pause.request, rbsim::command_t::PAUSE);
  // No step is taken after PAUSE is handled: the last state is effective_step − 1.
  const int64_t pausedAt = pause.effective_step - 1;
  waitForStep(pausedAt);
  spinFor(150ms);
  EXPECT_EQ(history().lastStep(), pausedAt);
  waitFor("a status saying paused", [&] {
    const auto& status = client().latestStatus();
    return status && status->paused && status->step == pausedAt;
  });

  const rbsim::ack_t step = stepAndWait(7);
  EXPECT_EQ(step.request, rbsim::command_t::STEP);
  EXPECT_EQ(step.effective_step, pausedAt + 1);
  spinFor(150ms);
  EXPECT_EQ(history().lastStep(), pausedAt + 7) << "STEP 7 must take exactly 7 steps";
  for (int64_t s = pausedAt + 1; s <= pausedAt + 7; ++s)
    EXPECT_TRUE(history().has(s)) << "state of step " << s << " (state rate 0: every step)";
  EXPECT_NEAR(history().at(pausedAt + 7).sim_time,
              static_cast<double>(pausedAt + 7) * client().world()->dt, 1e-12);
}

// Two STEPs sent back to back: the second one's steps come after the
// first's, so its effective_step (the step during which it takes effect) is
// the one after them, whether or not the server read it before stepping.
TEST_F(Commands, QueuedStepsAreAcknowledgedWithTheirOwnFirstStep) {
  startServer("free_bodies.yaml", {"--paused", "--state-rate", "0"});
  const int64_t start = currentStep();
  const client::Request first = client().step(3);
  const client::Request second = client().step(2);
  const rbsim::ack_t firstAck = expectAccepted(first);
  const rbsim::ack_t secondAck = expectAccepted(second);
  waitForStep(start + 5);
  spinFor(100ms);
  EXPECT_EQ(history().lastStep(), start + 5) << "3 + 2 steps";
  EXPECT_EQ(firstAck.effective_step, start + 1);
  EXPECT_EQ(secondAck.effective_step, start + 4);
}

TEST_F(Commands, ResumeStepsAgainAndStepNeedsPause) {
  startServer("free_bodies.yaml", {"--paused"});
  const int64_t start = currentStep();
  const rbsim::ack_t zero = expectRejected(client().step(0));
  EXPECT_NE(zero.reason.find("num_steps"), std::string::npos) << zero.reason;

  const rbsim::ack_t resume = expectAccepted(client().resume());
  EXPECT_EQ(resume.request, rbsim::command_t::RESUME);
  waitFor("steps after RESUME", [&] { return currentStep() >= start + 50; });
  waitFor("a status saying running",
          [&] { return client().latestStatus() && !client().latestStatus()->paused; });

  const rbsim::ack_t refused = expectRejected(client().step(3));
  EXPECT_NE(refused.reason.find("PAUSE"), std::string::npos) << refused.reason;
  const int64_t now = currentStep();
  waitFor("the server to keep stepping", [&] { return currentStep() >= now + 50; });
}

TEST_F(Commands, ResetReturnsToTheInitialWorld) {
  startServer("free_bodies.yaml", {"--paused", "--state-rate", "0"});
  const rbsim::world_state_t initial = *client().latestState();
  const int64_t revision = client().world()->world_revision;
  ASSERT_EQ(initial.step, 0);

  client::Wrench push;
  push.body = "puck";
  push.force = {3.0, 0.0, 0.0};
  push.point = toVec3(client::findBody(initial, "puck")->position);
  push.mode = client::WrenchMode::Persistent;
  expectAccepted(client().applyWrench(push));
  expectAccepted(client().spawn(kProbeYaml));
  stepAndWait(20);
  ASSERT_NE(toVec3(history().body(20, "puck").linear_velocity),
            toVec3(client::findBody(initial, "puck")->linear_velocity));

  const rbsim::ack_t reset = expectAccepted(client().reset());
  EXPECT_EQ(reset.request, rbsim::command_t::RESET);
  waitFor("the state after RESET", [&] {
    const auto& state = client().latestState();
    return state && state->world_revision > revision + 1 && state->step == 0;
  });
  const rbsim::world_state_t after = *client().latestState();
  EXPECT_DOUBLE_EQ(after.sim_time, 0.0);
  ASSERT_EQ(after.bodies.size(), initial.bodies.size()) << "the spawned body must be gone";
  for (std::size_t i = 0; i < after.bodies.size(); ++i) {
    const auto& a = after.bodies[i];
    const auto& b = initial.bodies[i];
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(toVec3(a.position), toVec3(b.position)) << a.name;
    EXPECT_TRUE(
        std::equal(std::begin(a.orientation), std::end(a.orientation), std::begin(b.orientation)))
        << a.name;
    EXPECT_EQ(toVec3(a.linear_velocity), toVec3(b.linear_velocity)) << a.name;
    EXPECT_EQ(toVec3(a.angular_velocity), toVec3(b.angular_velocity)) << a.name;
  }
  waitFor("the world description after RESET",
          [&] { return client().world()->world_revision == after.world_revision; });
  EXPECT_EQ(client::findBody(*client().world(), "probe"), nullptr);

  // The persistent wrench went with the old world.
  stepAndWait(5);
  EXPECT_EQ(toVec3(history().body(5, "puck").linear_velocity),
            toVec3(client::findBody(initial, "puck")->linear_velocity));
}

TEST_F(Commands, SpawnAndRemoveBodies) {
  startServer("free_bodies.yaml", {"--paused", "--state-rate", "0"});
  const int64_t revision = client().world()->world_revision;
  const int32_t largest = largestId(*client().world());

  const rbsim::ack_t spawned = expectAccepted(client().spawn(kProbeYaml));
  EXPECT_EQ(spawned.request, rbsim::command_t::SPAWN);
  waitFor("the world description with the probe",
          [&] { return client::findBody(*client().world(), "probe") != nullptr; });
  EXPECT_GT(client().world()->world_revision, revision);
  const auto probe = *client::findBody(*client().world(), "probe");
  EXPECT_GT(probe.id, largest) << "a new body gets a new id";
  EXPECT_EQ(probe.mass, 2.0);
  EXPECT_EQ(probe.shape_type, "sphere");

  const rbsim::ack_t duplicate = expectRejected(client().spawn(kProbeYaml));
  EXPECT_NE(duplicate.reason.find("probe"), std::string::npos) << duplicate.reason;
  expectRejected(client().spawn("{name: bad, shape: {type: sphere, radius: -1.0}}"));
  expectRejected(client().spawn("not: [valid"));

  // It moves like a free body: 10 steps at 1 m/s.
  const rbsim::ack_t step = stepAndWait(10);
  const auto& moved = history().body(step.effective_step + 9, "probe");
  EXPECT_EQ(moved.id, probe.id);
  EXPECT_NEAR(moved.position[0], 5.0 + 10 * client().world()->dt, 1e-12);

  const rbsim::ack_t removed = expectAccepted(client().remove("probe"));
  EXPECT_EQ(removed.request, rbsim::command_t::REMOVE);
  waitFor("the world description without the probe",
          [&] { return client::findBody(*client().world(), "probe") == nullptr; });
  const int64_t after = stepAndWait(1).effective_step;
  EXPECT_EQ(client::findBody(history().at(after), "probe"), nullptr);

  const rbsim::ack_t again = expectRejected(client().remove("probe"));
  EXPECT_NE(again.reason.find("probe"), std::string::npos) << again.reason;

  // Spawned again under the same name, it is a new body with a new id.
  expectAccepted(client().spawn(kProbeYaml));
  waitFor("the world description with the new probe",
          [&] { return client::findBody(*client().world(), "probe") != nullptr; });
  EXPECT_GT(client::findBody(*client().world(), "probe")->id, probe.id) << "ids are never reused";
}

// A compound arrives through the same parser as a config file's bodies, and
// viewers get its parts in the world description.
TEST_F(Commands, SpawnACompoundBody) {
  startServer("free_bodies.yaml", {"--paused", "--state-rate", "0"});
  const char* dumbbellYaml =
      "{name: dumbbell, position: [0, 0, 20], density: 1000, linear_velocity: [1, 0, 0],\n"
      " shape: {type: compound, shapes: [\n"
      "  {shape: {type: sphere, radius: 0.1}, position: [-0.4, 0, 0]},\n"
      "  {shape: {type: sphere, radius: 0.1}, position: [0.4, 0, 0]},\n"
      "  {shape: {type: capsule, radius: 0.02, half_length: 0.3},\n"
      "   rpy: [0, 1.5707963267948966, 0]}]}}";
  expectAccepted(client().spawn(dumbbellYaml));
  waitFor("the world description with the dumbbell",
          [&] { return client::findBody(*client().world(), "dumbbell") != nullptr; });
  const rbsim::body_description_t dumbbell = *client::findBody(*client().world(), "dumbbell");
  EXPECT_EQ(dumbbell.shape_type, "compound");
  ASSERT_EQ(dumbbell.num_parts, 3);
  ASSERT_EQ(dumbbell.parts.size(), 3u);
  EXPECT_EQ(dumbbell.parts[0].shape_type, "sphere");
  EXPECT_EQ(dumbbell.parts[0].radius, 0.1);
  EXPECT_EQ(dumbbell.parts[1].position[0], 0.4);
  EXPECT_EQ(dumbbell.parts[2].shape_type, "capsule");
  EXPECT_EQ(dumbbell.parts[2].half_length, 0.3);
  // Two spheres and a capsule of water: 2 (4/3 π r³) + π r² (2 h) + 4/3 π r³ for the caps.
  const double sphere = 4.0 / 3.0 * M_PI * 0.001;
  const double rod = M_PI * 0.0004 * 0.6 + 4.0 / 3.0 * M_PI * 8e-6;
  EXPECT_NEAR(dumbbell.mass, 1000.0 * (2.0 * sphere + rod), 1e-9);

  // A nested compound is refused with the loader's message.
  const rbsim::ack_t nested = expectRejected(client().spawn(
      "{name: nest, shape: {type: compound, shapes: [{shape: {type: compound, shapes: []}}]}}"));
  EXPECT_NE(nested.reason.find("a compound cannot contain a compound"), std::string::npos)
      << nested.reason;

  // It moves like any free body (zero gravity here): 10 steps at 1 m/s.
  const rbsim::ack_t step = stepAndWait(10);
  const auto& moved = history().body(step.effective_step + 9, "dumbbell");
  EXPECT_EQ(moved.id, dumbbell.id);
  EXPECT_NEAR(moved.position[0], 10 * client().world()->dt, 1e-12);
  EXPECT_EQ(moved.position[2], 20.0);
}

// wire contract (body_state_t.id): "a removed body's id is never given to a
// later body". RESET removes the bodies spawned since the start.
TEST_F(Commands, BodyIdsAreNeverReusedAcrossReset) {
  startServer("free_bodies.yaml", {"--paused"});
  expectAccepted(client().spawn(kProbeYaml));
  waitFor("the probe", [&] { return client::findBody(*client().world(), "probe") != nullptr; });
  const int32_t probeId = client::findBody(*client().world(), "probe")->id;

  expectAccepted(client().reset());
  waitFor("the world after RESET",
          [&] { return client::findBody(*client().world(), "probe") == nullptr; });
  expectAccepted(client().spawn(
      "{name: other_probe, shape: {type: sphere, radius: 0.1}, mass: 1.0, position: [0, 0, 9]}"));
  waitFor("the new probe",
          [&] { return client::findBody(*client().world(), "other_probe") != nullptr; });
  EXPECT_GT(client::findBody(*client().world(), "other_probe")->id, probeId)
      << "the id of the body RESET removed was given to a new body";
}

TEST_F(Commands, SetRealTimeFactorAndPublishWorld) {
  startServer("free_bodies.yaml", {});
  const rbsim::ack_t rtf = expectAccepted(client().setRealTimeFactor(2.5));
  EXPECT_EQ(rtf.request, rbsim::command_t::SET_REAL_TIME_FACTOR);
  waitFor("a status with the new target factor", [&] {
    return client().latestStatus() && client().latestStatus()->target_real_time_factor == 2.5;
  });
  expectRejected(client().setRealTimeFactor(-1.0));
  expectRejected(client().setRealTimeFactor(std::numeric_limits<double>::quiet_NaN()));

  const uint64_t worlds = client().worldCount();
  const rbsim::ack_t publish = expectAccepted(client().publishWorld());
  EXPECT_EQ(publish.request, rbsim::command_t::PUBLISH_WORLD);
  waitFor("the requested world description", [&] { return client().worldCount() > worlds; });
  EXPECT_EQ(client().world()->total_bodies, 4);
}

}  // namespace
}  // namespace rbsim::e2e
