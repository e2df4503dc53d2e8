#include "physics/body/integrator.h"

#include <cmath>

namespace rbsim {

StateRate stateRate(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                    const ForceInputs& inputs) {
  const NetWrench wrench = evaluateWrench(state, rotation, dynamics, inputs, true);
  const Vec3 omega = angularVelocityFrom(rotation, dynamics.inverseInertiaBody, state.angularMomentum);
  return {state.linearMomentum * dynamics.inverseMass, orientationRate(state.orientation, omega),
          wrench.force, wrench.torque};
}

RigidState advanceState(const RigidState& state, const StateRate& rate, double h) {
  return {state.position + h * rate.velocity, addScaled(state.orientation, rate.spin, h),
          state.linearMomentum + h * rate.force, state.angularMomentum + h * rate.torque};
}

RigidState rk4Combine(const RigidState& state, const StateRate& k1, const StateRate& k2,
                      const StateRate& k3, const StateRate& k4, double dt) {
  const double h6 = dt / 6.0;
  RigidState next;
  next.position =
      state.position + h6 * (k1.velocity + 2.0 * k2.velocity + 2.0 * k3.velocity + k4.velocity);
  next.linearMomentum =
      state.linearMomentum + h6 * (k1.force + 2.0 * k2.force + 2.0 * k3.force + k4.force);
  next.angularMomentum =
      state.angularMomentum + h6 * (k1.torque + 2.0 * k2.torque + 2.0 * k3.torque + k4.torque);
  Quaternion q = state.orientation;
  q = addScaled(q, k1.spin, h6);
  q = addScaled(q, k2.spin, 2.0 * h6);
  q = addScaled(q, k3.spin, 2.0 * h6);
  q = addScaled(q, k4.spin, h6);
  next.orientation = q.normalized();
  return next;
}

NetWrench evaluateWrench(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                      const ForceInputs& inputs, bool includeDamping) {
  NetWrench wrench;
  wrench.force = dynamics.mass * inputs.gravity;
  if (inputs.load != nullptr && inputs.load->active) {
    const Vec3 external = inputs.load->forceAt(rotation);
    wrench.force += external;
    wrench.torque += inputs.load->torqueAt(rotation);
  }
  if (includeDamping) {
    wrench.force -= dynamics.linearDamping * state.linearMomentum;
    wrench.torque -= dynamics.angularDamping * state.angularMomentum;
  }
  return wrench;
}

RigidState explicitEulerStep(const RigidState& state, const Mat3& rotation,
                             const BodyDynamics& dynamics, const ForceInputs& inputs, double dt) {
  RigidState next = advanceState(state, stateRate(state, rotation, dynamics, inputs), dt);
  next.orientation = next.orientation.normalized();
  return next;
}

namespace {

// The halves of semi-implicit Euler, with internal linkage so that the
// free-body step inlines them (the free loop runs this for every body).
[[gnu::always_inline]] inline Momenta momentaAfterForces(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                           const ForceInputs& inputs, double dt) {
  const NetWrench wrench = evaluateWrench(state, rotation, dynamics, inputs, false);
  Momenta next{state.linearMomentum + dt * wrench.force, state.angularMomentum + dt * wrench.torque};
  // Implicit (backward Euler) damping: P' = P* − c dt P'. Skipped when zero so
  // that undamped bodies pay no division.
  if (dynamics.linearDamping != 0.0) next.linear /= 1.0 + dt * dynamics.linearDamping;
  if (dynamics.angularDamping != 0.0) next.angular /= 1.0 + dt * dynamics.angularDamping;
  return next;
}

}  // namespace

Momenta integrateMomenta(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                         const ForceInputs& inputs, double dt) {
  return momentaAfterForces(state, rotation, dynamics, inputs, dt);
}

Momenta firstHalfKick(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                      const ForceInputs& inputs, double h) {
  const NetWrench wrench = evaluateWrench(state, rotation, dynamics, inputs, false);
  const double dt = 0.5 * h;
  Momenta next{state.linearMomentum + dt * wrench.force, state.angularMomentum + dt * wrench.torque};
  // 1 − e^(−x) (1 + x/2), x = c h, without cancellation for small x.
  const auto share = [h](double c) {
    const double x = c * h;
    return -std::expm1(-x) - 0.5 * x * std::exp(-x);
  };
  if (dynamics.linearDamping != 0.0) next.linear -= share(dynamics.linearDamping) * state.linearMomentum;
  if (dynamics.angularDamping != 0.0) next.angular -= share(dynamics.angularDamping) * state.angularMomentum;
  return next;
}

RigidState semiImplicitEulerStep(const RigidState& state, const Mat3& rotation,
                                 const BodyDynamics& dynamics, const ForceInputs& inputs,
                                 double dt) {
  const Momenta momenta = momentaAfterForces(state, rotation, dynamics, inputs, dt);
  const Vec3 velocity = momenta.linear * dynamics.inverseMass;
  const Vec3 omega = angularVelocityFrom(rotation, dynamics.inverseInertiaBody, momenta.angular);
  const IntegratedPose pose = advancedPose(state.position, state.orientation, velocity, omega, dt);
  return {pose.position, pose.orientation, momenta.linear, momenta.angular};
}

RigidState rk4Step(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                   const ForceInputs& inputs, double dt) {
  // Intermediate stages use the rotation of their normalised quaternion; the
  // stage state itself is left as the method prescribes.
  const auto stageRate = [&](const RigidState& stage) {
    return stateRate(stage, stage.orientation.normalized().toRotationMatrix(), dynamics, inputs);
  };
  const StateRate k1 = stateRate(state, rotation, dynamics, inputs);
  const StateRate k2 = stageRate(advanceState(state, k1, 0.5 * dt));
  const StateRate k3 = stageRate(advanceState(state, k2, 0.5 * dt));
  const StateRate k4 = stageRate(advanceState(state, k3, dt));
  return rk4Combine(state, k1, k2, k3, k4, dt);
}

RigidState integrateStep(IntegratorKind kind, const RigidState& state, const Mat3& rotation,
                         const BodyDynamics& dynamics, const ForceInputs& inputs, double dt) {
  switch (kind) {
    case IntegratorKind::ExplicitEuler:
      return explicitEulerStep(state, rotation, dynamics, inputs, dt);
    case IntegratorKind::SemiImplicitEuler:
      return semiImplicitEulerStep(state, rotation, dynamics, inputs, dt);
    case IntegratorKind::Rk4:
      return rk4Step(state, rotation, dynamics, inputs, dt);
  }
  return state;
}

}  // namespace rbsim
