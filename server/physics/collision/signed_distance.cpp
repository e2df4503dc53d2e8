#include "physics/collision/signed_distance.h"

#include <algorithm>
#include <cmath>

#include "physics/collision/ccd_support.h"
#include "physics/collision/gjk.h"

namespace rbsim {

namespace {

// Below this distance (relative to the solids' size) the cores count as
// touching: the direction between GJK's closest points is then mostly
// rounding, and the overlap path gives a better one.
constexpr double kTouchRatio = 1e-9;

// The core as a solid of its own (a radius-0 sphere is a point, a radius-0
// capsule a segment), for libccd, which only knows support functions.
ConvexGeometry coreGeometry(const ConvexGeometry& geometry) {
  if (std::holds_alternative<SphereShape>(geometry)) return SphereShape{0.0};
  if (const auto* capsule = std::get_if<CapsuleShape>(&geometry))
    return CapsuleShape{0.0, capsule->halfLength};
  return geometry;
}

// Spheres and capsules: their cores (points, segments) have no volume.
bool hasThinCore(const ConvexGeometry& geometry) {
  return coreRadius(geometry) > 0.0;
}

// The unit axis of a capsule's core in the world, or zero for a sphere.
Vec3 coreAxis(const PlacedConvex& piece) {
  return std::holds_alternative<CapsuleShape>(*piece.geometry) ? Vec3(piece.pose.rotation.col(2))
                                                               : Vec3::Zero();
}

Vec3 anyPerpendicular(const Vec3& u) {
  int smallest = 0;
  u.cwiseAbs().minCoeff(&smallest);
  return u.cross(Vec3::Unit(smallest)).normalized();
}

// Two thin cores that cross: their difference (a point, segment or
// parallelogram) holds the origin and has no volume, so the depth is exactly
// rA + rB along any direction normal to it; pick one, pointing from A to B.
Vec3 crossingCoresNormal(const PlacedConvex& a, const PlacedConvex& b) {
  const Vec3 axisA = coreAxis(a);
  const Vec3 axisB = coreAxis(b);
  const Vec3 cross = axisA.cross(axisB);
  Vec3 normal;
  if (cross.norm() > 1e-9) {
    normal = cross.normalized();
  } else if (axisA.squaredNorm() > 0.0 || axisB.squaredNorm() > 0.0) {
    normal = anyPerpendicular(axisA.squaredNorm() > 0.0 ? axisA : axisB);
  } else {
    normal = Vec3::UnitZ();  // concentric spheres: every direction is as good
  }
  return normal.dot(b.pose.translation - a.pose.translation) < 0.0 ? Vec3(-normal) : normal;
}

}  // namespace

SignedDistance signedDistance(const PlacedConvex& a, const PlacedConvex& b,
                              const DistanceSettings& settings) {
  const double radiusA = coreRadius(*a.geometry);
  const double radiusB = coreRadius(*b.geometry);
  // GJK on the cores, the radii added back: exact for spheres and capsules,
  // and a shallow overlap of a sphere or capsule needs no libccd at all.
  const GjkResult cores =
      gjkDistance(a, b, GjkShapes::Cores, GjkSettings{settings.maxIterations, settings.tolerance});
  SignedDistance result;
  result.iterations = cores.iterations;
  result.converged = cores.converged;
  const double scale = std::max(geometrySize(*a.geometry), geometrySize(*b.geometry));

  const bool apart = !cores.overlap && cores.distance > kTouchRatio * scale;
  if (apart || (hasThinCore(*a.geometry) && hasThinCore(*b.geometry))) {
    result.normal =
        apart ? Vec3((cores.pointB - cores.pointA) / cores.distance) : crossingCoresNormal(a, b);
    const double coreDistance = apart ? cores.distance : 0.0;
    result.distance = coreDistance - radiusA - radiusB;
    result.pointA = cores.pointA + radiusA * result.normal;
    result.pointB = cores.pointA + (coreDistance - radiusB) * result.normal;
    return result;
  }

  // The cores overlap: the depth of the cores by libccd, plus the radii (the
  // Minkowski difference is the cores' difference grown by rA + rB, which
  // adds rA + rB to the support function along every direction).
  const ConvexGeometry coreA = coreGeometry(*a.geometry);
  const ConvexGeometry coreB = coreGeometry(*b.geometry);
  const Penetration depth =
      penetration(PlacedConvex{&coreA, a.pose}, PlacedConvex{&coreB, b.pose},
                  PenetrationSettings{settings.maxIterations, settings.penetrationTolerance});
  result.normal = depth.normal;
  result.distance = -(depth.depth + radiusA + radiusB);
  result.pointA = depth.pointA + radiusA * depth.normal;
  result.pointB = depth.pointB - radiusB * depth.normal;
  return result;
}

}  // namespace rbsim
