// The explicit-Euler rotation warning: the drift it predicts against the
// closed form for a symmetric top, and when it is (not) given.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rbsim/physics/rotation_drift.h"
#include "support/torque_free_world.h"

namespace rbsim {
namespace {

// A 1 kg disc (r = 5 cm, 4 cm thick: A = 7.58e-4, C = 1.25e-3 kg·m²)
// spinning at `speed` about an axis tilted by `tilt` from its symmetry axis:
// it nutates, torque-free.
World spinningDisc(IntegratorKind integrator, double dt, double speed, double tilt) {
  BodyDef def;
  def.name = "top";
  def.shape = CylinderShape{0.05, 0.02};
  def.mass = 1.0;
  def.angularVelocity = speed * Vec3(std::sin(tilt), 0.0, std::cos(tilt));
  return testing::torqueFreeWorld(def, integrator, dt);
}

// The symmetric top under explicit Euler (rotation_drift.h): x = |L⊥|² grows
// logistically, x' = λ x (1 − x/|L|²), λ = dt |L|² (1/A − 1/C)/A, and
// E = ½ (x/A + (|L|² − x)/C). Returns the time at which E has grown by the
// fraction g: x = x₀ + 2 g E₀ / (1/A − 1/C), t = ln(x (|L|² − x₀) / (x₀ (|L|² − x))) / λ.
double logisticTime(double dt, double speed, double tilt, double g) {
  const double a = (3.0 * 0.05 * 0.05 + 0.04 * 0.04) / 12.0, c = 0.5 * 0.05 * 0.05;
  const double l3 = c * speed * std::cos(tilt), lt = a * speed * std::sin(tilt);
  const double l2 = l3 * l3 + lt * lt, x0 = lt * lt;
  const double lambda = dt * l2 * (1.0 / a - 1.0 / c) / a;
  const double energy = 0.5 * (x0 / a + (l2 - x0) / c);
  const double x = x0 + 2.0 * g * energy / (1.0 / a - 1.0 / c);
  return std::log(x * (l2 - x0) / (x0 * (l2 - x))) / lambda;
}

TEST(RotationDrift, ExplicitEulerGrowsATopsEnergyLogisticallyUpToTheCeiling) {
  for (const double dt : {1e-3, 5e-4}) {
    for (const double tilt : {0.02, 0.05}) {
      World world = spinningDisc(IntegratorKind::ExplicitEuler, dt, 188.0, tilt);
      const double energy = world.totalKineticEnergy();
      const auto warnings = rotationDriftWarnings(world, 10.0);
      ASSERT_EQ(warnings.size(), 1u);
      const double ceiling = warnings[0].energyCeiling;
      // The times at which the energy has grown by 1% (the warning's) and by
      // a quarter, half and three quarters of the ceiling, against the
      // closed form. It is the leading order in θ = |ω| dt (≤ 0.19 here):
      // its rate is good to O(θ²), so the times to 3 θ².
      const double theta = 188.0 * dt, tolerance = 3.0 * theta * theta;
      EXPECT_NEAR(warnings[0].thresholdTime / logisticTime(dt, 188.0, tilt, 0.01), 1.0, tolerance)
          << "dt " << dt << " tilt " << tilt;
      double nextLevel = 0.25;
      for (int i = 1; i <= static_cast<int>(std::lround(1.0 / dt)); ++i) {
        world.step();
        const double growth = world.totalKineticEnergy() / energy - 1.0;
        if (nextLevel < 1.0 && growth > nextLevel * ceiling) {
          EXPECT_NEAR(world.time() / logisticTime(dt, 188.0, tilt, nextLevel * ceiling), 1.0,
                      tolerance)
              << "dt " << dt << " tilt " << tilt << " level " << nextLevel;
          nextLevel += 0.25;
        }
      }
      EXPECT_GE(nextLevel, 1.0);
      const double final = world.totalKineticEnergy() / energy - 1.0;
      EXPECT_NEAR(final, ceiling, 1e-3 * ceiling) << "saturated at |L|²/(2 I_min)";
    }
  }
}

TEST(RotationDrift, WarnsForAFastTopWithEitherEulerMethodButNotRk4) {
  const World top = spinningDisc(IntegratorKind::ExplicitEuler, 1e-3, 188.0, 0.05);
  const auto warnings = rotationDriftWarnings(top, 10.0);
  ASSERT_EQ(warnings.size(), 1u);
  const RotationDriftWarning& w = warnings[0];
  EXPECT_EQ(w.body, "top");
  EXPECT_NEAR(w.angularSpeed, 188.0, 1e-9);
  EXPECT_GT(w.thresholdTime, 0.0);
  EXPECT_LT(w.thresholdTime, 1.0);
  EXPECT_NE(w.message.find("body 'top'"), std::string::npos) << w.message;
  EXPECT_NE(w.message.find("rk4"), std::string::npos) << w.message;
  EXPECT_NE(w.message.find("explicit Euler"), std::string::npos) << w.message;
  // The threshold time scales as 1/dt, so the suggested dt reaches 1% near
  // the horizon: within ±20% of it.
  const World smaller = spinningDisc(IntegratorKind::ExplicitEuler, w.suggestedStep, 188.0, 0.05);
  EXPECT_TRUE(rotationDriftWarnings(smaller, 8.0).size() == 0u);
  EXPECT_TRUE(rotationDriftWarnings(smaller, 12.0).size() == 1u);

  // Semi-implicit Euler turns a torque-free body exactly as explicit Euler
  // does: the same warning, at the same time, under its own name.
  const auto semiImplicit =
      rotationDriftWarnings(spinningDisc(IntegratorKind::SemiImplicitEuler, 1e-3, 188.0, 0.05), 10.0);
  ASSERT_EQ(semiImplicit.size(), 1u);
  EXPECT_EQ(semiImplicit[0].thresholdTime, w.thresholdTime);
  EXPECT_NE(semiImplicit[0].message.find("semi-implicit Euler"), std::string::npos) << semiImplicit[0].message;
  EXPECT_TRUE(rotationDriftWarnings(spinningDisc(IntegratorKind::Rk4, 1e-3, 188.0, 0.05), 10.0).empty());
  // A spin about the symmetry axis (ω ∥ L) does not drift, at any speed.
  EXPECT_TRUE(
      rotationDriftWarnings(spinningDisc(IntegratorKind::ExplicitEuler, 1e-3, 1000.0, 0.0), 10.0)
          .empty());
  // A slow top: λ ∝ |ω|², 1% takes far longer than 10 s.
  EXPECT_TRUE(
      rotationDriftWarnings(spinningDisc(IntegratorKind::ExplicitEuler, 1e-3, 5.0, 0.05), 10.0)
          .empty());
  // A sphere has no axis of least inertia to drift to (ceiling 0).
  WorldSettings settings;
  settings.integrator = IntegratorKind::ExplicitEuler;
  World ball(settings);
  BodyDef def;
  def.name = "ball";
  def.shape = SphereShape{0.1};
  def.angularVelocity = Vec3(300, 200, 100);
  ASSERT_TRUE(ball.createBody(def).ok());
  EXPECT_TRUE(rotationDriftWarnings(ball, 10.0).empty());
}

}  // namespace
}  // namespace rbsim
