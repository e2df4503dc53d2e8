// Capsule contacts. A capsule is a segment (its core) grown by a radius, so
// each contact is a core–feature query plus the radius (Box2D v3's
// b2CollideCapsules and b2CollideCapsuleAndPolygon, lifted to 3D):
//  - apart cores: the exact closest points, one contact; two when the core
//    lies parallel to the other's segment or to a hull face, so that a
//    lying capsule rests instead of rocking on one point;
//  - crossing cores (only a hull can swallow a core): the separating axes
//    of the segment and the hull, and face clipping (Gregorius, "Robust
//    contact creation for physics simulations", GDC 2015).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "physics/collision/closest_points.h"
#include "physics/collision/contact_routines.h"
#include "physics/collision/polygon_clipping.h"

namespace rbsim {

namespace {

// Below this distance (m) two points coincide and give no direction.
constexpr double kCoincident = 1e-12;

struct Segment {
  Vec3 start;
  Vec3 end;
};

Segment capsuleCore(const CapsuleShape& capsule, const Transform& pose) {
  return {pose.apply(Vec3(0.0, 0.0, -capsule.halfLength)),
          pose.apply(Vec3(0.0, 0.0, capsule.halfLength))};
}

bool parallel(const Vec3& u, const Vec3& v) {
  const double lengths = u.norm() * v.norm();
  return lengths > 0.0 && u.cross(v).norm() <= kFlatSine * lengths;
}

// The capsule (core in the hull's frame) lying on hull face `face`: its
// lowest line clipped to the face. World results.
bool addLyingOnFace(const ConvexHull& hull, const Transform& hullPose, std::size_t face,
                    const Segment& core, double radius, const ContactSettings& settings,
                    ContactManifold& out) {
  const ConvexHull::Face& hullFace = hull.faces[face];
  std::vector<Vec3> polygon;
  polygon.reserve(hullFace.vertices.size());
  for (const int v : hullFace.vertices) {
    polygon.push_back(hullPose.apply(hull.vertices[static_cast<std::size_t>(v)]));
  }
  const Vec3 normal = hullPose.rotate(hullFace.normal);
  const std::array<Vec3, 2> lowest{hullPose.apply(core.start) - radius * normal,
                                   hullPose.apply(core.end) - radius * normal};
  std::vector<ContactPoint> candidates;
  clipIncidentFeature(polygon, normal, lowest, true,
                      makeFeatureId(FeatureKind::FaceOfA, static_cast<uint32_t>(face), 0, 0),
                      settings.margin, candidates);
  if (candidates.empty()) return false;
  reduceContacts(candidates, normal, out);
  out.normal = normal;
  return true;
}

// One contact between hull point q and core point c (hull frame) along the
// unit `normal` (hull -> capsule).
bool addSinglePoint(const Transform& hullPose, const Vec3& q, const Vec3& c, const Vec3& normal,
                    double radius, uint32_t featureId, const ContactSettings& settings,
                    ContactManifold& out) {
  ContactPoint point;
  point.pointA = hullPose.apply(q);
  point.pointB = hullPose.apply(c - radius * normal);
  point.depth = radius - normal.dot(c - q);
  point.featureId = featureId;
  if (point.depth < -settings.margin) return false;
  out.normal = hullPose.rotate(normal);
  out.add(point);
  return true;
}

bool insideFace(const ConvexHull& hull, const ConvexHull::Face& face, const Vec3& p) {
  const std::size_t count = face.vertices.size();
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3& a = hull.vertices[static_cast<std::size_t>(face.vertices[k])];
    const Vec3& b = hull.vertices[static_cast<std::size_t>(face.vertices[(k + 1) % count])];
    if ((b - a).cross(face.normal).dot(p - a) > 0.0) return false;
  }
  return true;
}

// The closest points of a segment and a hull that it does not touch:
// either a segment end over a face, or a point of a hull edge.
struct ClosestFeatures {
  Vec3 onHull = Vec3::Zero();
  Vec3 onSegment = Vec3::Zero();
  double distance = std::numeric_limits<double>::infinity();
  int edge = -1;  // the hull edge, when the closest hull point is on one
  int face = -1;  // the hull face, when it is inside one
};

ClosestFeatures closestToSegment(const ConvexHull& hull, const Segment& core) {
  ClosestFeatures best;
  for (const Vec3& p : {core.start, core.end}) {
    for (std::size_t f = 0; f < hull.faces.size(); ++f) {
      const ConvexHull::Face& face = hull.faces[f];
      const double height = face.normal.dot(p) - face.offset;
      if (height > 0.0 && height < best.distance && insideFace(hull, face, p)) {
        best = {p - height * face.normal, p, height, -1, static_cast<int>(f)};
      }
    }
  }
  for (std::size_t e = 0; e < hull.edges.size(); ++e) {
    const Vec3& v0 = hull.vertices[static_cast<std::size_t>(hull.edges[e][0])];
    const Vec3& v1 = hull.vertices[static_cast<std::size_t>(hull.edges[e][1])];
    const SegmentClosestPoints closest = closestPointsOfSegments(v0, v1, core.start, core.end);
    const double distance = (closest.onSecond - closest.onFirst).norm();
    if (distance < best.distance) {
      best = {closest.onFirst, closest.onSecond, distance, static_cast<int>(e), -1};
    }
  }
  return best;
}

}  // namespace

