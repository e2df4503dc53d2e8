#pragma once
// Numbers of several constraints side by side, one per lane: the
// structure-of-arrays form in which a sweep solves kLanes constraints that
// share no moving body with the same instructions (as Box2D v3's wide
// contact solver does). Eigen's fixed-size arrays carry the lanes, so the
// compiler uses whatever vector width the build targets (two doubles with
// SSE2, four with AVX2) without intrinsics.

#include <Eigen/Core>

#include "rbsim/physics/math_types.h"

namespace rbsim {

inline constexpr int kLanes = 4;

using Lanes = Eigen::Array<double, kLanes, 1>;

// A 3-vector per lane.
struct LaneVec3 {
  Lanes x = Lanes::Zero(), y = Lanes::Zero(), z = Lanes::Zero();

  void set(int lane, const Vec3& v) {
    x[lane] = v.x();
    y[lane] = v.y();
    z[lane] = v.z();
  }
  Vec3 get(int lane) const { return {x[lane], y[lane], z[lane]}; }
};

inline Lanes dot(const LaneVec3& a, const LaneVec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

inline LaneVec3 operator-(const LaneVec3& a, const LaneVec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

// a += s b, lane by lane.
inline void addScaled(LaneVec3& a, const Lanes& s, const LaneVec3& b) {
  a.x += s * b.x;
  a.y += s * b.y;
  a.z += s * b.z;
}

}  // namespace rbsim
