// Wrenches against the mechanics they must produce, on free bodies in zero
// gravity (worlds/free_bodies.yaml), with the server paused and stepped so
// that every step's state is seen (--state-rate 0).
//
// Momentum is what the integrator updates by F·dt each step, so a velocity
// or angular-momentum change must match F·T to rounding: 1e-9 relative.

#include <gtest/gtest.h>

#include <rbsim/wrench_t.hpp>

#include "rigid_body_math.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

constexpr double kTolerance = 1e-9;

class WrenchPhysics : public ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    startServer("free_bodies.yaml", {"--paused", "--state-rate", "0"});
  }
  double dt() { return client().world()->dt; }  // s
};

Vec3 velocityOf(const rbsim::body_state_t& body) {
  return toVec3(body.linear_velocity);
}

TEST_F(WrenchPhysics, WorldForceForDurationChangesVelocityByFTOverM) {
  const double mass = description("puck").mass;
  const int64_t start = currentStep();
  const Vec3 v0 = velocityOf(history().body(start, "puck"));

  client::Wrench wrench;
  wrench.body = "puck";
  wrench.force = {0.6, -1.2, 0.9};
  wrench.point = toVec3(history().body(start, "puck").position);
  wrench.mode = client::WrenchMode::Duration;
  wrench.duration = 0.05;
  const int64_t steps = 50;  // T / dt
  const rbsim::ack_t ack = expectAccepted(client().applyWrench(wrench));
  EXPECT_EQ(ack.request, rbsim::wrench_t::MODE_DURATION);
  EXPECT_EQ(ack.effective_step, start + 1)
      << "a wrench received while paused acts from the next step";

  stepAndWait(steps + 30);
  const int64_t k = ack.effective_step;

  // The first state that shows the change is the state of the effective step.
  int64_t firstChanged = -1;
  for (int64_t step = start; step <= start + steps + 30 && firstChanged < 0; ++step)
    if (velocityOf(history().body(step, "puck")) != v0) firstChanged = step;
  EXPECT_EQ(firstChanged, k);

  // While it acts, v grows by F·dt/m per step.
  for (int64_t j = 1; j <= steps; ++j) {
    const Vec3 expected = v0 + (static_cast<double>(j) * dt() / mass) * wrench.force;
    EXPECT_LT(relativeError(velocityOf(history().body(k - 1 + j, "puck")) - v0, expected - v0),
              kTolerance)
        << "after " << j << " steps of the wrench";
  }
  // In all: F·T/m; and nothing after.
  const Vec3 total = velocityOf(history().body(k + steps - 1, "puck")) - v0;
  EXPECT_LT(relativeError(total, (wrench.duration / mass) * wrench.force), kTolerance);
  EXPECT_EQ(velocityOf(history().body(k + steps + 29, "puck")),
            velocityOf(history().body(k + steps - 1, "puck")))
      << "the wrench must stop after " << steps << " steps";
  // The world point (the centre of mass when the wrench first acted) moves
  // with the puck: no torque. A point left behind in the world would have
  // had a lever arm of −v t, and turned it.
  EXPECT_EQ(toVec3(history().body(k + steps + 29, "puck").angular_velocity), Vec3({0.0, 0.0, 0.0}));
}

// A world-frame force at a corner given in the body (point_frame BODY), on
// a turned box at rest: one step changes L by dt (R r_b) × F. From rest the
// body turns by about ½ α t² within the step, which changes the mean torque
// RK4 sees by a relative α dt²/6: the force is small enough (α ≈ 2.5e-4
// rad/s²) that this is 4e-11, well inside the tolerance.
TEST_F(WrenchPhysics, WorldForceAtABodyCornerChangesAngularMomentumByItsLeverMoment) {
  const auto& tilted = description("tilted");
  const int64_t start = currentStep();
  const auto& before = history().body(start, "tilted");
  const Mat3 rotation = rotationOf(before.orientation);

  client::Wrench wrench;
  wrench.body = "tilted";
  wrench.frame = client::Frame::World;
  wrench.pointFrame = client::Frame::Body;
  wrench.force = {2e-6, -3e-6, 8e-6};  // N, world
  wrench.point = {0.2, -0.1, 0.05};    // m, a corner, body frame
  const rbsim::ack_t ack = expectAccepted(client().applyWrench(wrench));
  EXPECT_EQ(ack.effective_step, start + 1);
  stepAndWait(3);

  const auto momentumAt = [&](int64_t step) {
    const auto& body = history().body(step, "tilted");
    return angularMomentum(body.orientation, tilted.inertia, body.angular_velocity);
  };
  const Vec3 lever = rotation * *wrench.point;
  const Vec3 expected = dt() * cross(lever, wrench.force);
  const Vec3 change = momentumAt(start + 1) - momentumAt(start);
  EXPECT_LT(relativeError(change, expected), kTolerance);
  EXPECT_LT(relativeError(velocityOf(history().body(start + 1, "tilted")),
                          (dt() / tilted.mass) * wrench.force),
            kTolerance);
  // Neither the unturned corner nor the same numbers read as a world point.
  EXPECT_GT(relativeError(change, dt() * cross(*wrench.point, wrench.force)), 0.1);
  const Vec3 asWorldPoint = *wrench.point - toVec3(before.position);
  EXPECT_GT(relativeError(change, dt() * cross(asWorldPoint, wrench.force)), 0.1);
  // One step only: torque-free afterwards.
  EXPECT_LT(relativeError(momentumAt(start + 3), momentumAt(start + 1)), 1e-12);
}

