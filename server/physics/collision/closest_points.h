#pragma once
// Closest points between the simple features contact generation works with:
// points, segments and convex polygons (Ericson, "Real-Time Collision
// Detection", 2005, ch. 5).

#include <span>

#include "rbsim/physics/math_types.h"

namespace rbsim {

// Parameter t in [0, 1] of the point of segment [a, b] closest to p (0 for a
// degenerate segment).
double closestParameterOnSegment(const Vec3& p, const Vec3& a, const Vec3& b);
inline Vec3 closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  return a + closestParameterOnSegment(p, a, b) * (b - a);
}

struct SegmentClosestPoints {
  Vec3 onFirst = Vec3::Zero();
  Vec3 onSecond = Vec3::Zero();
  double s = 0.0;  // parameter on the first segment, in [0, 1]
  double t = 0.0;  // parameter on the second
};

// Closest points of segments [p1, q1] and [p2, q2] (Ericson §5.1.9). For
// parallel segments the pair is one of many; callers that care (capsules
// lying side by side) treat that case themselves.
SegmentClosestPoints closestPointsOfSegments(const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                             const Vec3& q2);

// The point of a convex planar polygon (vertices counter-clockwise about
// `normal`) closest to p.
Vec3 closestPointOnConvexPolygon(const Vec3& p, std::span<const Vec3> polygon, const Vec3& normal);

// A unit vector perpendicular to the unit vector v, chosen deterministically.
Vec3 unitPerpendicular(const Vec3& v);

}  // namespace rbsim
