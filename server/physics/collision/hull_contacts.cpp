// Hull–hull contact (a box enters as boxHull): the separating-axis test
// over both hulls' face normals and over the edge pairs that build a face of
// the Minkowski difference, found with the Gauss-map test (Gregorius, "The
// Separating Axis Test between Convex Polyhedra", GDC 2013), then face
// clipping or one edge–edge point as for boxes (Gregorius, "Robust contact
// creation for physics simulations", GDC 2015).

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "physics/collision/closest_points.h"
#include "physics/collision/contact_routines.h"
#include "physics/collision/polygon_clipping.h"

namespace rbsim {

namespace {

struct AxisQuery {
  double separation = -std::numeric_limits<double>::infinity();  // m
  int first = -1;                                                // face, or edge of A
  int second = -1;                                               // edge of B
  Vec3 axis = Vec3::Zero();  // edge queries: unit, in A's frame, from A towards B
};

// An edge with its two faces: face0 runs start -> end in its
// counter-clockwise loop, face1 runs end -> start.
struct HullEdge {
  int start = 0;
  int end = 0;
  int face0 = 0;
  int face1 = 0;
};

// ConvexHull lists edges without their faces; the Gauss-map test needs them.
// Pairing the directed edges of the face loops finds both at once.
std::vector<HullEdge> edgesWithFaces(const ConvexHull& hull) {
  struct Directed {
    int low, high, start, end, face;
  };
  std::vector<Directed> directed;
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const std::vector<int>& loop = hull.faces[f].vertices;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k];
      const int b = loop[(k + 1) % loop.size()];
      directed.push_back({std::min(a, b), std::max(a, b), a, b, static_cast<int>(f)});
    }
  }
  std::sort(directed.begin(), directed.end(), [](const Directed& x, const Directed& y) {
    if (x.low != y.low) return x.low < y.low;
    if (x.high != y.high) return x.high < y.high;
    return x.face < y.face;
  });
  std::vector<HullEdge> edges;
  edges.reserve(directed.size() / 2);
  for (std::size_t i = 0; i + 1 < directed.size();) {
    const Directed& x = directed[i];
    const Directed& y = directed[i + 1];
    if (x.low == y.low && x.high == y.high) {
      edges.push_back({x.start, x.end, x.face, y.face});
      i += 2;
    } else {
      ++i;  // an edge without its twin (a malformed hull): no axis from it
    }
  }
  return edges;
}

// Do the arcs a–b and c–d of the Gauss map cross? Then the two edges whose
// adjacent face normals they join build a face of the Minkowski difference
// (Gregorius 2013; c and d are B's normals, already negated).
bool isMinkowskiFace(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 bxa = b.cross(a);
  const Vec3 dxc = d.cross(c);
  const double cba = c.dot(bxa);
  const double dba = d.dot(bxa);
  const double adc = a.dot(dxc);
  const double bdc = b.dot(dxc);
  return cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0;
}

// The largest separation of `points` from the planes normal · p = offset.
AxisQuery queryFaces(const std::vector<Vec3>& normals, const std::vector<double>& offsets,
                     const std::vector<Vec3>& points) {
  AxisQuery best;
  for (std::size_t f = 0; f < normals.size(); ++f) {
    double deepest = std::numeric_limits<double>::infinity();
    for (const Vec3& p : points) deepest = std::min(deepest, normals[f].dot(p));
    const double separation = deepest - offsets[f];
    if (separation > best.separation) best = {separation, static_cast<int>(f), -1, Vec3::Zero()};
  }
  return best;
}

std::vector<Vec3> worldPolygon(const ConvexHull& hull, const Transform& pose, int face) {
  std::vector<Vec3> polygon;
  const std::vector<int>& loop = hull.faces[static_cast<std::size_t>(face)].vertices;
  polygon.reserve(loop.size());
  for (const int v : loop)
    polygon.push_back(pose.apply(hull.vertices[static_cast<std::size_t>(v)]));
  return polygon;
}

bool faceContact(const ConvexHull& reference, const Transform& referencePose,
                 const ConvexHull& incident, const Transform& incidentPose, int referenceFace,
                 bool referenceIsA, const ContactSettings& settings, ContactManifold& out) {
  const Vec3 normal =
      referencePose.rotate(reference.faces[static_cast<std::size_t>(referenceFace)].normal);
  const Vec3 local = incidentPose.inverseRotate(normal);
  int incidentFace = 0;
  double mostAntiParallel = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < incident.faces.size(); ++f) {
    const double alignment = incident.faces[f].normal.dot(local);
    if (alignment < mostAntiParallel) {
      mostAntiParallel = alignment;
      incidentFace = static_cast<int>(f);
    }
  }
  const std::vector<Vec3> referencePolygon = worldPolygon(reference, referencePose, referenceFace);
  const std::vector<Vec3> incidentPolygon = worldPolygon(incident, incidentPose, incidentFace);
  std::vector<ContactPoint> candidates;
  candidates.reserve(incidentPolygon.size() + referencePolygon.size());
  const FeatureKind kind = referenceIsA ? FeatureKind::FaceOfA : FeatureKind::FaceOfB;
  clipIncidentFeature(referencePolygon, normal, incidentPolygon, referenceIsA,
                      makeFeatureId(kind, static_cast<uint32_t>(referenceFace),
                                    static_cast<uint32_t>(incidentFace), 0),
                      settings.margin, candidates);
  if (candidates.empty()) return false;
  reduceContacts(candidates, normal, out);
  out.normal = referenceIsA ? normal : Vec3(-normal);
  return true;
}

}  // namespace

