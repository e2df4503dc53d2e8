// Sleeping never eats a push, seen from a client: boxes at rest fall asleep
// after the sleep time; a 0.25 s wrench scheduled (apply_at_step) at each of
// 31 steps around that moment, one box each, changes each box's velocity by
// exactly F T / m, and no state shows a velocity taken back.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "rigid_body_math.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

class Sleeping : public ServerTest {};

TEST_F(Sleeping, NeverEatsAWrenchScheduledAroundTheSleepTime) {
  startServer("sleepy_boxes.yaml", {"--paused", "--state-rate", "0"});
  const double dt = client().world()->dt;
  const int64_t start = currentStep();
  ASSERT_EQ(start, 0);
  // At rest from the start, a box falls asleep in the step that takes its
  // rest time to 0.5 s: step 500 (the library's tests pin this down).
  const int64_t asleep = 500;
  const int64_t steps = 250;  // 0.25 s
  const double force = 4.0, mass = 2.0;
  for (int i = 0; i <= 30; ++i) {
    client::Wrench wrench;
    wrench.body = "box" + std::to_string(i);
    wrench.force = {force, 0.0, 0.0};
    wrench.pointFrame = client::Frame::Body;  // at the centre of mass
    wrench.mode = client::WrenchMode::Duration;
    wrench.duration = steps * dt;
    wrench.applyAtStep = asleep - 25 + i;
    const rbsim::ack_t ack = expectAccepted(client().applyWrench(wrench));
    EXPECT_EQ(ack.effective_step, wrench.applyAtStep);
  }
  // Every state is checked, so step in short bursts: 780 states of 31 bodies
  // at once overflow the client's socket buffer on a loaded machine (UDP
  // drops them), and the test would then miss states rather than physics.
  const int64_t total = asleep + 5 + steps + 10;
  for (int64_t done = 0; done < total; done += 20) stepAndWait(std::min<int64_t>(20, total - done));
  for (int i = 0; i <= 30; ++i) {
    const std::string name = "box" + std::to_string(i);
    const int64_t first = asleep - 25 + i;
    double previous = 0.0;
    for (int64_t step = first; step < first + steps; ++step) {
      const double v = history().body(step, name).linear_velocity[0];
      EXPECT_GT(v, previous) << name << ": a velocity taken back at step " << step;
      previous = v;
    }
    const double expected = force * steps * dt / mass;
    EXPECT_NEAR(history().body(first + steps - 1, name).linear_velocity[0], expected,
                1e-12 * expected)
        << name << ", pushed from step " << first;
    EXPECT_EQ(history().body(first + steps + 9, name).linear_velocity[0],
              history().body(first + steps - 1, name).linear_velocity[0])
        << name << ": nothing after the wrench";
  }
}

// The status counts the sleeping bodies: none before the sleep time, all 31
// after it, one less once a push wakes a box.
TEST_F(Sleeping, StatusCountsTheSleepingBodies) {
  startServer("sleepy_boxes.yaml", {"--paused"});
  const auto statusAt = [&](int64_t step, int32_t sleeping) {
    waitFor("a status of step " + std::to_string(step) + " with " + std::to_string(sleeping) +
                " bodies asleep",
            [&] {
              const auto& status = client().latestStatus();
              return status && status->step == step && status->num_sleeping_bodies == sleeping;
            });
  };
  expectAccepted(client().step(400));
  statusAt(400, 0);
  expectAccepted(client().step(200));  // past the sleep time (0.5 s at rest)
  statusAt(600, 31);
  client::Wrench push;
  push.body = "box7";
  push.force = {1.0, 0.0, 0.0};
  push.mode = client::WrenchMode::OneStep;
  expectAccepted(client().applyWrench(push));
  expectAccepted(client().step(1));
  statusAt(601, 30);
}

}  // namespace
}  // namespace rbsim::e2e
