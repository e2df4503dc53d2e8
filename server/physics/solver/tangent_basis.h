#pragma once
// The friction directions of a contact normal.

#include <cmath>

#include "rbsim/physics/math_types.h"

namespace rbsim {

// A tangent basis that depends only on the normal, so that friction impulses
// accumulated along t1, t2 last step still mean the same thing this step
// (warm starting needs that).
inline void tangentBasis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const Vec3 axis = std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : Vec3::UnitY();
  t1 = n.cross(axis).normalized();
  t2 = n.cross(t1);
}

}  // namespace rbsim
