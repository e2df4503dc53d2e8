#include "physics/query/ray_shapes.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>
#include <variant>

namespace rbsim {

namespace {

// The span of the union of two overlapping spans (parts of one convex
// solid): it enters where the first part is entered.
void unite(RaySpan& total, const RaySpan& part) {
  if (part.isEmpty()) return;
  if (part.enter < total.enter) {
    total.enter = part.enter;
    total.normal = part.normal;
  }
  total.exit = std::max(total.exit, part.exit);
}

// Where the line origin + t direction is within `radius` of the z axis (an
// infinite cylinder), with the radial normal where it enters.
RaySpan radialSpan(double radius, const Vec3& origin, const Vec3& direction) {
  const double a = direction.x() * direction.x() + direction.y() * direction.y();
  const double originSquared = origin.x() * origin.x() + origin.y() * origin.y();
  if (a == 0.0) return originSquared <= radius * radius ? RaySpan::everywhere() : RaySpan{};
  // As for the sphere, in the xy plane.
  const double mid = -(origin.x() * direction.x() + origin.y() * direction.y()) / a;
  const double cx = origin.x() + mid * direction.x();
  const double cy = origin.y() + mid * direction.y();
  const double closest = std::hypot(cx, cy);
  if (closest > radius) return {};
  const double half = std::sqrt((radius - closest) * (radius + closest) / a);
  RaySpan span{mid - half, mid + half, Vec3::Zero()};
  const double px = origin.x() + span.enter * direction.x();
  const double py = origin.y() + span.enter * direction.y();
  const double length = std::hypot(px, py);
  span.normal = length > 0.0 ? Vec3(px / length, py / length, 0.0) : Vec3::UnitX();
  return span;
}

// Where the line is within the slab |z| <= halfLength, with the cap's
// normal where it enters.
RaySpan slabSpanZ(double halfLength, const Vec3& origin, const Vec3& direction) {
  if (direction.z() == 0.0) return std::abs(origin.z()) <= halfLength ? RaySpan::everywhere() : RaySpan{};
  const double t0 = (-halfLength - origin.z()) / direction.z();
  const double t1 = (halfLength - origin.z()) / direction.z();
  // Rising, the line enters through the bottom cap (normal −z).
  return direction.z() > 0.0 ? RaySpan{t0, t1, -Vec3::UnitZ()} : RaySpan{t1, t0, Vec3::UnitZ()};
}

// The part of `a` inside `b` too: the intersection of two solids' spans,
// entering where the later of the two is entered.
RaySpan intersect(const RaySpan& a, const RaySpan& b) {
  if (a.isEmpty() || b.isEmpty()) return {};
  RaySpan span = a.enter >= b.enter ? a : b;
  span.exit = std::min(a.exit, b.exit);
  if (span.isEmpty()) return {};
  return span;
}

}  // namespace

RaySpan sphereSpan(double radius, const Vec3& origin, const Vec3& direction) {
  const double a = direction.squaredNorm();
  if (a == 0.0) return origin.norm() <= radius ? RaySpan::everywhere() : RaySpan{};
  // The line's point nearest the centre, at t = mid, is `closest` from it;
  // the chord's half length follows from (r − |c|)(r + |c|), which keeps
  // its digits where r² − |c|² would cancel (Haines et al. 2019).
  const double mid = -origin.dot(direction) / a;
  const double closest = (origin + mid * direction).norm();
  if (closest > radius) return {};
  const double half = std::sqrt((radius - closest) * (radius + closest) / a);
  RaySpan span{mid - half, mid + half, Vec3::Zero()};
  const Vec3 point = origin + span.enter * direction;
  const double length = point.norm();
  span.normal = length > 0.0 ? Vec3(point / length) : Vec3::UnitZ();
  return span;
}

RaySpan boxSpan(const Vec3& halfExtents, const Vec3& origin, const Vec3& direction) {
  RaySpan span = RaySpan::everywhere();
  for (int axis = 0; axis < 3; ++axis) {
    const double h = halfExtents[axis];
    if (direction[axis] == 0.0) {
      // Parallel to this slab: inside it everywhere or nowhere.
      if (std::abs(origin[axis]) > h) return {};
      continue;
    }
    const double inverse = 1.0 / direction[axis];  // one division, not two: leaves are tested at every ray
    double t0 = (-h - origin[axis]) * inverse;
    double t1 = (h - origin[axis]) * inverse;
    double outward = -1.0;  // rising along the axis, the line enters through the −h face
    if (t0 > t1) {
      std::swap(t0, t1);
      outward = 1.0;
    }
    if (t0 > span.enter) {
      span.enter = t0;
      span.normal = Vec3::Zero();
      span.normal[axis] = outward;
    }
    span.exit = std::min(span.exit, t1);
    if (span.isEmpty()) return {};
  }
  return span;
}

RaySpan cylinderSpan(double radius, double halfLength, const Vec3& origin, const Vec3& direction) {
  // The solid is the infinite cylinder cut by the slab between the caps.
  return intersect(radialSpan(radius, origin, direction), slabSpanZ(halfLength, origin, direction));
}

RaySpan capsuleSpan(double radius, double halfLength, const Vec3& origin, const Vec3& direction) {
  // The capsule is the union of the cylinder between the caps' centres and
  // the two spheres; being convex, the line's span in it is the union of
  // its spans in the three.
  const Vec3 offset(0.0, 0.0, halfLength);
  RaySpan span = cylinderSpan(radius, halfLength, origin, direction);
  if (halfLength == 0.0) span = {};  // a sphere: the cylinder is flat
  unite(span, sphereSpan(radius, origin - offset, direction));
  unite(span, sphereSpan(radius, origin + offset, direction));
  if (span.isEmpty()) return {};
  // The normal from the nearest point of the core segment: the right one
  // whichever part was entered first, and continuous where they meet.
  const Vec3 point = origin + span.enter * direction;
  const Vec3 core(0.0, 0.0, std::clamp(point.z(), -halfLength, halfLength));
  const Vec3 away = point - core;
  const double length = away.norm();
  if (std::isfinite(length) && length > 0.0) span.normal = away / length;
  return span;
}

RaySpan hullSpan(const ConvexHull& hull, const Vec3& origin, const Vec3& direction) {
  // Cyrus–Beck: the hull is the intersection of its faces' half-spaces
  // n · p <= c; each one clips the line's span from one side.
  RaySpan span = RaySpan::everywhere();
  for (std::size_t f = 0; f < hull.faceNormals.size(); ++f) {
    const Vec3& normal = hull.faceNormals[f];
    const double approach = normal.dot(direction);
    const double clearance = hull.faceOffsets[f] - normal.dot(origin);  // >= 0: origin on the inner side
    if (approach == 0.0) {
      if (clearance < 0.0) return {};  // parallel to the face and outside it
      continue;
    }
    const double t = clearance / approach;
    if (approach < 0.0) {
      if (t > span.enter) {
        span.enter = t;
        span.normal = normal;
      }
    } else {
      span.exit = std::min(span.exit, t);
    }
    if (span.isEmpty()) return {};
  }
  return span;
}

RaySpan halfSpaceSpan(const Vec3& normal, double offset, const Vec3& origin, const Vec3& direction) {
  const double approach = normal.dot(direction);
  const double clearance = offset - normal.dot(origin);
  if (approach == 0.0) return clearance >= 0.0 ? RaySpan::everywhere() : RaySpan{};
  const double t = clearance / approach;
  const double inf = std::numeric_limits<double>::infinity();
  return approach < 0.0 ? RaySpan{t, inf, normal} : RaySpan{-inf, t, Vec3::Zero()};
}

RaySpan convexSpan(const ConvexGeometry& geometry, const Vec3& origin, const Vec3& direction) {
  return std::visit(
      [&](const auto& shape) -> RaySpan {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, SphereShape>) {
          return sphereSpan(shape.radius, origin, direction);
        } else if constexpr (std::is_same_v<T, BoxShape>) {
          return boxSpan(shape.halfExtents, origin, direction);
        } else if constexpr (std::is_same_v<T, CylinderShape>) {
          return cylinderSpan(shape.radius, shape.halfLength, origin, direction);
        } else if constexpr (std::is_same_v<T, CapsuleShape>) {
          return capsuleSpan(shape.radius, shape.halfLength, origin, direction);
        } else {
          static_assert(std::is_same_v<T, std::shared_ptr<const ConvexHull>>);
          return hullSpan(*shape, origin, direction);
        }
      },
      geometry);
}

std::optional<RayEntry> firstEntry(const RaySpan& span, double maxFraction) {
  if (span.isEmpty() || span.exit < 0.0 || span.enter > maxFraction) return std::nullopt;
  if (span.enter < 0.0) return RayEntry{0.0, Vec3::Zero(), true};
  return RayEntry{span.enter, span.normal, false};
}

}  // namespace rbsim
