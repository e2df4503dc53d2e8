#include "rbsim/physics/rotation_drift.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "physics/body/integrator.h"

namespace rbsim {

namespace {

double rotationalEnergy(const RigidState& state, const Mat3& rotation,
                        const BodyDynamics& dynamics) {
  return 0.5 * state.angularMomentum.dot(angularVelocityFrom(rotation, dynamics.inverseInertiaBody,
                                                             state.angularMomentum));
}

}  // namespace

std::vector<RotationDriftWarning> rotationDriftWarnings(const World& world, double horizon,
                                                        double threshold) {
  std::vector<RotationDriftWarning> warnings;
  const WorldSettings& settings = world.settings();
  // RK4 follows the rotation (its error is of fifth order per step); both
  // Euler methods take the same orientation update for a torque-free body.
  if (settings.integrator == IntegratorKind::Rk4 || !(horizon > 0.0)) return warnings;
  const char* method =
      settings.integrator == IntegratorKind::ExplicitEuler ? "explicit Euler" : "semi-implicit Euler";
  const double dt = settings.dt;
  constexpr double kMaxSteps = 1e7;  // per body: a horizon beyond it is checked up to it
  const auto steps = static_cast<long>(std::min(std::ceil(horizon / dt), kMaxSteps));
  for (const BodyView body : world.bodies()) {
    if (body.isStatic() || body.isSleeping() || body.isFrozen()) continue;
    BodyDynamics dynamics = body.dynamics();
    dynamics.linearDamping = dynamics.angularDamping = 0.0;  // damping only takes energy out
    RigidState state = body.state();
    state.linearMomentum.setZero();
    const double energy = rotationalEnergy(state, body.rotation(), dynamics);
    if (!(energy > 0.0)) continue;
    const double ceiling = state.angularMomentum.squaredNorm() *
                               dynamics.inverseInertiaBody.maxCoeff() / (2.0 * energy) -
                           1.0;
    if (!(ceiling > threshold)) continue;
    // Its own torque-free rotation, as the world's integrator takes it.
    Mat3 rotation = body.rotation();
    long crossed = -1;
    for (long i = 1; i <= steps; ++i) {
      state = integrateStep(settings.integrator, state, rotation, dynamics, ForceInputs{}, dt);
      rotation = state.orientation.toRotationMatrix();
      if (rotationalEnergy(state, rotation, dynamics) > (1.0 + threshold) * energy) {
        crossed = i;
        break;
      }
    }
    if (crossed < 0) continue;
    RotationDriftWarning warning;
    warning.body = body.name();
    warning.angularSpeed = body.angularVelocity().norm();
    warning.thresholdTime = static_cast<double>(crossed) * dt;
    warning.energyCeiling = ceiling;
    warning.suggestedStep = dt * warning.thresholdTime / horizon;
    char text[640];
    std::snprintf(
        text, sizeof text,
        "body '%s' spins at |w| = %.4g rad/s: %s at dt = %.4g s makes its "
        "rotational energy grow by %.3g%% within %.4g s (the horizon is %.4g s), and on up to "
        "+%.3g%% (all of its angular momentum about its axis of least inertia); use "
        "world.integrator: rk4, or dt below about %.2g s",
        warning.body.c_str(), warning.angularSpeed, method, dt, 100.0 * threshold, warning.thresholdTime,
        horizon, 100.0 * ceiling, warning.suggestedStep);
    warning.message = text;
    warnings.push_back(std::move(warning));
  }
  return warnings;
}

}  // namespace rbsim
