#pragma once
// ODE integrators over the state (x, q, P, L) of rbsim/physics/rigid_state.h.
//
// Each is a pure function (state, constants, loads, dt) -> state, so tests
// can call it without a World. The quaternion is renormalised once at the end
// of every step; the angular momentum L is the state, so a torque-free body
// keeps its world-frame L exactly (no gyroscopic term to integrate).

#include "physics/body/external_load.h"
#include "rbsim/physics/integrator_kind.h"
#include "rbsim/physics/rigid_state.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

// Everything that pushes on one body during a step: gravity, the external
// load (may be null) and the body's damping (in BodyDynamics).
struct ForceInputs {
  Vec3 gravity = Vec3::Zero();          // m/s²
  const ExternalLoad* load = nullptr;   // null or inactive: no external load
};

// Total force and torque (about the centre of mass) at a state, damping included.
struct NetWrench {
  Vec3 force = Vec3::Zero();   // N, world
  Vec3 torque = Vec3::Zero();  // N·m, world
};
NetWrench evaluateWrench(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                      const ForceInputs& inputs, bool includeDamping);

// `rotation` must be state.orientation's rotation matrix (callers cache it).

// The time derivative of the state: dx/dt = v, dq/dt = ½ [0, ω] q, dP/dt = F,
// dL/dt = τ, forces and torques from evaluateWrench with damping. Exposed so
// that a system of bodies coupled by forces of its own (penalty contact) can
// be integrated with the same stages: the caller adds those forces to
// `force` and `torque`.
struct StateRate {
  Vec3 velocity;    // dx/dt, m/s
  Quaternion spin;  // dq/dt, 1/s
  Vec3 force;       // dP/dt, N
  Vec3 torque;      // dL/dt, N·m
};
StateRate stateRate(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                    const ForceInputs& inputs);
// state + h · rate, the quaternion not renormalised (as inside a step).
RigidState advanceState(const RigidState& state, const StateRate& rate, double h);
// The classical RK4 update from the four stage rates, quaternion renormalised.
RigidState rk4Combine(const RigidState& state, const StateRate& k1, const StateRate& k2,
                      const StateRate& k3, const StateRate& k4, double dt);

// x += v dt, q += ½ ω q dt, P += F dt, L += τ dt, every right-hand side
// taken at the start of the step.
RigidState explicitEulerStep(const RigidState& state, const Mat3& rotation,
                             const BodyDynamics& dynamics, const ForceInputs& inputs, double dt);

// P and L first (damping implicitly: P' = (P + F dt) / (1 + c dt), stable for
// any c dt), then x and q with the new v and ω. Symplectic for the
// translational part. Its two halves below are what the contact solver runs
// its impulses between, so bodies in contact and free bodies take the same
// arithmetic.
RigidState semiImplicitEulerStep(const RigidState& state, const Mat3& rotation,
                                 const BodyDynamics& dynamics, const ForceInputs& inputs,
                                 double dt);

// The first half: momenta after the forces of dt, damping implicit.
struct Momenta {
  Vec3 linear = Vec3::Zero();   // P, kg·m/s, world
  Vec3 angular = Vec3::Zero();  // L, kg·m²/s, world, about the centre of mass
};
Momenta integrateMomenta(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                         const ForceInputs& inputs, double dt);

// RATTLE's first half kick of a step of length h (the joint step's
// islands that touch nothing): the forces at the start over h/2, and the
// damping on the momenta the step starts with, e^(−c h) (1 + c h/2) of them
// left, which is 1 − c h/2 to O((c h)³). Its second half is
// integrateMomenta over h/2, implicit, 1 / (1 + c h/2): an explicit half
// and an implicit one make a symmetric, second-order pair (two implicit
// halves are first order), and undisturbed momenta decay by exactly
// e^(−c h) a step, never past zero however large c h. Without damping,
// the same bits as integrateMomenta over h/2.
Momenta firstHalfKick(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                      const ForceInputs& inputs, double h);

// dq/dt = ½ [0, ω] q, ω in the world frame (quaternion kinematics as in
// Baraff's rigid-body notes).
inline Quaternion orientationRate(const Quaternion& q, const Vec3& omega) {
  const Quaternion w{0.0, omega.x(), omega.y(), omega.z()};
  const Quaternion product = w * q;
  return {0.5 * product.w, 0.5 * product.x, 0.5 * product.y, 0.5 * product.z};
}

inline Quaternion addScaled(const Quaternion& q, const Quaternion& rate, double h) {
  return {q.w + h * rate.w, q.x + h * rate.x, q.y + h * rate.y, q.z + h * rate.z};
}

// The second half: x += v dt, q += ½ [0, ω] q dt, then q normalised. Inline:
// the free loop and the solved bodies run it for every body.
struct IntegratedPose {
  Vec3 position;
  Quaternion orientation;
};
inline IntegratedPose advancedPose(const Vec3& position, const Quaternion& orientation, const Vec3& linearVelocity,
                         const Vec3& angularVelocity, double dt) {
  return {position + dt * linearVelocity,
          addScaled(orientation, orientationRate(orientation, angularVelocity), dt).normalized()};
}
inline void integratePose(Vec3& position, Quaternion& orientation, const Vec3& linearVelocity,
                          const Vec3& angularVelocity, double dt) {
  const IntegratedPose next = advancedPose(position, orientation, linearVelocity, angularVelocity, dt);
  position = next.position;
  orientation = next.orientation;
}

// Classical RK4: forces, torques, velocities re-evaluated at each stage.
RigidState rk4Step(const RigidState& state, const Mat3& rotation, const BodyDynamics& dynamics,
                   const ForceInputs& inputs, double dt);

// Dispatches on the world's choice.
RigidState integrateStep(IntegratorKind kind, const RigidState& state, const Mat3& rotation,
                         const BodyDynamics& dynamics, const ForceInputs& inputs, double dt);

}  // namespace rbsim
