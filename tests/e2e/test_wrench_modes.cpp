// Every wrench mode (one step, duration, persistent with its per-client
// replacement, clear) and apply_at_step, seen step by step on the free ball
// of worlds/free_bodies.yaml (zero gravity, at rest): the velocity changes by
// exactly (sum of the forces acting in step s)·dt/m in the state of step s.

#include <gtest/gtest.h>

#include <rbsim/wrench_t.hpp>

#include "rbsim/client/lookup.h"
#include "rigid_body_math.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

class WrenchModes : public ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    startServer("free_bodies.yaml", {"--paused", "--state-rate", "0"});
  }

  Vec3 velocity(int64_t step) { return toVec3(history().body(step, "ball").linear_velocity); }

  // Checks that the forces acting on the ball during `step` sum to `force`.
  void expectNetForceDuring(int64_t step, const Vec3& force) {
    const double dt = client().world()->dt;
    const double mass = description("ball").mass;
    const Vec3 change = velocity(step) - velocity(step - 1);
    if (force == Vec3{0.0, 0.0, 0.0}) {
      EXPECT_EQ(change, force) << "no force should act during step " << step;
    } else {
      EXPECT_LT(relativeError(change, (dt / mass) * force), 1e-9) << "during step " << step;
    }
  }

  client::Wrench force(const Vec3& f, client::WrenchMode mode) {
    client::Wrench wrench;
    wrench.body = "ball";
    wrench.force = f;
    // Through the centre of mass (the ball is a sphere: a lever arm would
    // only spin it, but keep it clean).
    wrench.point = toVec3(client::findBody(*client().latestState(), "ball")->position);
    wrench.mode = mode;
    return wrench;
  }
};

TEST_F(WrenchModes, OneStepActsDuringExactlyOneStep) {
  const Vec3 f{0.5, -0.25, 0.125};
  const rbsim::ack_t ack =
      expectAccepted(client().applyWrench(force(f, client::WrenchMode::OneStep)));
  EXPECT_EQ(ack.request, rbsim::wrench_t::MODE_ONE_STEP);
  const int64_t k = ack.effective_step;
  stepAndWait(4);
  expectNetForceDuring(k - 0, f);
  expectNetForceDuring(k + 1, {0, 0, 0});
  expectNetForceDuring(k + 2, {0, 0, 0});
  EXPECT_EQ(velocity(k - 1), Vec3({0, 0, 0}));
}

TEST_F(WrenchModes, ApplyAtStepSchedulesAFutureStep) {
  const int64_t start = currentStep();
  client::Wrench wrench = force({0.0, 0.0, 1.0}, client::WrenchMode::OneStep);
  wrench.applyAtStep = start + 6;
  const rbsim::ack_t ack = expectAccepted(client().applyWrench(wrench));
  EXPECT_EQ(ack.effective_step, start + 6);
  stepAndWait(8);
  for (int64_t step = start + 1; step <= start + 8; ++step)
    expectNetForceDuring(step, step == start + 6 ? wrench.force : Vec3{0, 0, 0});
}

TEST_F(WrenchModes, DurationIsRoundedToWholeSteps) {
  // 3.4 ms at dt = 1 ms: three steps; 0.2 ms: at least one.
  client::Wrench wrench = force({1.0, 0.0, 0.0}, client::WrenchMode::Duration);
  wrench.duration = 0.0034;
  const int64_t k = expectAccepted(client().applyWrench(wrench)).effective_step;
  stepAndWait(5);
  for (int64_t step = k; step < k + 5; ++step)
    expectNetForceDuring(step, step < k + 3 ? wrench.force : Vec3{0, 0, 0});

  wrench.duration = 0.0002;
  const int64_t k2 = expectAccepted(client().applyWrench(wrench)).effective_step;
  stepAndWait(2);
  expectNetForceDuring(k2, wrench.force);
  expectNetForceDuring(k2 + 1, {0, 0, 0});
}

TEST_F(WrenchModes, PersistentIsReplacedPerClientAndCleared) {
  auto other = makeClient("e2e-other");
  const Vec3 f1{1.0, 0.0, 0.0}, f2{0.0, 2.0, 0.0}, f3{0.0, 0.0, -1.0};

  // Persistent acts until replaced.
  const int64_t k1 = expectAccepted(client().applyWrench(force(f1, client::WrenchMode::Persistent)))
                         .effective_step;
  stepAndWait(3);
  for (int64_t s = k1; s < k1 + 3; ++s) expectNetForceDuring(s, f1);

  // A new persistent wrench from the same client on the same body replaces it.
  const int64_t k2 = expectAccepted(client().applyWrench(force(f2, client::WrenchMode::Persistent)))
                         .effective_step;
  EXPECT_EQ(k2, k1 + 3);
  stepAndWait(3);
  for (int64_t s = k2; s < k2 + 3; ++s) expectNetForceDuring(s, f2);

  // Another client's persistent wrench adds to it: replacement is per client.
  const int64_t k3 =
      expectAccepted(other->applyWrench(force(f3, client::WrenchMode::Persistent)), other.get())
          .effective_step;
  stepAndWait(3);
  for (int64_t s = k3; s < k3 + 3; ++s) expectNetForceDuring(s, f2 + f3);

  // CLEAR removes only this client's wrenches on the body.
  const rbsim::ack_t cleared = expectAccepted(client().clearWrenches("ball"));
  EXPECT_EQ(cleared.request, rbsim::wrench_t::MODE_CLEAR);
  const int64_t k4 = cleared.effective_step;
  stepAndWait(3);
  for (int64_t s = k4; s < k4 + 3; ++s) expectNetForceDuring(s, f3);

  // CLEAR with no body: all of the other client's wrenches.
  const int64_t k5 = expectAccepted(other->clearWrenches(""), other.get()).effective_step;
  stepAndWait(3);
  for (int64_t s = k5; s < k5 + 3; ++s) expectNetForceDuring(s, {0, 0, 0});
}

TEST_F(WrenchModes, ClearStopsADurationWrenchButNotAOneStep) {
  client::Wrench longPush = force({0.0, 1.0, 0.0}, client::WrenchMode::Duration);
  longPush.duration = 1.0;
  const int64_t k = expectAccepted(client().applyWrench(longPush)).effective_step;
  stepAndWait(4);
  for (int64_t s = k; s < k + 4; ++s) expectNetForceDuring(s, longPush.force);

  // A one-step wrench and a CLEAR for the same step: the clear takes the
  // duration wrench, the one-step push still acts.
  const Vec3 tap{0.0, 0.0, 0.5};
  const int64_t kTap =
      expectAccepted(client().applyWrench(force(tap, client::WrenchMode::OneStep))).effective_step;
  const int64_t kClear = expectAccepted(client().clearWrenches("ball")).effective_step;
  EXPECT_EQ(kTap, k + 4);
  EXPECT_EQ(kClear, k + 4);
  stepAndWait(3);
  expectNetForceDuring(k + 4, tap);
  expectNetForceDuring(k + 5, {0, 0, 0});
  expectNetForceDuring(k + 6, {0, 0, 0});
}

}  // namespace
}  // namespace rbsim::e2e
