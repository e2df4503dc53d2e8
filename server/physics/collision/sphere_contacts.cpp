// Contacts of a sphere with the other primitives: the closest point of the
// other solid to the sphere's centre (Ericson, "Real-Time Collision
// Detection", §5.1), one contact point. A centre inside the other solid
// leaves by the nearest face, the minimum-translation direction.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "physics/collision/closest_points.h"
#include "physics/collision/contact_routines.h"

namespace rbsim {

namespace {

// Below this distance (m) two points coincide and give no direction.
constexpr double kCoincident = 1e-12;

// One contact between a point q on the surface of A and a sphere around
// `center` on the side of `normal` (unit, A -> sphere).
bool addSphereContact(const Vec3& q, const Vec3& normal, double depth, const Vec3& center,
                      double radius, uint32_t featureId, const ContactSettings& settings,
                      ContactManifold& out) {
  if (depth < -settings.margin) return false;
  ContactPoint point;
  point.pointA = q;
  point.pointB = center - radius * normal;
  point.depth = depth;
  point.featureId = featureId;
  out.normal = normal;
  out.add(point);
  return true;
}

}  // namespace

bool collideSpheres(const Vec3& centerA, double radiusA, const Vec3& centerB, double radiusB,
                    const ContactSettings& settings, ContactManifold& out) {
  const Vec3 offset = centerB - centerA;
  const double distance = offset.norm();
  if (distance > radiusA + radiusB + settings.margin) return false;
  // Concentric spheres have no preferred direction: push along +z.
  const Vec3 normal = distance > kCoincident ? Vec3(offset / distance) : Vec3::UnitZ();
  return addSphereContact(centerA + radiusA * normal, normal, radiusA + radiusB - distance, centerB,
                          radiusB, makeFeatureId(FeatureKind::Other, 0, 0, 0), settings, out);
}

bool collideBoxSphere(const BoxShape& box, const Transform& boxPose, const Vec3& center,
                      double radius, const ContactSettings& settings, ContactManifold& out) {
  const Vec3& h = box.halfExtents;
  const Vec3 local = boxPose.applyInverse(center);
  const Vec3 clamped = local.cwiseMax(-h).cwiseMin(h);
  const Vec3 offset = local - clamped;
  const double distance = offset.norm();
  if (distance > kCoincident) {
    if (distance > radius + settings.margin) return false;
    // The Voronoi region (face, edge or corner) is the feature: per axis
    // inside, below or above the slab.
    uint32_t region = 0;
    for (int k = 2; k >= 0; --k) {
      region = 3 * region + (local[k] < -h[k] ? 1u : local[k] > h[k] ? 2u : 0u);
    }
    return addSphereContact(boxPose.apply(clamped), boxPose.rotate(offset / distance),
                            radius - distance, center, radius,
                            makeFeatureId(FeatureKind::Other, region, 0, 0), settings, out);
  }
  // The centre is inside: leave through the nearest face.
  const Vec3 gaps = h - local.cwiseAbs();
  int axis = 0;
  gaps.minCoeff(&axis);
  const bool negative = local[axis] < 0.0;
  Vec3 onFace = local;
  onFace[axis] = negative ? -h[axis] : h[axis];
  Vec3 normal = Vec3::Zero();
  normal[axis] = negative ? -1.0 : 1.0;
  return addSphereContact(
      boxPose.apply(onFace), boxPose.rotate(normal), radius + gaps[axis], center, radius,
      makeFeatureId(FeatureKind::Other,
                    27u + 2u * static_cast<uint32_t>(axis) + (negative ? 1u : 0u), 0, 0),
      settings, out);
}

bool collideCapsuleSphere(const CapsuleShape& capsule, const Transform& capsulePose,
                          const Vec3& center, double radius, const ContactSettings& settings,
                          ContactManifold& out) {
  const Vec3 start = capsulePose.apply(Vec3(0.0, 0.0, -capsule.halfLength));
  const Vec3 end = capsulePose.apply(Vec3(0.0, 0.0, capsule.halfLength));
  return collideSpheres(closestPointOnSegment(center, start, end), capsule.radius, center, radius,
                        settings, out);
}

bool collideCylinderSphere(const CylinderShape& cylinder, const Transform& cylinderPose,
                           const Vec3& center, double radius, const ContactSettings& settings,
                           ContactManifold& out) {
  const Vec3 local = cylinderPose.applyInverse(center);
  const double radial = std::hypot(local.x(), local.y());
  const double h = cylinder.halfLength;
  const double r = cylinder.radius;
  if (radial > r || std::abs(local.z()) > h) {
    Vec3 closest = local;
    if (radial > r) {
      closest.x() *= r / radial;
      closest.y() *= r / radial;
    }
    closest.z() = std::clamp(local.z(), -h, h);
    const Vec3 offset = local - closest;
    const double distance = offset.norm();
    if (distance > radius + settings.margin) return false;
    const uint32_t region = (radial > r ? 1u : 0u) + (local.z() > h    ? 2u
                                                      : local.z() < -h ? 4u
                                                                       : 0u);
    return addSphereContact(cylinderPose.apply(closest), cylinderPose.rotate(offset / distance),
                            radius - distance, center, radius,
                            makeFeatureId(FeatureKind::Other, region, 0, 0), settings, out);
  }
  // Inside: out through the nearer of the cap and the side.
  const double capGap = h - std::abs(local.z());
  const double sideGap = r - radial;
  Vec3 normal;
  Vec3 onSurface = local;
  uint32_t region = 0;
  if (capGap <= sideGap) {
    normal = local.z() < 0.0 ? Vec3(-Vec3::UnitZ()) : Vec3::UnitZ();
    onSurface.z() = local.z() < 0.0 ? -h : h;
    region = local.z() < 0.0 ? 8u : 9u;
  } else {
    normal =
        radial > kCoincident ? Vec3(local.x() / radial, local.y() / radial, 0.0) : Vec3::UnitX();
    onSurface.head<2>() = r * normal.head<2>();
    region = 10u;
  }
  return addSphereContact(cylinderPose.apply(onSurface), cylinderPose.rotate(normal),
                          radius + std::min(capGap, sideGap), center, radius,
                          makeFeatureId(FeatureKind::Other, region, 0, 0), settings, out);
}

bool collideHullSphere(const ConvexHull& hull, const Transform& hullPose, const Vec3& center,
                       double radius, const ContactSettings& settings, ContactManifold& out) {
  const Vec3 local = hullPose.applyInverse(center);
  double bestSeparation = -std::numeric_limits<double>::infinity();
  std::size_t bestFace = 0;
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const double separation = hull.faces[f].normal.dot(local) - hull.faces[f].offset;
    if (separation > bestSeparation) {
      bestSeparation = separation;
      bestFace = f;
    }
  }
  // A face's separation never exceeds the distance: a cheap early out.
  if (bestSeparation > radius + settings.margin) return false;
  if (bestSeparation <= 0.0) {
    const Vec3& normal = hull.faces[bestFace].normal;
    return addSphereContact(
        hullPose.apply(local - bestSeparation * normal), hullPose.rotate(normal),
        radius - bestSeparation, center, radius,
        makeFeatureId(FeatureKind::Other, static_cast<uint32_t>(bestFace), 1, 0), settings, out);
  }
  // Outside: the closest point lies on one of the faces that see the centre.
  Vec3 closest = Vec3::Zero();
  double closestDistanceSquared = std::numeric_limits<double>::infinity();
  std::vector<Vec3> polygon;
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const ConvexHull::Face& face = hull.faces[f];
    if (face.normal.dot(local) - face.offset <= 0.0) continue;
    polygon.clear();
    for (const int v : face.vertices) polygon.push_back(hull.vertices[static_cast<std::size_t>(v)]);
    const Vec3 q = closestPointOnConvexPolygon(local, polygon, face.normal);
    const double distanceSquared = (local - q).squaredNorm();
    if (distanceSquared < closestDistanceSquared) {
      closestDistanceSquared = distanceSquared;
      closest = q;
      bestFace = f;
    }
  }
  const double distance = std::sqrt(closestDistanceSquared);
  if (distance > radius + settings.margin) return false;
  return addSphereContact(hullPose.apply(closest), hullPose.rotate((local - closest) / distance),
                          radius - distance, center, radius,
                          makeFeatureId(FeatureKind::Other, static_cast<uint32_t>(bestFace), 2, 0),
                          settings, out);
}

}  // namespace rbsim
