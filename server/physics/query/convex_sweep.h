#pragma once
// Where a convex solid, swept along a segment without turning, first
// touches another convex solid or a half-space: the narrow phase of shape
// casts (world.h, castShape).
//
// Against a convex solid, by conservative advancement along the sweep
// (Mirtich, "Impulse-based dynamic simulation of rigid body systems",
// thesis, 1996, §2.4) with GJK distances (collision/gjk.h): at the distance
// d between the solids, closest along the unit n, the gap closes at the
// rate delta · n per unit fraction, so advancing by d / (delta · n) cannot
// pass the first touch. Under a translation the distance is a convex
// function of the fraction (the distance from the origin of a line through
// the solids' Minkowski difference), so each advance is a Newton step from
// below: it never overshoots, ends in one step on a face and converges
// quadratically on a curved surface; and a gap that does not close at the
// current fraction never closes later, which ends a miss at once. The same
// idea is GJK ray casting's (van den Bergen, "Ray casting against general
// convex objects with application to continuous collision detection",
// 2004). Spheres and capsules are swept as their cores (a point, a
// segment) with their radii added back, which GJK finds faster and exactly.
//
// Against a half-space, in closed form from the solid's support point.

#include <optional>

#include "physics/collision/broad_phase.h"
#include "physics/collision/collider.h"
#include "physics/collision/convex_geometry.h"
#include "rbsim/physics/transform.h"

namespace rbsim {

struct SweepContact {
  double fraction = 0.0;       // of the sweep, where the solids first touch
  Vec3 point = Vec3::Zero();   // m, world: the target's point touched there
  Vec3 normal = Vec3::Zero();  // unit, world, out of the target (the sweep's reverse when it starts touching)
};

// The solid `moving`, at `start` (geometry frame -> world) and moved by
// `delta` (m, world) over the sweep, against `target`: its first touch at a
// fraction in [0, maxFraction], if any. A sweep that starts touching or
// overlapping the target (within the tolerance) touches it at 0.
std::optional<SweepContact> sweepAgainstConvex(const ConvexGeometry& moving, const Transform& start,
                                               const Vec3& delta, const PlacedConvex& target,
                                               double maxFraction);
std::optional<SweepContact> sweepAgainstHalfSpace(const ConvexGeometry& moving, const Transform& start,
                                                  const Vec3& delta, const HalfSpace& target,
                                                  double maxFraction);

// m: the gap at which two solids count as touching, for solids of these
// sizes (geometrySize): 1e-7 of their size. The advance stops within it,
// and the touch is then found in closed form, exactly for a face and to
// the square of the gap for a curved surface. Smaller would not help: the
// normal is the direction of the closest points at that gap, which GJK
// gives to about 1e-16 m, so it is good to about 1e-16 / gap (1e-9 here);
// the point is the target's closest point there, off the exact touch by
// at most the gap times the tangent of the sweep's angle to the normal.
inline double sweepTouchTolerance(double movingSize, double targetSize) {
  return 1e-7 * (movingSize + targetSize);
}

}  // namespace rbsim
