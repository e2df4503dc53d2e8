// Box–box contact: the separating-axis test over the 15 candidate axes
// (Ericson, "Real-Time Collision Detection", §4.4.1; Gottschalk's OBB test),
// then either a face contact by clipping the incident face against the
// reference face's sides, or one edge–edge point (Gregorius, "Robust contact
// creation for physics simulations", GDC 2015; the same scheme as ODE's
// dBoxBox and qu3e's q3BoxtoBox).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "physics/collision/box_features.h"
#include "physics/collision/closest_points.h"
#include "physics/collision/contact_routines.h"
#include "physics/collision/polygon_clipping.h"

namespace rbsim {

namespace {

struct AxisQuery {
  double separation = -std::numeric_limits<double>::infinity();  // m
  int index = -1;
  Vec3 axis = Vec3::Zero();  // edge queries: unit, in A's frame, from A towards B
};

std::array<Vec3, 4> worldFace(const Vec3& halfExtents, const Transform& pose, int face) {
  const std::array<int, 4> corners = boxFaceVertices(face);
  std::array<Vec3, 4> polygon;
  for (std::size_t k = 0; k < 4; ++k) polygon[k] = pose.apply(boxVertex(halfExtents, corners[k]));
  return polygon;
}

bool faceContact(const Vec3& halfRef, const Transform& poseRef, const Vec3& halfInc,
                 const Transform& poseInc, int referenceAxis, bool referenceIsA,
                 const ContactSettings& settings, ContactManifold& out) {
  const Vec3 axis = poseRef.rotation.col(referenceAxis);
  const bool negative = axis.dot(poseInc.translation - poseRef.translation) < 0.0;
  const int referenceFace = boxFaceIndex(referenceAxis, negative);
  const Vec3 referenceNormal = negative ? Vec3(-axis) : axis;

  // The incident face is the one most anti-parallel to the reference normal.
  const Vec3 local = poseInc.inverseRotate(referenceNormal);
  int incidentAxis = 0;
  local.cwiseAbs().maxCoeff(&incidentAxis);
  const int incidentFace = boxFaceIndex(incidentAxis, local[incidentAxis] > 0.0);

  const std::array<Vec3, 4> reference = worldFace(halfRef, poseRef, referenceFace);
  const std::array<Vec3, 4> incident = worldFace(halfInc, poseInc, incidentFace);
  std::vector<ContactPoint> candidates;
  candidates.reserve(8);
  const FeatureKind kind = referenceIsA ? FeatureKind::FaceOfA : FeatureKind::FaceOfB;
  clipIncidentFeature(reference, referenceNormal, incident, referenceIsA,
                      makeFeatureId(kind, static_cast<uint32_t>(referenceFace),
                                    static_cast<uint32_t>(incidentFace), 0),
                      settings.margin, candidates);
  if (candidates.empty()) return false;
  reduceContacts(candidates, referenceNormal, out);
  out.normal = referenceIsA ? referenceNormal : Vec3(-referenceNormal);
  return true;
}

// The edge of a box along `axis` that is farthest along `direction` (box
// frame), as its two ends, and an id: axis and the signs of the other two.
struct BoxEdge {
  Vec3 start;
  Vec3 end;
  uint32_t id = 0;
};
BoxEdge supportEdge(const Vec3& halfExtents, int axis, const Vec3& direction) {
  Vec3 middle = Vec3::Zero();
  uint32_t signs = 0;
  for (int k = 1; k <= 2; ++k) {
    const int other = (axis + k) % 3;
    const bool positive = direction[other] >= 0.0;
    middle[other] = positive ? halfExtents[other] : -halfExtents[other];
    if (positive) signs |= 1u << (k - 1);
  }
  Vec3 along = Vec3::Zero();
  along[axis] = halfExtents[axis];
  return {middle - along, middle + along, static_cast<uint32_t>(axis) * 4u + signs};
}

}  // namespace

bool collideBoxes(const BoxShape& boxA, const Transform& poseA, const BoxShape& boxB,
                  const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  const Vec3& hA = boxA.halfExtents;
  const Vec3& hB = boxB.halfExtents;
  // Everything in A's frame: B's axes are the columns of r, its centre t.
  const Mat3 r = poseA.rotation.transpose() * poseB.rotation;
  const Mat3 absR = r.cwiseAbs();
  const Vec3 t = poseA.inverseRotate(poseB.translation - poseA.translation);
  const double margin = settings.margin;

  AxisQuery faceA;
  for (int i = 0; i < 3; ++i) {
    const double separation = std::abs(t[i]) - (hA[i] + absR.row(i).dot(hB));
    if (separation > margin) return false;
    if (separation > faceA.separation) faceA = {separation, i, Vec3::Zero()};
  }
  AxisQuery faceB;
  for (int j = 0; j < 3; ++j) {
    const double separation = std::abs(t.dot(r.col(j))) - (absR.col(j).dot(hA) + hB[j]);
    if (separation > margin) return false;
    if (separation > faceB.separation) faceB = {separation, j, Vec3::Zero()};
  }
  AxisQuery edge;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Vec3 axis = Vec3::Unit(i).cross(r.col(j));
      const double length = axis.norm();
      if (length < kParallelEdgeSine) continue;
      axis /= length;
      if (axis.dot(t) < 0.0) axis = -axis;
      const double separation =
          axis.dot(t) - axis.cwiseAbs().dot(hA) - (r.transpose() * axis).cwiseAbs().dot(hB);
      if (separation > margin) return false;
      if (separation > edge.separation) edge = {separation, 3 * i + j, axis};
    }
  }

  const double faceSeparation = std::max(faceA.separation, faceB.separation);
  if (edge.index >= 0 &&
      edge.separation > kRelativeEdgeTolerance * faceSeparation + kAbsoluteTolerance) {
    const int i = edge.index / 3;
    const int j = edge.index % 3;
    const BoxEdge onA = supportEdge(hA, i, edge.axis);
    const BoxEdge onB = supportEdge(hB, j, -(r.transpose() * edge.axis));
    const SegmentClosestPoints closest = closestPointsOfSegments(
        poseA.apply(onA.start), poseA.apply(onA.end), poseB.apply(onB.start), poseB.apply(onB.end));
    const Vec3 normal = poseA.rotate(edge.axis);
    ContactPoint point;
    point.pointA = closest.onFirst;
    point.pointB = closest.onSecond;
    point.depth = normal.dot(point.pointA - point.pointB);
    point.featureId = makeFeatureId(FeatureKind::EdgeEdge, onA.id, onB.id, 0);
    if (point.depth < -margin) return false;
    out.normal = normal;
    out.add(point);
    return true;
  }

  if (faceB.separation > kRelativeFaceTolerance * faceA.separation + kAbsoluteTolerance) {
    return faceContact(hB, poseB, hA, poseA, faceB.index, false, settings, out);
  }
  return faceContact(hA, poseA, hB, poseB, faceA.index, true, settings, out);
}

}  // namespace rbsim