int addSideBySide(const Vec3& startA, const Vec3& endA, double radiusA, const Vec3& startB,
                  const Vec3& endB, double radiusB, const Vec3& normal, uint32_t featureBase,
                  const ContactSettings& settings, ContactManifold& out) {
  const Vec3 along = endA - startA;
  const double length = along.norm();
  if (length <= kCoincident) return 0;
  const Vec3 unit = along / length;
  const double s0 = unit.dot(startB - startA);
  const double s1 = unit.dot(endB - startA);
  const std::array<double, 2> ends{std::max(0.0, std::min(s0, s1)),
                                   std::min(length, std::max(s0, s1))};
  if (ends[1] - ends[0] <= kCoincident) return 0;
  int added = 0;
  for (std::size_t k = 0; k < 2; ++k) {
    const Vec3 onA = startA + ends[k] * unit;
    const Vec3 onB = closestPointOnSegment(onA, startB, endB);
    ContactPoint point;
    point.pointA = onA + radiusA * normal;
    point.pointB = onB - radiusB * normal;
    point.depth = normal.dot(point.pointA - point.pointB);
    point.featureId = featureBase | static_cast<uint32_t>(k);
    if (point.depth >= -settings.margin) {
      out.add(point);
      ++added;
    }
  }
  if (added > 0) out.normal = normal;
  return added;
}

bool collideCapsules(const CapsuleShape& capsuleA, const Transform& poseA,
                     const CapsuleShape& capsuleB, const Transform& poseB,
                     const ContactSettings& settings, ContactManifold& out) {
  const Segment a = capsuleCore(capsuleA, poseA);
  const Segment b = capsuleCore(capsuleB, poseB);
  const double radii = capsuleA.radius + capsuleB.radius;
  const SegmentClosestPoints closest = closestPointsOfSegments(a.start, a.end, b.start, b.end);
  const Vec3 offset = closest.onSecond - closest.onFirst;
  const double distance = offset.norm();
  if (distance > radii + settings.margin) return false;

  const Vec3 dA = a.end - a.start;
  const Vec3 dB = b.end - b.start;
  Vec3 normal;
  if (distance > kCoincident) {
    normal = offset / distance;
  } else {
    // Crossing cores: the common perpendicular, away from A's centre.
    const Vec3 cross = dA.cross(dB);
    normal = cross.norm() > kCoincident ? Vec3(cross.normalized())
             : dA.norm() > kCoincident  ? unitPerpendicular(dA.normalized())
                                        : Vec3::UnitZ();
    if (normal.dot(poseB.translation - poseA.translation) < 0.0) normal = -normal;
  }

  if (parallel(dA, dB)) {
    // Side by side: the normal perpendicular to A, as it is for the
    // interior points of exactly parallel cores.
    const Vec3 unit = dA.normalized();
    const Vec3 perpendicular = normal - normal.dot(unit) * unit;
    if (perpendicular.norm() > kFlatSine) {
      const uint32_t base = makeFeatureId(FeatureKind::EdgeEdge, 0, 0, 0);
      if (addSideBySide(a.start, a.end, capsuleA.radius, b.start, b.end, capsuleB.radius,
                        perpendicular.normalized(), base, settings, out) > 0) {
        return true;
      }
    }
  }

  ContactPoint point;
  point.pointA = closest.onFirst + capsuleA.radius * normal;
  point.pointB = closest.onSecond - capsuleB.radius * normal;
  point.depth = radii - normal.dot(offset);
  point.featureId = makeFeatureId(FeatureKind::Other, 0, 0, 0);
  out.normal = normal;
  out.add(point);
  return true;
}

