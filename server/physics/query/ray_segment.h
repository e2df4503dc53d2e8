#pragma once
// A ray as the queries cast it: the segment origin + t delta for fractions
// t in [0, 1] (of the whole segment), and the slab test of such a segment
// against an axis-aligned box, with which the ray tree's walk prunes.

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/collision/aabb.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct RaySegment {
  Vec3 origin = Vec3::Zero();         // m
  Vec3 delta = Vec3::UnitX();         // m: the segment's end minus its start
  Vec3 inverseDelta = Vec3::UnitX();  // 1/delta per axis, finite: see inverseOrHuge

  RaySegment() = default;
  RaySegment(const Vec3& start, const Vec3& startToEnd)
      : origin(start),
        delta(startToEnd),
        inverseDelta(inverseOrHuge(startToEnd.x()), inverseOrHuge(startToEnd.y()), inverseOrHuge(startToEnd.z())) {}

  // 1/d, or ±1e300 (d's sign) for |d| <= 1e-300 (zero, and denormals whose
  // inverse overflows). A finite stand-in for ±inf keeps 0 × inverse from
  // giving NaN for a segment parallel to a slab that starts on one of its
  // planes: the slab then holds it from fraction 0, the safe side, and any
  // other start gives fractions of ±1e300 or more, as inf would.
  static double inverseOrHuge(double d) {
    return std::abs(d) > 1e-300 ? 1.0 / d : std::copysign(1e300, d);
  }
};

// The fraction at which the segment enters `box` (0 when it starts inside),
// if it meets the box at some fraction in [0, maxFraction]; +inf otherwise.
// The slab test (Kay and Kajiya 1986; Williams, Barrus, Morley and Shirley,
// "An efficient and robust ray-box intersection algorithm", 2005): each
// axis's slab holds the segment between two fractions, and the box holds
// it where all three intervals overlap. Branch-free: the walk of the tree
// runs it twice per node.
inline double segmentEntersBox(const RaySegment& ray, const Eigen::Array3d& lower, const Eigen::Array3d& upper,
                               double maxFraction) {
  const Eigen::Array3d t0 = (lower - ray.origin.array()) * ray.inverseDelta.array();
  const Eigen::Array3d t1 = (upper - ray.origin.array()) * ray.inverseDelta.array();
  const double near = std::max(t0.min(t1).maxCoeff(), 0.0);
  const double far = std::min(t0.max(t1).minCoeff(), maxFraction);
  return near <= far ? near : std::numeric_limits<double>::infinity();
}
inline double segmentEntersBox(const RaySegment& ray, const Aabb& box, double maxFraction) {
  return segmentEntersBox(ray, box.min.array(), box.max.array(), maxFraction);
}

}  // namespace rbsim
