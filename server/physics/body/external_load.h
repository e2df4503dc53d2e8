#pragma once
// Forces and torques applied to one body from outside during one step.
//
// Every force acts at a point fixed in the body (r, body frame, relative to
// the centre of mass); what differs is the frame of the force:
//  - world-frame forces keep their world direction while the body turns, so
//    the moment of one is (R r) × f. Their sum Σ (R rᵢ) × fᵢ is kept in the
//    fixed-size matrix S = Σ rᵢ fᵢᵀ: with M = R S, (R rᵢ) × fᵢ summed is the
//    axial vector of M, τ_k = ε_kjl M_jl. So any number of wrenches costs
//    one 3×3 product per evaluation, and no per-wrench storage.
//  - body-frame forces turn with the body: their resultant and moment are
//    fixed in body space and rotate with R.
// Neither depends on the position, only on R; RK4 re-evaluates both at each
// of its stages, where the body has turned.

#include "rbsim/physics/math_types.h"

namespace rbsim {

struct ExternalLoad {
  bool active = false;                   // false: all of the below are zero (first: read most)
  Vec3 worldForce = Vec3::Zero();        // N, world frame: Σ fᵢ of world-frame forces
  Mat3 worldForceLevers = Mat3::Zero();  // m·N: S = Σ rᵢ fᵢᵀ, rᵢ body frame, fᵢ world frame
  Vec3 worldTorque = Vec3::Zero();       // N·m, world frame: pure couples
  Vec3 bodyForce = Vec3::Zero();         // N, body frame, through the centre of mass
  Vec3 bodyTorque = Vec3::Zero();        // N·m, body frame, about the centre of mass

  // World-frame force f acting at body point r (body frame, relative to the
  // centre of mass), plus a world-frame couple.
  void addWorldWrench(const Vec3& force, const Vec3& torque, const Vec3& bodyPoint) {
    active = true;
    worldForce += force;
    worldForceLevers += bodyPoint * force.transpose();
    worldTorque += torque;
  }
  // Force f at body point r plus a couple, all in the body frame.
  void addBodyWrench(const Vec3& force, const Vec3& torque, const Vec3& bodyPoint) {
    active = true;
    bodyForce += force;
    bodyTorque += bodyPoint.cross(force) + torque;
  }

  // Resultant force and torque about the centre of mass for a body with
  // rotation R (body -> world).
  Vec3 forceAt(const Mat3& rotation) const { return worldForce + rotation * bodyForce; }
  Vec3 torqueAt(const Mat3& rotation) const {
    const Mat3 m = rotation * worldForceLevers;
    const Vec3 levers(m(1, 2) - m(2, 1), m(2, 0) - m(0, 2), m(0, 1) - m(1, 0));
    return worldTorque + levers + rotation * bodyTorque;
  }

  void clear() { *this = ExternalLoad{}; }
};

}  // namespace rbsim