bool collideHullCapsule(const ConvexHull& hull, const Transform& hullPose,
                        const CapsuleShape& capsule, const Transform& capsulePose,
                        const ContactSettings& settings, ContactManifold& out) {
  const double margin = settings.margin;
  const double radius = capsule.radius;
  // The core in the hull's frame.
  const Transform capsuleToHull = hullPose.inverse() * capsulePose;
  const Segment core = capsuleCore(capsule, capsuleToHull);
  const Vec3 along = core.end - core.start;

  // Separating axes of segment and hull: the hull's faces, then each hull
  // edge crossed with the segment.
  double faceSeparation = -std::numeric_limits<double>::infinity();
  std::size_t bestFace = 0;
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const ConvexHull::Face& face = hull.faces[f];
    const double separation =
        std::min(face.normal.dot(core.start), face.normal.dot(core.end)) - face.offset;
    if (separation > faceSeparation) {
      faceSeparation = separation;
      bestFace = f;
    }
  }
  if (faceSeparation > radius + margin) return false;
  double edgeSeparation = -std::numeric_limits<double>::infinity();
  std::size_t bestEdge = 0;
  Vec3 edgeAxis = Vec3::Zero();
  for (std::size_t e = 0; e < hull.edges.size(); ++e) {
    const Vec3& v0 = hull.vertices[static_cast<std::size_t>(hull.edges[e][0])];
    const Vec3 edge = hull.vertices[static_cast<std::size_t>(hull.edges[e][1])] - v0;
    Vec3 axis = edge.cross(along);
    const double length = axis.norm();
    if (length < kParallelEdgeSine * edge.norm() * along.norm()) continue;
    axis /= length;
    double hullMin = std::numeric_limits<double>::infinity();
    double hullMax = -hullMin;
    for (const Vec3& v : hull.vertices) {
      hullMin = std::min(hullMin, axis.dot(v));
      hullMax = std::max(hullMax, axis.dot(v));
    }
    const double coreMin = std::min(axis.dot(core.start), axis.dot(core.end));
    const double coreMax = std::max(axis.dot(core.start), axis.dot(core.end));
    double separation = coreMin - hullMax;
    if (hullMin - coreMax > separation) {
      separation = hullMin - coreMax;
      axis = -axis;
    }
    if (separation > radius + margin) return false;
    if (separation > edgeSeparation) {
      edgeSeparation = separation;
      bestEdge = e;
      edgeAxis = axis;
    }
  }

  if (std::max(faceSeparation, edgeSeparation) > 0.0) {
    // The core is outside the hull: exact closest points.
    const ClosestFeatures closest = closestToSegment(hull, core);
    if (closest.distance > radius + margin) return false;
    if (closest.distance > kCoincident) {
      const Vec3 normal = (closest.onSegment - closest.onHull) / closest.distance;
      std::size_t facing = 0;
      for (std::size_t f = 1; f < hull.faces.size(); ++f) {
        if (hull.faces[f].normal.dot(normal) > hull.faces[facing].normal.dot(normal)) facing = f;
      }
      const Vec3& faceNormal = hull.faces[facing].normal;
      if (faceNormal.dot(normal) >= kFlatCosine &&
          std::abs(faceNormal.dot(along)) <= kFlatSine * along.norm() &&
          addLyingOnFace(hull, hullPose, facing, core, radius, settings, out)) {
        return true;
      }
      if (closest.edge >= 0) {
        const auto& edge = hull.edges[static_cast<std::size_t>(closest.edge)];
        const Segment hullEdge{hullPose.apply(hull.vertices[static_cast<std::size_t>(edge[0])]),
                               hullPose.apply(hull.vertices[static_cast<std::size_t>(edge[1])])};
        const Segment worldCore{hullPose.apply(core.start), hullPose.apply(core.end)};
        if (parallel(hullEdge.end - hullEdge.start, along) &&
            addSideBySide(
                hullEdge.start, hullEdge.end, 0.0, worldCore.start, worldCore.end, radius,
                hullPose.rotate(normal),
                makeFeatureId(FeatureKind::EdgeEdge, static_cast<uint32_t>(closest.edge), 0, 0),
                settings, out) > 0) {
          return true;
        }
      }
      const uint32_t feature = closest.edge >= 0 ? static_cast<uint32_t>(closest.edge)
                                                 : static_cast<uint32_t>(closest.face);
      return addSinglePoint(
          hullPose, closest.onHull, closest.onSegment, normal, radius,
          makeFeatureId(FeatureKind::Other, feature, closest.edge >= 0 ? 1u : 2u, 0), settings,
          out);
    }
  }

  // The core crosses the hull: the axis of least penetration, faces preferred.
  if (edgeSeparation > kRelativeEdgeTolerance * faceSeparation + kAbsoluteTolerance) {
    const auto& edge = hull.edges[bestEdge];
    const SegmentClosestPoints closest = closestPointsOfSegments(
        hull.vertices[static_cast<std::size_t>(edge[0])],
        hull.vertices[static_cast<std::size_t>(edge[1])], core.start, core.end);
    return addSinglePoint(
        hullPose, closest.onFirst, closest.onSecond, edgeAxis, radius,
        makeFeatureId(FeatureKind::EdgeEdge, static_cast<uint32_t>(bestEdge), 0, 0), settings, out);
  }
  if (addLyingOnFace(hull, hullPose, bestFace, core, radius, settings, out)) return true;
  // The core pokes through the face outside its sides: its deeper end.
  const ConvexHull::Face& face = hull.faces[bestFace];
  const Vec3& deeper =
      face.normal.dot(core.start) <= face.normal.dot(core.end) ? core.start : core.end;
  const Vec3 onFace = deeper - (face.normal.dot(deeper) - face.offset) * face.normal;
  return addSinglePoint(hullPose, onFace, deeper, face.normal, radius,
                        makeFeatureId(FeatureKind::Other, static_cast<uint32_t>(bestFace), 3, 0),
                        settings, out);
}

}  // namespace rbsim
