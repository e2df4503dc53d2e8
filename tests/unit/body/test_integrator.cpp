// The integrators as pure functions, against closed forms: each scheme's own
// exact discrete solution for constant forces, the continuous one for RK4.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/body/integrator.h"

namespace rbsim {
namespace {

constexpr double kDt = 1e-3;

BodyDynamics isotropicBody(double mass, double moment) {
  BodyDynamics d;
  d.mass = mass;
  d.inverseMass = 1.0 / mass;
  d.inertiaBody = Vec3::Constant(moment);
  d.inverseInertiaBody = Vec3::Constant(1.0 / moment);
  return d;
}

RigidState run(IntegratorKind kind, RigidState state, const BodyDynamics& dynamics,
               const ForceInputs& inputs, int steps) {
  for (int i = 0; i < steps; ++i)
    state = integrateStep(kind, state, state.orientation.toRotationMatrix(), dynamics, inputs, kDt);
  return state;
}

class ConstantAcceleration : public ::testing::TestWithParam<IntegratorKind> {};

// x_n = x0 + v0 t + a dt² · {n(n-1)/2 explicit, n(n+1)/2 semi-implicit, n²/2 RK4}.
double discreteQuadraticFactor(IntegratorKind kind, double n) {
  switch (kind) {
    case IntegratorKind::ExplicitEuler:
      return n * (n - 1) / 2;
    case IntegratorKind::SemiImplicitEuler:
      return n * (n + 1) / 2;
    case IntegratorKind::Rk4:
      return n * n / 2;  // exact for a quadratic
  }
  return 0;
}

TEST_P(ConstantAcceleration, FreeFallMatchesTheSchemesClosedForm) {
  const BodyDynamics body = isotropicBody(2.0, 0.1);
  RigidState start;
  start.position = Vec3(0.0, 0.0, 10.0);
  const Vec3 v0(1.0, -0.5, 2.0);
  start.linearMomentum = body.mass * v0;
  ForceInputs inputs;
  inputs.gravity = Vec3(0.0, 0.0, -9.81);
  const int n = 1500;
  const RigidState end = run(GetParam(), start, body, inputs, n);
  const double t = n * kDt;
  const Vec3 expectedPosition =
      start.position + v0 * t + inputs.gravity * kDt * kDt * discreteQuadraticFactor(GetParam(), n);
  EXPECT_LT((end.position - expectedPosition).norm(), 1e-11);
  EXPECT_LT((end.linearMomentum - body.mass * (v0 + inputs.gravity * t)).norm(), 1e-11);
  // And every scheme converges to the continuous ½ g t² within O(dt).
  const Vec3 continuous = start.position + v0 * t + 0.5 * inputs.gravity * t * t;
  EXPECT_LT((end.position - continuous).norm(), 0.5 * 9.81 * t * kDt * 1.01);
  EXPECT_EQ(end.angularMomentum, Vec3::Zero());
}

TEST_P(ConstantAcceleration, ConstantWorldForceThroughCentre) {
  const BodyDynamics body = isotropicBody(4.0, 0.3);
  ExternalLoad load;
  const Vec3 force(3.0, -1.0, 0.5);
  load.addWorldWrench(force, Vec3::Zero(), Vec3::Zero());
  ForceInputs inputs;
  inputs.load = &load;
  const int n = 800;
  const RigidState end = run(GetParam(), RigidState{}, body, inputs, n);
  const Vec3 a = force / body.mass;
  EXPECT_LT((end.position - a * kDt * kDt * discreteQuadraticFactor(GetParam(), n)).norm(), 1e-12);
  EXPECT_LT((end.linearMomentum - force * n * kDt).norm(), 1e-12);
  EXPECT_LT(end.angularMomentum.norm(), 1e-15);  // the force acts through the centre of mass
}

TEST_P(ConstantAcceleration, ConstantTorqueOnIsotropicBodyTurnsAboutAFixedAxis) {
  const double moment = 0.5;
  const BodyDynamics body = isotropicBody(1.0, moment);
  const Vec3 torque(0.0, 0.0, 0.2);
  ExternalLoad load;
  load.addWorldWrench(Vec3::Zero(), torque, Vec3::Zero());
  ForceInputs inputs;
  inputs.load = &load;
  const int n = 2000;
  const RigidState end = run(GetParam(), RigidState{}, body, inputs, n);
  EXPECT_LT((end.angularMomentum - torque * n * kDt).norm(), 1e-13);  // L = τ t
  // θ = ½ α t² for RK4; the Euler schemes sum the step rotations as above.
  const double alpha = torque.z() / moment;
  const double angle = alpha * kDt * kDt * discreteQuadraticFactor(GetParam(), n);
  const Quaternion expected = Quaternion::fromAxisAngle(Vec3::UnitZ(), angle);
  // Each Euler step turns by 2·atan(ω dt / 2) rather than ω dt: O((ω dt)³) per step.
  const double tolerance = GetParam() == IntegratorKind::Rk4 ? 1e-11 : 1e-8;
  EXPECT_NEAR(end.orientation.w, expected.w, tolerance);
  EXPECT_NEAR(end.orientation.z, expected.z, tolerance);
  EXPECT_NEAR(end.orientation.x, 0.0, 1e-15);
  EXPECT_NEAR(end.orientation.y, 0.0, 1e-15);
}

// Forces at off-centre points: test_wrench_frames.cpp.

TEST_P(ConstantAcceleration, BodyFrameForceActsAlongTheRotatedAxis) {
  const BodyDynamics body = isotropicBody(2.0, 1.0);
  RigidState start;
  start.orientation = Quaternion::fromAxisAngle(Vec3::UnitZ(), M_PI / 2);  // body x = world y
  ExternalLoad load;
  load.addBodyWrench(Vec3(5.0, 0.0, 0.0), Vec3::Zero(), Vec3::Zero());
  ForceInputs inputs;
  inputs.load = &load;
  const RigidState next =
      integrateStep(GetParam(), start, start.orientation.toRotationMatrix(), body, inputs, kDt);
  EXPECT_LT((next.linearMomentum - Vec3(0.0, 5.0 * kDt, 0.0)).norm(), 1e-15);
}

TEST_P(ConstantAcceleration, DampingDecaysMomentum) {
  BodyDynamics body = isotropicBody(1.0, 1.0);
  body.linearDamping = 2.0;
  body.angularDamping = 0.5;
  RigidState start;
  start.linearMomentum = Vec3(1.0, 0.0, 0.0);
  start.angularMomentum = Vec3(0.0, 0.0, 1.0);
  const int n = 1000;
  const RigidState end = run(GetParam(), start, body, ForceInputs{}, n);
  // Closed forms of each scheme for dP/dt = -c P.
  const auto decay = [&](double c) {
    switch (GetParam()) {
      case IntegratorKind::ExplicitEuler:
        return std::pow(1.0 - c * kDt, n);
      case IntegratorKind::SemiImplicitEuler:
        return std::pow(1.0 / (1.0 + c * kDt), n);
      case IntegratorKind::Rk4:
        return std::exp(-c * n * kDt);
    }
    return 0.0;
  };
  EXPECT_NEAR(end.linearMomentum.x(), decay(2.0), 1e-12);
  EXPECT_NEAR(end.angularMomentum.z(), decay(0.5), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, ConstantAcceleration,
                         ::testing::Values(IntegratorKind::ExplicitEuler,
                                           IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4),
                         [](const auto& testParam) { return std::string(integratorName(testParam.param)); });

}  // namespace
}  // namespace rbsim
