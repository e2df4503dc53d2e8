#pragma once
// A ray as the queries cast it: the segment origin + t delta for fractions
// t in [0, 1] (of the whole segment), and the slab test of such a segment
// against an axis-aligned box, which the AABB tree's ray walk uses to prune.

#include <limits>
#include <utility>

#include "physics/collision/aabb.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct RaySegment {
  Vec3 origin = Vec3::Zero();        // m
  Vec3 delta = Vec3::UnitX();        // m: the segment's end minus its start
  Vec3 inverseDelta = Vec3::UnitX();  // 1/delta per axis; ±inf where delta is ±0

  RaySegment() = default;
  RaySegment(const Vec3& start, const Vec3& startToEnd)
      : origin(start), delta(startToEnd), inverseDelta(startToEnd.cwiseInverse()) {}
};

// The fraction at which the segment enters `box` (0 when it starts inside),
// if it meets the box at some fraction in [0, maxFraction]; +inf otherwise.
// The slab test (Kay and Kajiya 1986; Williams, Barrus, Morley and Shirley,
// "An efficient and robust ray-box intersection algorithm", 2005): each
// axis's slab holds the segment between two fractions, and the box holds
// it where all three intervals overlap. A zero component of delta gives
// ±inf fractions, so a segment parallel to a slab is inside it everywhere
// or nowhere; when it lies exactly in a slab's face plane the product is
// 0 × inf = NaN, and NaN fails every comparison below, so that axis
// restricts nothing: the box is kept, which for pruning is the safe side.
inline double segmentEntersBox(const RaySegment& ray, const Aabb& box, double maxFraction) {
  double near = 0.0;
  double far = maxFraction;
  for (int axis = 0; axis < 3; ++axis) {
    double t0 = (box.min[axis] - ray.origin[axis]) * ray.inverseDelta[axis];
    double t1 = (box.max[axis] - ray.origin[axis]) * ray.inverseDelta[axis];
    if (ray.inverseDelta[axis] < 0.0) std::swap(t0, t1);
    if (t0 > near) near = t0;
    if (t1 < far) far = t1;
  }
  return near <= far ? near : std::numeric_limits<double>::infinity();
}

}  // namespace rbsim
