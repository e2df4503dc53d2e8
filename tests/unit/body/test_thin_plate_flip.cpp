// A free body whose inertia is given as data, Ibody = diag(1, 2, 3) kg·m²:
// a thin plate (I3 = I1 + I2), which no solid of the shape it collides as
// has. Spun about its intermediate axis with a small push about the major
// one, it flips over periodically (the intermediate-axis theorem); RK4 must
// keep |L| and T and put the flips where the closed form of the Euler
// equations does.
//
// The closed form (Landau & Lifshitz, Mechanics, §37), for I1 < I2 < I3,
// energy E and |L| = M with M² > 2 E I2:
//   ω1 = sqrt((2 E I3 − M²) / (I1 (I3 − I1))) cn τ
//   ω2 = sqrt((2 E I3 − M²) / (I2 (I3 − I2))) sn τ
//   ω3 = sqrt((M² − 2 E I1) / (I3 (I3 − I1))) dn τ
//   τ = λ t, λ = sqrt((I3 − I2)(M² − 2 E I1) / (I1 I2 I3)),
//   k² = (I2 − I1)(2 E I3 − M²) / ((I3 − I2)(M² − 2 E I1)),
// body-frame components, with the Jacobi elliptic functions of modulus k,
// whose period in τ is 4 K(k). Starting at ω = (0, a, b) is starting at
// τ = K (cn K = 0, sn K = 1, dn K = k'), so ω2 = sn changes sign at
// τ = 2K, 4K, ...: at t_n = (2n − 1) K / λ, every half period 2K/λ.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "rbsim/physics/world.h"
#include "support/torque_free_world.h"

