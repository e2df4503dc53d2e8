#pragma once
// The signed distance between two convex solids
// and their closest (or deepest) points.
//  - apart: GJK distance (our own implementation; libccd has no distance
//    query), with a signed-volume simplex solver that stays robust for
//    nearly degenerate simplices;
//  - overlapping: penetration depth and direction from libccd (behind
//    ccd_support.cpp, the only file that includes <ccd/ccd.h>), negative.

#include "physics/collision/collider.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct DistanceSettings {
  int maxIterations = 64;    // GJK; also bounds libccd's GJK and MPR loops
  double tolerance = 1e-12;  // m, relative to the solids' size: GJK's stopping gap
  // Relative to the solids' size: libccd's EPA/MPR stopping tolerance (see
  // PenetrationSettings::tolerance). Sphere and capsule pairs do not use it.
  double penetrationTolerance = 1e-6;
};

// Always pointB − pointA = distance × normal. Apart, or for sphere and
// capsule pairs, the points are the closest points on the two surfaces.
// Overlapping otherwise, they lie on A's and B's support planes along the
// normal, placed over the overlap (see ccd_support.h): a witness of the
// depth, not a contact manifold.
struct SignedDistance {
  double distance = 0.0;        // m: > 0 apart, < 0 penetrating (minus the depth)
  Vec3 pointA = Vec3::Zero();   // m, world: on A's surface
  Vec3 pointB = Vec3::Zero();   // m, world: on B's surface
  Vec3 normal = Vec3::UnitZ();  // unit, world, from A towards B (the direction to move B out)
  int iterations = 0;
  bool converged = true;  // false: iteration cap hit; the result is the best found
};

SignedDistance signedDistance(const PlacedConvex& a, const PlacedConvex& b,
                              const DistanceSettings& settings = {});

}  // namespace rbsim
