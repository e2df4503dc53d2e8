#pragma once
// Penetration depth, direction and contact point of two overlapping convex
// pieces, by libccd. This header and ccd_support.cpp are the only places
// that know about libccd; the rest of rbsim sees our convention:
// the normal points from A to B, and moving B by depth × normal separates
// the pieces (libccd computes "penetration of obj2 into obj1"; we pass A as
// obj1, and the conversion is tested in test_signed_distance.cpp).

#include <optional>

#include "physics/collision/collider.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct PenetrationSettings {
  // Bounds libccd's GJK and MPR loops (CCD_INIT leaves them unbounded), and
  // through a budget of 4 × maxIterations support queries its EPA loop too.
  int maxIterations = 64;
  // Relative to the larger piece's size: libccd's EPA and MPR tolerances.
  // Polytope pairs come out exact; for curved pieces (cylinders) the depth
  // is within about tolerance × size and the normal within about
  // √tolerance rad (~12 µs a cylinder pair at 1e-6). Much
  // below 1e-7 it nears rounding, where EPA stops making progress and the
  // budget has to end it.
  double tolerance = 1e-6;
};

// Which method produced the answer, in the order they are tried.
enum class PenetrationMethod {
  Epa,              // libccd GJK + EPA (ccdGJKPenetration): the minimum depth
  Mpr,              // libccd MPR (ccdMPRPenetration), when EPA failed (libccd#25)
  SupportEstimate,  // both failed: the best of a set of candidate axes (SAT-like)
};

struct Penetration {
  // m: how far B must move along `normal` to stop overlapping, measured
  // exactly along that normal from the two support functions; 0 or less
  // when the pieces only touch (or do not overlap at all).
  double depth = 0.0;
  Vec3 normal = Vec3::UnitZ();  // unit, world, from A to B
  // m, world: pointA on A's support plane along normal, pointB on B's
  // support plane along −normal, with pointA − pointB = depth × normal;
  // placed over the overlap (libccd's point when it lies in both pieces'
  // bounding boxes, else the middle of their intersection: libccd#17).
  Vec3 pointA = Vec3::Zero();
  Vec3 pointB = Vec3::Zero();
  PenetrationMethod method = PenetrationMethod::Epa;
  // libccd's return codes, for diagnostics: 0 success, -1 no intersection
  // found, -2 out of memory; 1 means the call was not made.
  int epaStatus = 1;
  int mprStatus = 1;
};

// libccd's EPA alone, for pieces that overlap: the distance from the origin
// to the nearest face of EPA's final polytope. That polytope is the hull of
// support points of the Minkowski difference and holds the origin, so the
// distance is a lower bound on the penetration depth, within `tolerance` ×
// size of it; `normal` is that face's (A to B). Empty when EPA gives no
// usable answer (libccd#25, the support budget, non-finite input).
struct EpaBound {
  double depth = 0.0;  // m, <= the true depth
  Vec3 normal = Vec3::UnitZ();
};
std::optional<EpaBound> epaDepthBound(const PlacedConvex& a, const PlacedConvex& b,
                                      const PenetrationSettings& settings);

// For pieces that overlap (GJK says so); never fails: when libccd gives no
// usable answer the support-based estimate stands in, and `method` says so.
Penetration penetration(const PlacedConvex& a, const PlacedConvex& b,
                        const PenetrationSettings& settings = {});

}  // namespace rbsim