TEST_F(WrenchPhysics, PureTorqueChangesAngularMomentumByTauT) {
  const auto& spinner = description("spinner");
  const int64_t start = currentStep();
  const auto momentumAt = [&](int64_t step) {
    const auto& body = history().body(step, "spinner");
    return angularMomentum(body.orientation, spinner.inertia, body.angular_velocity);
  };

  client::Wrench wrench;
  wrench.body = "spinner";
  wrench.torque = {0.3, -0.2, 0.25};
  wrench.point = toVec3(history().body(start, "spinner").position);
  wrench.mode = client::WrenchMode::Duration;
  wrench.duration = 0.04;
  const int64_t steps = 40;
  const rbsim::ack_t ack = expectAccepted(client().applyWrench(wrench));
  stepAndWait(steps + 20);
  const int64_t k = ack.effective_step;

  // Torque-free before: L is constant although ω and the orientation change.
  const Vec3 l0 = momentumAt(start);
  EXPECT_LT(relativeError(momentumAt(k - 1), l0), 1e-12);
  // The first step of the wrench adds τ·dt.
  EXPECT_LT(relativeError(momentumAt(k) - l0, dt() * wrench.torque), kTolerance);
  // ΔL = I(q1) ω1 − I(q0) ω0 = τ·T.
  EXPECT_LT(relativeError(momentumAt(k + steps - 1) - l0, wrench.duration * wrench.torque),
            kTolerance);
  // Torque-free again afterwards: L stays while ω and q change (an
  // asymmetric top; were ω constant, L = I ω would check less).
  EXPECT_LT(relativeError(momentumAt(k + steps + 19), momentumAt(k + steps - 1)), 1e-12);
  EXPECT_GT(relativeError(toVec3(history().body(k + steps + 19, "spinner").angular_velocity),
                          toVec3(history().body(k + steps - 1, "spinner").angular_velocity)),
            1e-6);
  // A pure couple does not move the centre of mass.
  EXPECT_EQ(velocityOf(history().body(k + steps + 19, "spinner")), Vec3({0.0, 0.0, 0.0}));
}

TEST_F(WrenchPhysics, BodyFrameForceActsAlongTheRotatedAxis) {
  const double mass = description("tilted").mass;
  const int64_t start = currentStep();
  const auto& before = history().body(start, "tilted");
  const Mat3 rotation = rotationOf(before.orientation);

  client::Wrench wrench;
  wrench.body = "tilted";
  wrench.frame = client::Frame::Body;
  wrench.force = {0.8, -0.4, 0.3};  // body axes
  wrench.point = {0.0, 0.0, 0.0};   // the centre of mass
  wrench.mode = client::WrenchMode::Duration;
  wrench.duration = 0.02;
  const rbsim::ack_t ack = expectAccepted(client().applyWrench(wrench));
  EXPECT_EQ(ack.effective_step, start + 1);
  stepAndWait(30);

  const Vec3 worldForce = rotation * wrench.force;
  ASSERT_GT(relativeError(worldForce, wrench.force), 0.5) << "the body should be turned";
  const auto& after = history().body(start + 30, "tilted");
  EXPECT_EQ(velocityOf(history().body(start, "tilted")), Vec3({0.0, 0.0, 0.0}));
  EXPECT_LT(relativeError(velocityOf(after), (wrench.duration / mass) * worldForce), kTolerance);
  // Through the centre of mass: no rotation starts.
  EXPECT_EQ(toVec3(after.angular_velocity), Vec3({0.0, 0.0, 0.0}));
}

}  // namespace
}  // namespace rbsim::e2e
