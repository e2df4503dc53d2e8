#pragma once
// A rigid transform p -> rotation p + translation (a proper rotation, no scale).

#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct Transform {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();  // m

  static Transform identity() { return {}; }
  static Transform fromPose(const Vec3& position, const Quaternion& orientation) {
    return {orientation.toRotationMatrix(), position};
  }

  Vec3 apply(const Vec3& p) const { return rotation * p + translation; }
  Vec3 applyInverse(const Vec3& p) const { return rotation.transpose() * (p - translation); }
  Vec3 rotate(const Vec3& v) const { return rotation * v; }
  Vec3 inverseRotate(const Vec3& v) const { return rotation.transpose() * v; }
  Transform inverse() const { return {rotation.transpose(), -(rotation.transpose() * translation)}; }
};

// (outer ∘ inner): first inner, then outer.
inline Transform operator*(const Transform& outer, const Transform& inner) {
  return {outer.rotation * inner.rotation, outer.rotation * inner.translation + outer.translation};
}

}  // namespace rbsim
