#pragma once
// One scalar velocity constraint between two bodies A and B: a row of the
// contact Jacobian. Its velocity is
//     linear·(vB − vA) + armB·ωB − armA·ωA,
// and an impulse λ along it changes the bodies' velocities by
//     vA −= λ mA⁻¹ linear,  ωA −= λ IA⁻¹ armA,  vB += λ mB⁻¹ linear,  ωB += λ IB⁻¹ armB.
// The responses I⁻¹ arm are computed once per step, so the solver's sweeps
// need only dot products and scaled additions (no matrix products).
//
// A contact point's normal row has linear = n, armA = rA×n, armB = rB×n (Baraff's
// impulse formula in row form); a pure rotation row (torsion, tilt)
// has linear = 0 and armA = armB = the axis.

#include "rbsim/physics/math_types.h"

namespace rbsim {

struct VelocityRow {
  Vec3 linear = Vec3::Zero();
  Vec3 armA = Vec3::Zero();
  Vec3 armB = Vec3::Zero();
  Vec3 responseA = Vec3::Zero();  // IA⁻¹ armA, world
  Vec3 responseB = Vec3::Zero();  // IB⁻¹ armB, world

  void set(const Vec3& linearPart, const Vec3& armOfA, const Vec3& armOfB, const Mat3& inverseInertiaA,
           const Mat3& inverseInertiaB) {
    linear = linearPart;
    armA = armOfA;
    armB = armOfB;
    responseA = inverseInertiaA * armA;
    responseB = inverseInertiaB * armB;
  }

  double velocity(const Vec3& vA, const Vec3& wA, const Vec3& vB, const Vec3& wB) const {
    return linear.dot(vB - vA) + armB.dot(wB) - armA.dot(wA);
  }

  void apply(double lambda, double inverseMassA, double inverseMassB, Vec3& vA, Vec3& wA, Vec3& vB,
             Vec3& wB) const {
    vA -= (lambda * inverseMassA) * linear;
    wA -= lambda * responseA;
    vB += (lambda * inverseMassB) * linear;
    wB += lambda * responseB;
  }

  // K_ij: how much an impulse along `other` changes this row's velocity.
  // A body left out (held still, or static) contributes nothing.
  double coupling(const VelocityRow& other, double inverseMassA, double inverseMassB, bool withA,
                  bool withB) const {
    double k = 0.0;
    if (withA) k += inverseMassA * linear.dot(other.linear) + armA.dot(other.responseA);
    if (withB) k += inverseMassB * linear.dot(other.linear) + armB.dot(other.responseB);
    return k;
  }
};

}  // namespace rbsim
