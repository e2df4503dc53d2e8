// Coulomb friction against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBox;
using testing::addGround;
using testing::addSphere;
using testing::contactSettings;

constexpr double kG = 9.81;

TEST(Friction, SlidingBoxStopsAfterVSquaredOverTwoMuG) {
  for (double mu : {0.3, 0.6}) {
    World world(contactSettings(0.0, mu));
    addGround(world);
    const double v0 = 2.0;
    const BodyId box =
        addBox(world, "box", Vec3(0.1, 0.1, 0.1), Vec3(0, 0, 0.1), Quaternion::identity(), Vec3(v0, 0, 0));
    for (int i = 0; i < 3000; ++i) world.step();
    const double distance = world.body(box).position().x();
    // Discretisation: the first step carries v0 dt before friction acts fully
    // and the stop is resolved to a step: v0 dt ≈ 2 mm.
    EXPECT_NEAR(distance, v0 * v0 / (2.0 * mu * kG), 0.003) << "mu " << mu;
    EXPECT_LT(world.body(box).linearVelocity().norm(), 1e-6);
    // No sideways force: only round-off-level asymmetry of the corner solve (nm).
    EXPECT_NEAR(world.body(box).position().y(), 0.0, 1e-6);
  }
}

// A box on an incline of angle θ (the ground plane tilted about y).
struct Incline {
  double displacement;  // m along the slope, downhill positive
  double time;          // s
};
Incline slide(double theta, double mu, int steps) {
  World world(contactSettings(0.0, mu));
  const Vec3 normal(std::sin(theta), 0.0, std::cos(theta));
  addGround(world, normal);
  const Quaternion q = Quaternion::fromAxisAngle(Vec3::UnitY(), theta);
  const BodyId box = addBox(world, "box", Vec3(0.1, 0.1, 0.1), 0.1 * normal, q);
  const Vec3 start = world.body(box).position();
  for (int i = 0; i < steps; ++i) world.step();
  // Downhill along the slope: the in-plane direction of gravity.
  const Vec3 downhill = Vec3(std::cos(theta), 0.0, -std::sin(theta));
  return {(world.body(box).position() - start).dot(downhill), world.time()};
}

TEST(Friction, BoxOnInclineSticksBelowTheFrictionAngle) {
  const double mu = 0.5;  // friction angle atan(0.5) = 26.6°
  for (double degrees : {10.0, 20.0, 25.0}) {
    const Incline r = slide(degrees * std::numbers::pi / 180.0, mu, 2000);
    EXPECT_LT(std::abs(r.displacement), 1e-4) << degrees << " degrees";
  }
}

TEST(Friction, BoxOnInclineSlidesWithGTimesSinMinusMuCos) {
  const double mu = 0.3;
  for (double degrees : {25.0, 40.0}) {
    const double theta = degrees * std::numbers::pi / 180.0;
    const Incline r = slide(theta, mu, 1000);
    const double a = kG * (std::sin(theta) - mu * std::cos(theta));
    // s = ½ a t² (the semi-implicit step adds a dt t/2 ≈ 0.1%).
    EXPECT_NEAR(r.displacement, 0.5 * a * r.time * r.time, 0.01 * 0.5 * a * r.time * r.time)
        << degrees << " degrees";
  }
}

TEST(Friction, SphereLaunchedWithoutSpinEndsRollingAtFiveSeventhsOfItsSpeed) {
  World world(contactSettings(0.0, 0.3));
  addGround(world);
  const double v0 = 2.0, radius = 0.1;
  const BodyId ball = addSphere(world, "ball", radius, Vec3(0, 0, radius), Vec3(v0, 0, 0));
  for (int i = 0; i < 2000; ++i) world.step();
  const BodyView b = world.body(ball);
  EXPECT_NEAR(b.linearVelocity().x(), 5.0 / 7.0 * v0, 0.002 * v0);
  // Rolling: the contact point is at rest, ω = v / r about +y.
  EXPECT_NEAR(b.angularVelocity().y() * radius, b.linearVelocity().x(), 1e-4);
}

}  // namespace
}  // namespace rbsim
