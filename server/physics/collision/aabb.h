#pragma once
// Axis-aligned bounding box in some frame (world, unless a name says otherwise).

#include <algorithm>
#include <limits>

#include "rbsim/physics/transform.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct Aabb {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());   // m
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());  // m

  static Aabb empty() { return {}; }
  static Aabb everything() {
    const double inf = std::numeric_limits<double>::infinity();
    return {Vec3::Constant(-inf), Vec3::Constant(inf)};
  }
  bool isEmpty() const { return (min.array() > max.array()).any(); }
  bool overlaps(const Aabb& other) const {
    return (min.array() <= other.max.array()).all() && (other.min.array() <= max.array()).all();
  }
  bool contains(const Aabb& inner) const {
    return (min.array() <= inner.min.array()).all() && (inner.max.array() <= max.array()).all();
  }
  Aabb merged(const Aabb& other) const { return {min.cwiseMin(other.min), max.cwiseMax(other.max)}; }
  void include(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  Aabb fattened(double margin) const {
    return {min - Vec3::Constant(margin), max + Vec3::Constant(margin)};
  }
  Vec3 center() const { return 0.5 * (min + max); }
  Vec3 halfExtents() const { return 0.5 * (max - min); }
  // Half the surface area: the cost measure of the dynamic tree's insertion heuristic.
  double halfSurfaceArea() const {
    const Vec3 d = max - min;
    return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
  }
};

// The box around `local` after the transform: the centre moves, the half
// extents become |R| h (Arvo's method), exact for a transformed box.
inline Aabb transformedAabb(const Aabb& local, const Transform& transform) {
  if (local.isEmpty()) return local;
  const Vec3 center = transform.apply(local.center());
  const Vec3 half = transform.rotation.cwiseAbs() * local.halfExtents();
  return {center - half, center + half};
}

}  // namespace rbsim
