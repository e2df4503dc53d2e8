#include "physics/collision/convex_geometry.h"

#include <cmath>
#include <limits>
#include <type_traits>

namespace rbsim {

namespace {

// Every support function below must return a finite point of the solid for
// any direction, including zero and NaN (a NaN pose upstream must not turn
// into a NaN support point inside GJK or libccd). Comparisons written as
// `x >= 0` and `n > 0` are false for NaN, which picks a fixed corner.

double sideOf(double component, double half) {
  return component >= 0.0 ? half : -half;
}

Vec3 unitOrZero(const Vec3& v) {
  const double n = v.norm();
  return n > 0.0 ? Vec3(v / n) : Vec3::Zero();
}

Vec3 hullSupport(const ConvexHull& hull, const Vec3& direction) {
  // Small hulls scan (the first farthest vertex); larger ones climb their
  // vertex graph from a cube-map start (convex_hull.h), which stays exact on
  // plateaus of coplanar vertices: any vertex of a plateau is farthest.
  if (hull.vertices.empty()) return Vec3::Zero();
  return hull.vertices[static_cast<std::size_t>(supportVertex(hull, direction))];
}

// The core of a capsule: the segment of its axis.
Vec3 capsuleCoreSupport(const CapsuleShape& capsule, const Vec3& direction) {
  return {0.0, 0.0, sideOf(direction.z(), capsule.halfLength)};
}

}  // namespace

Vec3 supportPoint(const ConvexGeometry& geometry, const Vec3& direction) {
  return std::visit(
      [&](const auto& g) -> Vec3 {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, SphereShape>) {
          return g.radius * unitOrZero(direction);
        } else if constexpr (std::is_same_v<T, BoxShape>) {
          return {sideOf(direction.x(), g.halfExtents.x()),
                  sideOf(direction.y(), g.halfExtents.y()),
                  sideOf(direction.z(), g.halfExtents.z())};
        } else if constexpr (std::is_same_v<T, CapsuleShape>) {
          return capsuleCoreSupport(g, direction) + g.radius * unitOrZero(direction);
        } else if constexpr (std::is_same_v<T, CylinderShape>) {
          const double radial = std::hypot(direction.x(), direction.y());
          const Vec3 rim = radial > 0.0 ? Vec3(g.radius / radial * direction.x(),
                                               g.radius / radial * direction.y(), 0.0)
                                        : Vec3::Zero();
          return rim + Vec3(0.0, 0.0, sideOf(direction.z(), g.halfLength));
        } else {
          return hullSupport(*g, direction);
        }
      },
      geometry);
}

Aabb geometryBounds(const ConvexGeometry& geometry) {
  return std::visit(
      [](const auto& g) -> Aabb {
        using T = std::decay_t<decltype(g)>;
        Vec3 half;
        if constexpr (std::is_same_v<T, SphereShape>) {
          half = Vec3::Constant(g.radius);
        } else if constexpr (std::is_same_v<T, BoxShape>) {
          half = g.halfExtents;
        } else if constexpr (std::is_same_v<T, CapsuleShape>) {
          half = Vec3(g.radius, g.radius, g.halfLength + g.radius);
        } else if constexpr (std::is_same_v<T, CylinderShape>) {
          half = Vec3(g.radius, g.radius, g.halfLength);
        } else {
          return Aabb{g->lowerCorner, g->upperCorner};  // computed with the hull
        }
        return {-half, half};
      },
      geometry);
}

Aabb placedBounds(const ConvexGeometry& geometry, const Transform& pose) {
  // max_i = e_i · support(e_i) in the target frame; the support of the
  // placed solid along world direction d is pose(support(Rᵀ d)).
  Aabb box;
  for (int i = 0; i < 3; ++i) {
    const Vec3 axis = pose.rotation.row(i).transpose();  // Rᵀ e_i
    box.max[i] = pose.apply(supportPoint(geometry, axis))[i];
    box.min[i] = pose.apply(supportPoint(geometry, -axis))[i];
  }
  return box;
}

double geometrySize(const ConvexGeometry& geometry) {
  const Aabb box = geometryBounds(geometry);
  return box.isEmpty() ? 0.0 : box.halfExtents().norm();
}

Vec3 interiorPoint(const ConvexGeometry& geometry) {
  if (const auto* hull = std::get_if<std::shared_ptr<const ConvexHull>>(&geometry))
    return (*hull)->centroid;  // the mean of the vertices, computed with the hull
  return Vec3::Zero();
}

double coreRadius(const ConvexGeometry& geometry) {
  if (const auto* sphere = std::get_if<SphereShape>(&geometry)) return sphere->radius;
  if (const auto* capsule = std::get_if<CapsuleShape>(&geometry)) return capsule->radius;
  return 0.0;
}

Vec3 coreSupportPoint(const ConvexGeometry& geometry, const Vec3& direction) {
  if (std::holds_alternative<SphereShape>(geometry)) return Vec3::Zero();
  if (const auto* capsule = std::get_if<CapsuleShape>(&geometry))
    return capsuleCoreSupport(*capsule, direction);
  return supportPoint(geometry, direction);
}

}  // namespace rbsim
