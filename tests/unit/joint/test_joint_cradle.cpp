// Newton's cradle: five equal balls, each hung from the world by a hinge on
// a massless rod, in a row. The first is released from an angle; with e = 1
// and equal pendulums each collision exchanges the two balls' velocities
// (the contact point is at the height of the centres, on the rods'
// tangent), so the momentum runs along the row and the last ball leaves
// with the speed the first one arrived with, the three between staying still.
// The balls touch (gap 0) or hang a little apart, as real cradles are
// adjusted; a gap shorter than a step's travel closes within the step.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::hinge;
using testing::kGravity;

constexpr double kRadius = 0.05;  // m
constexpr double kMass = 0.2;     // kg
constexpr double kRod = 0.5;      // m, pivot to ball centre
constexpr double kPivotZ = 1.0;   // m
constexpr int kBalls = 5;

struct Cradle {
  World world;
  std::vector<BodyId> balls;
};

// Balls `gap` apart (m) at rest, hinged about y; the first pulled back by
// `release` (rad) towards −x.
Cradle makeCradle(IntegratorKind integrator, double dt, double gap, double release) {
  WorldSettings settings = testing::jointWorldSettings(integrator, dt);
  settings.contact.defaultMaterial.restitution = 1.0;
  settings.contact.defaultMaterial.friction = 0.0;
  Cradle cradle{World(settings), {}};
  for (int i = 0; i < kBalls; ++i) {
    const double x = i * (2.0 * kRadius + gap);
    const double angle = i == 0 ? release : 0.0;
    const Vec3 pivot(x, 0.0, kPivotZ);
    const Vec3 hanging(x - kRod * std::sin(angle), 0.0, kPivotZ - kRod * std::cos(angle));
    const BodyId ball =
        addBody(cradle.world, "ball" + std::to_string(i), SphereShape{kRadius}, kMass, hanging);
    addJoint(cradle.world, hinge("rod" + std::to_string(i), BodyId{}, ball, pivot, Vec3::UnitY()));
    cradle.balls.push_back(ball);
  }
  return cradle;
}

// The first ball's speed at the bottom: a physical pendulum (the ball turns
// with its rod), ½ I_pivot ω² = m g L (1 − cos θ0), I_pivot = m L² + 2/5 m r².
double arrivalSpeed(double release) {
  const double pivotInertia = kMass * kRod * kRod + 0.4 * kMass * kRadius * kRadius;
  const double omega = std::sqrt(2.0 * kMass * kGravity * kRod * (1.0 - std::cos(release)) / pivotInertia);
  return omega * kRod;
}

TEST(JointCradle, TheLastBallLeavesWithTheFirstBallsSpeedAndTheMiddleStaysStill) {
  const double release = 0.5;  // rad
  const double arrival = arrivalSpeed(release);
  for (const IntegratorKind integrator :
       {IntegratorKind::SemiImplicitEuler, IntegratorKind::ExplicitEuler, IntegratorKind::Rk4}) {
    for (const double gap : {0.0, 1e-4}) {
      for (const double dt : {1e-3, 5e-4}) {
        SCOPED_TRACE("integrator " + std::string(integratorName(integrator)) + ", gap " +
                     std::to_string(gap) + " m, dt " + std::to_string(dt) + " s");
        Cradle cradle = makeCradle(integrator, dt, gap, release);
        // Until the last ball has swung out and come back to the row: a
        // quarter period and a half (T ≈ 1.42 s for these pendulums).
        double lastMax = 0.0, middleMax = 0.0;
        for (int s = 0; s < static_cast<int>(0.9 / dt); ++s) {
          cradle.world.step();
          lastMax = std::max(lastMax, cradle.world.body(cradle.balls.back()).linearVelocity().norm());
          for (int i = 1; i + 1 < kBalls; ++i)
            middleMax = std::max(middleMax, cradle.world.body(cradle.balls[i]).linearVelocity().norm());
        }
        EXPECT_NEAR(lastMax / arrival, 1.0, 1e-3);
        // What the middle keeps: a swing of the last few micrometres a
        // collision left them off their rest (a simultaneous solve of the
        // row would send them off at 2/5 of the speed).
        EXPECT_LT(middleMax, 1e-2 * arrival);
      }
    }
  }
}

// With gaps a few steps' travel long, the collisions come one per step or
// slower, each between two balls only.
TEST(JointCradle, BallsHungApartPassTheMomentumOneCollisionAtATime) {
  const double release = 0.5;
  const double arrival = arrivalSpeed(release);
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE("dt " + std::to_string(dt) + " s");
    Cradle cradle = makeCradle(IntegratorKind::SemiImplicitEuler, dt, 1e-3, release);
    double lastMax = 0.0;
    for (int s = 0; s < static_cast<int>(0.9 / dt); ++s) {
      cradle.world.step();
      lastMax = std::max(lastMax, cradle.world.body(cradle.balls.back()).linearVelocity().norm());
    }
    EXPECT_NEAR(lastMax / arrival, 1.0, 1e-3);
    // The first four stop where they hit, up to a gap's travel before
    // their rest: a swing of at most a millimetre, ω·1 mm ≈ 4 mm/s.
    for (int i = 0; i + 1 < kBalls; ++i)
      EXPECT_LT(cradle.world.body(cradle.balls[i]).linearVelocity().norm(), 1e-2 * arrival) << "ball " << i;
  }
}

}  // namespace
}  // namespace rbsim