namespace rbsim {
namespace {

const Vec3 kMoments(1.0, 2.0, 3.0);  // kg·m²

// K(k) = π / (2 AGM(1, k')) (Abramowitz & Stegun 17.6): the arithmetic-
// geometric mean converges quadratically, to the last bit in a few rounds.
double completeEllipticK(double kPrime) {
  double a = 1.0;
  double g = kPrime;
  for (int i = 0; i < 40 && std::abs(a - g) > 1e-16 * a; ++i) {
    const double mean = 0.5 * (a + g);
    g = std::sqrt(a * g);
    a = mean;
  }
  return std::numbers::pi / (2.0 * a);
}

struct ClosedForm {
  double lambda = 0.0;      // 1/s
  double kPrime = 0.0;      // complementary modulus sqrt(1 − k²)
  double k2 = 0.0;          // k²
  double amplitude2 = 0.0;  // rad/s, of ω2
  double firstFlip() const { return completeEllipticK(kPrime) / lambda; }         // s
  double halfPeriod() const { return 2.0 * completeEllipticK(kPrime) / lambda; }  // s
};

ClosedForm closedForm(const Vec3& omega) {
  const double i1 = kMoments.x(), i2 = kMoments.y(), i3 = kMoments.z();
  const Vec3 l = kMoments.cwiseProduct(omega);
  const double m2 = l.squaredNorm();
  const double twoE = omega.dot(l);
  ClosedForm f;
  f.lambda = std::sqrt((i3 - i2) * (m2 - twoE * i1) / (i1 * i2 * i3));
  f.k2 = (i2 - i1) * (twoE * i3 - m2) / ((i3 - i2) * (m2 - twoE * i1));
  f.kPrime = std::sqrt(1.0 - f.k2);
  f.amplitude2 = std::sqrt((twoE * i3 - m2) / (i2 * (i3 - i2)));
  return f;
}

World makePlate(IntegratorKind kind, double dt, const Vec3& omega) {
  BodyDef def;
  def.name = "plate";
  // A cube collides; the given mass properties are a plate's.
  def.shape = BoxShape{Vec3(0.5, 0.5, 0.5)};
  def.mass = 10.0;
  def.inertia = Mat3(kMoments.asDiagonal());
  def.angularVelocity = omega;  // the body frame starts aligned with the world
  return testing::torqueFreeWorld(def, kind, dt);
}

struct PlateRun {
  double worstMomentum = 0.0;  // relative change of |L|
  double worstEnergy = 0.0;    // relative change of T
  std::vector<double> flips;   // s, sign changes of body-frame ω2
};

PlateRun simulate(IntegratorKind kind, double dt, const Vec3& omega, double duration) {
  World world = makePlate(kind, dt, omega);
  const BodyView body = world.bodies()[0];
  const double momentum0 = body.angularMomentum().norm();
  const double energy0 = body.kineticEnergy();
  PlateRun run;
  const auto omega2 = [&]() { return (body.rotation().transpose() * body.angularVelocity()).y(); };
  double previous = omega2();
  const auto steps = static_cast<int>(std::lround(duration / dt));
  for (int i = 1; i <= steps; ++i) {
    world.step();
    run.worstMomentum = std::max(run.worstMomentum,
                                 std::abs(body.angularMomentum().norm() - momentum0) / momentum0);
    run.worstEnergy = std::max(run.worstEnergy, std::abs(body.kineticEnergy() - energy0) / energy0);
    const double now = omega2();
    // Linear interpolation between the steps (see flipTolerance).
    if ((previous > 0.0) != (now > 0.0))
      run.flips.push_back(dt * (i - 1 + previous / (previous - now)));
    previous = now;
  }
  return run;
}

// How far a flip time may be from the closed form. Near a zero,
// ω2 ≈ a s + c s³ (s = t − t_n) with c/a = −(1 + k²) λ² / 6, since sn has
// sn' = 1, sn'' = 0 and sn''' = −(1 + k²) there. The secant through the
// steps at s = −h1 and s = h2 (h1 + h2 = dt) puts the zero at
// (c/a) h1 h2 (h1 − h2), at most |c/a| dt³ / (6√3) away. Doubled to leave
// as much again for RK4's own phase error, which is O(dt⁴) (its energy
// error is ~1e-12 here).
double flipTolerance(const ClosedForm& f, double dt) {
  const double interpolation =
      (1.0 + f.k2) * f.lambda * f.lambda / 6.0 * dt * dt * dt / (6.0 * std::sqrt(3.0));
  return 2.0 * interpolation;
}

TEST(ThinPlate, ClosedFormStartsAtTheInitialSpin) {
  // The formulas themselves: at τ = K they give back ω = (0, a, b).
  const Vec3 omega(0.0, 4.0, 0.2);
  const ClosedForm f = closedForm(omega);
  EXPECT_NEAR(f.amplitude2, omega.y(), 1e-14);
  const double i1 = kMoments.x(), i3 = kMoments.z();
  const Vec3 l = kMoments.cwiseProduct(omega);
  const double amplitude3 = std::sqrt((l.squaredNorm() - omega.dot(l) * i1) / (i3 * (i3 - i1)));
  EXPECT_NEAR(amplitude3 * f.kPrime, omega.z(), 1e-14);
  // K(0) = π/2 and K(k' = 1/√2) = Γ(1/4)² / (4 √π) (A&S 17.3.11 with k² = 1/2).
  EXPECT_NEAR(completeEllipticK(1.0), std::numbers::pi / 2.0, 1e-15);
  EXPECT_NEAR(completeEllipticK(std::sqrt(0.5)),
              std::tgamma(0.25) * std::tgamma(0.25) / (4.0 * std::sqrt(std::numbers::pi)), 1e-15);
}

class ThinPlateRk4 : public ::testing::TestWithParam<double> {};

TEST_P(ThinPlateRk4, ConservesMomentumAndEnergyAndFlipsOnTime) {
  const double dt = GetParam();
  const Vec3 omega(0.0, 4.0,
                   0.2);  // rad/s: about the intermediate axis, a push about the major one
  const ClosedForm f = closedForm(omega);
  const PlateRun run = simulate(IntegratorKind::Rk4, dt, omega, 10.0);
  EXPECT_LT(run.worstMomentum, 1e-11);
  EXPECT_LT(run.worstEnergy, 1e-11);
  std::vector<double> expected;
  for (double t = f.firstFlip(); t < 10.0; t += f.halfPeriod()) expected.push_back(t);
  ASSERT_GE(expected.size(), 2u);
  ASSERT_EQ(run.flips.size(), expected.size());
  for (std::size_t n = 0; n < expected.size(); ++n) {
    std::printf(
        "dt %g s: flip %zu at %.12f s, closed form %.12f s, error %.3g s (tolerance %.3g s)\n", dt,
        n, run.flips[n], expected[n], run.flips[n] - expected[n], flipTolerance(f, dt));
    EXPECT_NEAR(run.flips[n], expected[n], flipTolerance(f, dt)) << "flip " << n;
  }
  std::printf("dt %g s: worst relative change of |L| %.3g, of T %.3g\n", dt, run.worstMomentum,
              run.worstEnergy);
}

INSTANTIATE_TEST_SUITE_P(TwoSteps, ThinPlateRk4, ::testing::Values(1e-3, 5e-4),
                         [](const auto& testParam) {
                           return testParam.param == 1e-3 ? "dt_1ms" : "dt_0_5ms";
                         });

// The Euler integrators are first order and lose energy to their error
// (1.6 % over 10 s at 1 ms), which near the separatrix moves the later flips
// by seconds; the first flip still converges to the closed form at first
// order, its error halving with dt (a body frame or tensor off by anything
// would leave an error that does not vanish). |L| is the state they
// integrate and there is no torque: it does not change at all. (Without
// torque the two Euler methods take the same steps.)
class ThinPlateEuler : public ::testing::TestWithParam<IntegratorKind> {};

TEST_P(ThinPlateEuler, FirstFlipConvergesAtFirstOrder) {
  const Vec3 omega(0.0, 4.0, 0.2);
  const ClosedForm f = closedForm(omega);
  double previousError = 0.0;
  for (const double dt : {1e-3, 5e-4, 2.5e-4}) {
    const PlateRun run = simulate(GetParam(), dt, omega, 2.5);
    EXPECT_EQ(run.worstMomentum, 0.0);
    ASSERT_EQ(run.flips.size(), 1u) << "dt " << dt;
    const double error = std::abs(run.flips[0] - f.firstFlip());
    std::printf("%s dt %g s: first flip %.9f s, closed form %.9f s, error %.3g s\n",
                std::string(integratorName(GetParam())).c_str(), dt, run.flips[0], f.firstFlip(),
                error);
    if (previousError > 0.0) {
      EXPECT_GT(error / previousError, 0.45) << "dt " << dt;
      EXPECT_LT(error / previousError, 0.55) << "dt " << dt;
    }
    previousError = error;
  }
}

INSTANTIATE_TEST_SUITE_P(FirstOrder, ThinPlateEuler,
                         ::testing::Values(IntegratorKind::ExplicitEuler,
                                           IntegratorKind::SemiImplicitEuler),
                         [](const auto& testParam) {
                           return std::string(integratorName(testParam.param));
                         });

}  // namespace
}  // namespace rbsim
