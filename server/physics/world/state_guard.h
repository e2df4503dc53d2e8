#pragma once
// The numerical guard's check (rbsim/physics/numerical_guard.h says what
// it does to a body that fails it).
//
// Cost: bodies that fly free are cleared inside the integration loop on the
// momenta the integrator just returned (speedBounds: two squared norms);
// the others (in contact, swept by continuous collision, or near a limit)
// are judged after the step. On bench_free_bodies (1000 bodies) that is
// under 1 ns of ~113 ns a body-step with semi-implicit Euler and ~4 ns of
// ~212 with RK4.

#include <cmath>

#include "rbsim/physics/rigid_state.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/numerical_guard.h"

namespace rbsim {

// The guard's test on the stepping path: true when the state is healthy.
// NaN or ±inf in P or L always reaches v = P/M or ω = I⁻¹L (an infinity times
// a zero of the rotation is NaN), and NaN compares false, so two squared
// speeds cover the momenta; the pose is finite when the sum of its seven
// numbers is (a sum of poses cannot overflow: |x| is nowhere near 1e308).
// Eleven additions and six multiplications, three comparisons, no square
// root. judgeState says why a state failed.
inline bool isHealthy(const RigidState& state, const Vec3& linearVelocity, const Vec3& angularVelocity,
                      double maxLinearSpeedSquared, double maxAngularSpeedSquared) {
  const Quaternion& q = state.orientation;
  const double pose = state.position.x() + state.position.y() + state.position.z() + q.w + q.x + q.y + q.z;
  return pose - pose == 0.0 && linearVelocity.squaredNorm() <= maxLinearSpeedSquared &&
         angularVelocity.squaredNorm() <= maxAngularSpeedSquared;
}

// The guard's test inside a free integration step, on the state the
// integrator returned, before it is stored and before the velocities are
// derived from it: both bounds within the squared limits means healthy for
// certain; otherwise "judge it properly" (judgeState, after the velocities
// are known).
// - Starting from a healthy state, the new pose is the old one moved by the
//   new (or stage) velocities, which are finite when the new momenta are: a
//   non-finite force leaves a NaN or an infinity in P or L, and NaN compares
//   false. So the momenta say it all.
// - |v| = |P| / M exactly; |ω| = |R I⁻¹ Rᵀ L| <= |L| max(I⁻¹), so a bound
//   within the limit proves ω is too. Only a body spinning near the limit
//   (or a long thin one spinning about its long axis at a tenth of it) is
//   judged the slow way.
// Two squared norms on values the integrator just produced: the step does
// not wait on the velocities' matrix products.
struct SpeedBounds {
  double squaredSpeed = 0.0;  // |v|², exact
  double squaredSpin = 0.0;   // >= |ω|²
};
inline SpeedBounds speedBounds(const RigidState& next, double inverseMass, const Vec3& inverseInertiaBody) {
  const double maxInverseInertia = inverseInertiaBody.maxCoeff();
  return {next.linearMomentum.squaredNorm() * (inverseMass * inverseMass),
          next.angularMomentum.squaredNorm() * (maxInverseInertia * maxInverseInertia)};
}

// Judges a state and its derived velocities (world frame) against the limits.
inline StateVerdict judgeState(const RigidState& state, const Vec3& linearVelocity,
                               const Vec3& angularVelocity, const StateLimits& limits) {
  // Eigen's allFinite is x − x == x − x per component: branch-free, and
  // false for NaN and ±inf alike.
  const bool finite = state.position.allFinite() && state.linearMomentum.allFinite() &&
                      state.angularMomentum.allFinite() && state.orientation.isFinite();
  if (!finite) return {FreezeReason::NonFiniteState, 0.0, 0.0};
  // Squared norms against squared limits: no square root on the healthy path.
  // "Not within" rather than "above", so an infinite velocity derived from
  // finite momenta (a degenerate inertia) is caught too.
  const double linear = linearVelocity.squaredNorm();
  const double angular = angularVelocity.squaredNorm();
  if (!(linear <= limits.maxLinearSpeed * limits.maxLinearSpeed))
    return {FreezeReason::LinearSpeed, std::sqrt(linear), limits.maxLinearSpeed};
  if (!(angular <= limits.maxAngularSpeed * limits.maxAngularSpeed))
    return {FreezeReason::AngularSpeed, std::sqrt(angular), limits.maxAngularSpeed};
  return {};
}

}  // namespace rbsim
