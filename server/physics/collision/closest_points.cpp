#include "physics/collision/closest_points.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace rbsim {

namespace {

// Squared lengths (m²) below this make a segment a point. Far below any
// shape size we simulate, far above the rounding of coordinates near 1 m.
constexpr double kDegenerateLengthSquared = 1e-24;

}  // namespace

double closestParameterOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double lengthSquared = ab.squaredNorm();
  if (lengthSquared <= kDegenerateLengthSquared) return 0.0;
  return std::clamp((p - a).dot(ab) / lengthSquared, 0.0, 1.0);
}

SegmentClosestPoints closestPointsOfSegments(const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                             const Vec3& q2) {
  const Vec3 d1 = q1 - p1;
  const Vec3 d2 = q2 - p2;
  const Vec3 r = p1 - p2;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  double s = 0.0;
  double t = 0.0;
  if (a <= kDegenerateLengthSquared && e <= kDegenerateLengthSquared) {
    // Both are points.
  } else if (a <= kDegenerateLengthSquared) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kDegenerateLengthSquared) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denominator = a * e - b * b;  // >= 0; zero when parallel
      s = denominator > 0.0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return {p1 + s * d1, p2 + t * d2, s, t};
}

Vec3 closestPointOnConvexPolygon(const Vec3& p, std::span<const Vec3> polygon, const Vec3& normal) {
  // Inside every edge's outward side plane: the projection onto the plane is
  // the answer. Otherwise the closest point lies on the boundary.
  bool inside = true;
  const std::size_t count = polygon.size();
  for (std::size_t i = 0; i < count && inside; ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % count];
    if ((b - a).cross(normal).dot(p - a) > 0.0) inside = false;
  }
  if (inside) return p - normal.dot(p - polygon[0]) * normal;

  Vec3 best = polygon[0];
  double bestDistanceSquared = (p - best).squaredNorm();
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 q = closestPointOnSegment(p, polygon[i], polygon[(i + 1) % count]);
    const double distanceSquared = (p - q).squaredNorm();
    if (distanceSquared < bestDistanceSquared) {
      bestDistanceSquared = distanceSquared;
      best = q;
    }
  }
  return best;
}

Vec3 unitPerpendicular(const Vec3& v) {
  // Cross with the world axis least aligned with v: never near zero.
  const Vec3 absolute = v.cwiseAbs();
  Vec3 axis = Vec3::UnitX();
  if (absolute.y() < absolute.x() && absolute.y() <= absolute.z()) {
    axis = Vec3::UnitY();
  } else if (absolute.z() < absolute.x() && absolute.z() < absolute.y()) {
    axis = Vec3::UnitZ();
  }
  return v.cross(axis).normalized();
}

}  // namespace rbsim