bool collideHulls(const ConvexHull& hullA, const Transform& poseA, const ConvexHull& hullB,
                  const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  const double margin = settings.margin;
  // Everything in A's frame.
  const Transform bToA = poseA.inverse() * poseB;
  std::vector<Vec3> verticesB;
  verticesB.reserve(hullB.vertices.size());
  for (const Vec3& v : hullB.vertices) verticesB.push_back(bToA.apply(v));
  std::vector<Vec3> normalsA;
  std::vector<double> offsetsA;
  for (const ConvexHull::Face& face : hullA.faces) {
    normalsA.push_back(face.normal);
    offsetsA.push_back(face.offset);
  }
  std::vector<Vec3> normalsB;
  std::vector<double> offsetsB;
  for (const ConvexHull::Face& face : hullB.faces) {
    normalsB.push_back(bToA.rotate(face.normal));
    offsetsB.push_back(face.offset + normalsB.back().dot(bToA.translation));
  }

  const AxisQuery faceA = queryFaces(normalsA, offsetsA, verticesB);
  if (faceA.separation > margin) return false;
  const AxisQuery faceB = queryFaces(normalsB, offsetsB, hullA.vertices);
  if (faceB.separation > margin) return false;

  Vec3 centroidA = Vec3::Zero();
  for (const Vec3& v : hullA.vertices) centroidA += v;
  centroidA /= static_cast<double>(hullA.vertices.size());
  const std::vector<HullEdge> edgesA = edgesWithFaces(hullA);
  const std::vector<HullEdge> edgesB = edgesWithFaces(hullB);
  AxisQuery edge;
  for (std::size_t i = 0; i < edgesA.size(); ++i) {
    const HullEdge& eA = edgesA[i];
    const Vec3& pA = hullA.vertices[static_cast<std::size_t>(eA.start)];
    const Vec3 dA = hullA.vertices[static_cast<std::size_t>(eA.end)] - pA;
    const Vec3& a = normalsA[static_cast<std::size_t>(eA.face0)];
    const Vec3& b = normalsA[static_cast<std::size_t>(eA.face1)];
    for (std::size_t j = 0; j < edgesB.size(); ++j) {
      const HullEdge& eB = edgesB[j];
      if (!isMinkowskiFace(a, b, -normalsB[static_cast<std::size_t>(eB.face0)],
                           -normalsB[static_cast<std::size_t>(eB.face1)])) {
        continue;
      }
      const Vec3& pB = verticesB[static_cast<std::size_t>(eB.start)];
      const Vec3 dB = verticesB[static_cast<std::size_t>(eB.end)] - pB;
      Vec3 axis = dA.cross(dB);
      const double length = axis.norm();
      if (length < kParallelEdgeSine * dA.norm() * dB.norm()) continue;
      axis /= length;
      if (axis.dot(pA - centroidA) < 0.0) axis = -axis;
      const double separation = axis.dot(pB - pA);
      if (separation > margin) return false;
      if (separation > edge.separation) {
        edge = {separation, static_cast<int>(i), static_cast<int>(j), axis};
      }
    }
  }

  const double faceSeparation = std::max(faceA.separation, faceB.separation);
  if (edge.first >= 0 &&
      edge.separation > kRelativeEdgeTolerance * faceSeparation + kAbsoluteTolerance) {
    const HullEdge& eA = edgesA[static_cast<std::size_t>(edge.first)];
    const HullEdge& eB = edgesB[static_cast<std::size_t>(edge.second)];
    const SegmentClosestPoints closest =
        closestPointsOfSegments(poseA.apply(hullA.vertices[static_cast<std::size_t>(eA.start)]),
                                poseA.apply(hullA.vertices[static_cast<std::size_t>(eA.end)]),
                                poseB.apply(hullB.vertices[static_cast<std::size_t>(eB.start)]),
                                poseB.apply(hullB.vertices[static_cast<std::size_t>(eB.end)]));
    const Vec3 normal = poseA.rotate(edge.axis);
    ContactPoint point;
    point.pointA = closest.onFirst;
    point.pointB = closest.onSecond;
    point.depth = normal.dot(point.pointA - point.pointB);
    point.featureId = makeFeatureId(FeatureKind::EdgeEdge, static_cast<uint32_t>(edge.first),
                                    static_cast<uint32_t>(edge.second), 0);
    if (point.depth < -margin) return false;
    out.normal = normal;
    out.add(point);
    return true;
  }

  if (faceB.separation > kRelativeFaceTolerance * faceA.separation + kAbsoluteTolerance) {
    return faceContact(hullB, poseB, hullA, poseA, faceB.first, false, settings, out);
  }
  return faceContact(hullA, poseA, hullB, poseB, faceA.first, true, settings, out);
}

}  // namespace rbsim
