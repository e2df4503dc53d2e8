#pragma once
// Forces and torques applied to one body from outside during one step.
//
// Wrenches are accumulated in a form that can be re-evaluated at any state,
// because RK4 needs the load at its intermediate stages, where the body has
// moved and turned:
//  - world-frame forces at world points act through fixed world points, so
//    their torque about the centre of mass changes as the body moves. With
//    F = Σ fᵢ and T₀ = Σ (pᵢ − x₀) × fᵢ taken about the reference point x₀,
//    the torque about a later centre x is T₀ − (x − x₀) × F. Taking moments
//    about x₀ (the centre of mass when the first wrench arrived) rather than
//    about the world origin keeps precision for bodies far from the origin.
//  - body-frame forces at body points turn with the body: their resultant
//    and moment are fixed in body space and rotate with R.

#include "physics/math/types.h"

namespace rbsim {

struct ExternalLoad {
  Vec3 referencePoint = Vec3::Zero();  // m, world: x₀, the point worldTorque is taken about
  Vec3 worldForce = Vec3::Zero();      // N, world frame
  Vec3 worldTorque = Vec3::Zero();     // N·m, world frame, about referencePoint
  Vec3 bodyForce = Vec3::Zero();       // N, body frame, through the centre of mass
  Vec3 bodyTorque = Vec3::Zero();      // N·m, body frame, about the centre of mass
  bool active = false;                 // false: all of the above are zero

  // Force f at world point p plus a pure torque, all in the world frame.
  // `centerOfMass` is the body's current x (becomes x₀ on first use).
  void addWorldWrench(const Vec3& force, const Vec3& torque, const Vec3& point,
                      const Vec3& centerOfMass);
  // Force f at body point r (relative to the centre of mass) plus a pure
  // torque, all in the body frame.
  void addBodyWrench(const Vec3& force, const Vec3& torque, const Vec3& point);

  // Resultant force and torque about the centre of mass for a body at
  // position x with rotation R.
  Vec3 forceAt(const Mat3& rotation) const { return worldForce + rotation * bodyForce; }
  Vec3 torqueAt(const Vec3& position, const Mat3& rotation) const;

  void clear() { *this = ExternalLoad{}; }
};

inline void ExternalLoad::addWorldWrench(const Vec3& force, const Vec3& torque, const Vec3& point,
                                         const Vec3& centerOfMass) {
  if (!active) {
    referencePoint = centerOfMass;
    active = true;
  }
  worldForce += force;
  worldTorque += (point - referencePoint).cross(force) + torque;
}

inline void ExternalLoad::addBodyWrench(const Vec3& force, const Vec3& torque, const Vec3& point) {
  active = true;
  bodyForce += force;
  bodyTorque += point.cross(force) + torque;
}

inline Vec3 ExternalLoad::torqueAt(const Vec3& position, const Mat3& rotation) const {
  return worldTorque - (position - referencePoint).cross(worldForce) + rotation * bodyTorque;
}

}  // namespace rbsim
