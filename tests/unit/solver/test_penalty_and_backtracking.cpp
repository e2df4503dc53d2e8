// The alternatives to the impulse model: penalty forces and
// backtracking to the time of collision (both in Baraff, "Rigid Body
// Simulation", SIGGRAPH course notes).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

using testing::addGround;
using testing::addSphere;
using testing::contactSettings;

constexpr double kG = 9.81;

TEST(Penalty, RestingBodySinksByMgOverK) {
  for (double k : {1e5, 4e5}) {
    WorldSettings settings = contactSettings(0.0, 0.5);
    settings.contact.model = ContactModel::Penalty;
    settings.contact.penaltyStiffness = k;
    settings.contact.penaltyDamping = 2.0 * std::sqrt(k * 4.19);  // critically damped: settles fast
    World world(settings);
    addGround(world);
    const BodyId ball = addSphere(world, "ball", 0.1, Vec3(0, 0, 0.1));
    for (int i = 0; i < 3000; ++i) world.step();
    const double sink = 0.1 - world.body(ball).position().z();
    const double expected = world.body(ball).mass() * kG / k;
    EXPECT_NEAR(sink, expected, 0.01 * expected) << "k " << k;
  }
}

TEST(Penalty, BounceLosesTheEnergyTheDampingSays) {
  // A linear spring–dashpot that never pulls (the force is clamped at zero)
  // returns the ball with e = exp(−ζ/√(1−ζ²) (π − atan(2ζ√(1−ζ²)/(1−2ζ²))))
  // (Schwager and Pöschel 2007), ζ = c / (2 √(k m)).
  const double k = 1e4, zeta = 0.1;
  WorldSettings settings = contactSettings(0.0, 0.0);
  settings.gravity = Vec3::Zero();
  settings.contact.model = ContactModel::Penalty;
  settings.contact.penaltyStiffness = k;
  const double mass = 1000.0 * 4.0 / 3.0 * std::numbers::pi * 0.001;  // sphere r = 0.1 m, water
  settings.contact.penaltyDamping = 2.0 * zeta * std::sqrt(k * mass);
  World damped(settings);
  addGround(damped);
  const BodyId b = addSphere(damped, "ball", 0.1, Vec3(0, 0, 0.2), Vec3(0, 0, -1.0));
  for (int i = 0; i < 1000; ++i) damped.step();
  const double s = std::sqrt(1.0 - zeta * zeta);
  const double e = std::exp(-zeta / s * (std::numbers::pi - std::atan(2.0 * zeta * s / (1.0 - 2.0 * zeta * zeta))));
  // Semi-implicit Euler over a contact of ~64 steps: O((ω dt)²) ≈ 0.3%.
  EXPECT_NEAR(damped.body(b).linearVelocity().z(), e * 1.0, 0.015 * e);
  EXPECT_GT(damped.body(b).position().z(), 0.1);  // it left the ground
}

double apexAfterFirstBounce(bool backtracking, double e, double& deepestAtStepEnd) {
  WorldSettings settings = contactSettings(e, 0.5);
  settings.contact.backtracking = backtracking;
  World world(settings);
  addGround(world);
  const double radius = 0.1, h0 = 1.0;
  const BodyId ball = addSphere(world, "ball", radius, Vec3(0, 0, radius + h0));
  double previous = 0.0;
  deepestAtStepEnd = -1.0;
  for (int i = 0; i < 5000; ++i) {
    world.step();
    const double bottom = world.body(ball).position().z() - radius;
    deepestAtStepEnd = std::max(deepestAtStepEnd, -bottom);
    const double v = world.body(ball).linearVelocity().z();
    if (previous > 0.0 && v <= 0.0) return bottom;
    previous = v;
  }
  return -1.0;
}

TEST(Backtracking, GivesTheSameBounceAsTheImpulseModelAndNeverOverlaps) {
  for (double e : {0.8, 0.5}) {
    double impulseDepth = 0.0, backtrackingDepth = 0.0;
    const double impulse = apexAfterFirstBounce(false, e, impulseDepth);
    const double backtracked = apexAfterFirstBounce(true, e, backtrackingDepth);
    ASSERT_GT(impulse, 0.0);
    ASSERT_GT(backtracked, 0.0);
    // Both within the discretisation of the impulse model's early bounce (v dt).
    EXPECT_NEAR(backtracked, impulse, 0.01) << "e " << e;
    EXPECT_NEAR(backtracked, e * e * 1.0, 0.01) << "e " << e;
    EXPECT_LE(backtrackingDepth, 1e-9) << "the ball never ends a step inside the ground";
  }
}

}  // namespace
}  // namespace rbsim
