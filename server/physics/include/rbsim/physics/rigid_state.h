#pragma once
// The state vector of one rigid body: 13 numbers (x, q, P, L), as in
// Baraff, "Rigid Body Simulation", SIGGRAPH course notes.

#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct RigidState {
  Vec3 position = Vec3::Zero();                     // x: centre of mass, m, world frame
  Quaternion orientation = Quaternion::identity();  // q: body -> world, unit
  Vec3 linearMomentum = Vec3::Zero();               // P = M v, kg·m/s, world frame
  Vec3 angularMomentum = Vec3::Zero();              // L = I ω, kg·m²/s, world frame, about x
};

// The per-body constants the integrators need. Body space has its axes along
// the principal axes, so the body-space inertia is the diagonal `inertiaBody`.
struct BodyDynamics {
  double mass = 1.0;                        // kg
  double inverseMass = 1.0;                 // 1/kg, 0 for static bodies
  Vec3 inertiaBody = Vec3::Ones();          // kg·m², principal moments
  Vec3 inverseInertiaBody = Vec3::Ones();   // 1/(kg·m²), 0 for static bodies
  double linearDamping = 0.0;               // 1/s: dP/dt = -c P
  double angularDamping = 0.0;              // 1/s: dL/dt = -c L
};

// ω = I⁻¹(t) L with I⁻¹(t) = R Ibody⁻¹ Rᵀ: taken to body space, scaled by
// the principal inverse moments, taken back (the reading of R Ibody⁻¹ Rᵀ
// that Baraff's rigid-body notes give).
inline Vec3 angularVelocityFrom(const Mat3& rotation, const Vec3& inverseInertiaBody,
                                const Vec3& angularMomentum) {
  return rotation * inverseInertiaBody.cwiseProduct(rotation.transpose() * angularMomentum);
}

}  // namespace rbsim
