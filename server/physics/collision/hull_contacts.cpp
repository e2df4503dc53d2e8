// Hull–hull contact (a box enters as boxHull): the separating-axis test
// over both hulls' face normals and over the edge pairs that build a face of
// the Minkowski difference, found with the Gauss-map test (Gregorius, "The
// Separating Axis Test between Convex Polyhedra", GDC 2013), then face
// clipping or one edge–edge point as for boxes (Gregorius, "Robust contact
// creation for physics simulations", GDC 2015).
//
// Two ways to the same answer. Small pairs test every face against every
// vertex and every edge pair (collideHullsExhaustive). Larger pairs
// (meshes of hundreds of vertices, where that costs milliseconds) first ask
// GJK how far apart the hulls are, then test only the faces and edge pairs
// that can decide the answer; each shortcut is a bound, so the result is the
// exhaustive test's (see collideHulls below for each argument).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <cstddef>
#include <limits>
#include <vector>

#include "physics/collision/ccd_support.h"
#include "physics/collision/closest_points.h"
#include "physics/collision/gjk.h"
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

// Do the arcs a–b and c–d of the Gauss map cross? Then the two edges whose
// adjacent face normals they join build a face of the Minkowski difference
// (Gregorius 2013; c and d are B's normals, already negated). bxa = b × a
// and dxc = d × c belong to one edge each, so callers compute them once.
bool isMinkowskiFace(const Vec3& a, const Vec3& b, const Vec3& bxa, const Vec3& c, const Vec3& d,
                     const Vec3& dxc) {
  const double cba = c.dot(bxa);
  const double dba = d.dot(bxa);
  if (!(cba * dba < 0.0)) return false;
  const double adc = a.dot(dxc);
  const double bdc = b.dot(dxc);
  return adc * bdc < 0.0 && cba * bdc > 0.0;
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


// Everything below works in A's frame: B's vertices and normals are brought
// there by bToA.
struct HullPair {
  const ConvexHull& a;
  const ConvexHull& b;
  Transform bToA;
  double margin;
  // B's face normals and vertices in A's frame when the caller has them
  // all (the exhaustive test); null: each is brought over when needed.
  const std::vector<Vec3>* normalsB = nullptr;
  const std::vector<Vec3>* verticesB = nullptr;

  Vec3 normalB(int face) const {
    const std::size_t f = static_cast<std::size_t>(face);
    return normalsB ? (*normalsB)[f] : Vec3(bToA.rotate(b.faceNormals[f]));
  }
  Vec3 vertexB(int vertex) const {
    const std::size_t v = static_cast<std::size_t>(vertex);
    return verticesB ? (*verticesB)[v] : Vec3(bToA.apply(b.vertices[v]));
  }
};

// What the edge pairs' test needs of one edge, in A's frame: its Gauss-map
// arc (the normals of its faces, negated for B, and their cross product)
// and its segment.
struct EdgeData {
  Vec3 normal0;
  Vec3 normal1;
  Vec3 arcCross;  // normal1 × normal0
  Vec3 start;
  Vec3 along;  // end − start
  double length;
};

EdgeData edgeDataOfA(const HullPair& pair, int i) {
  const ConvexHull::FaceEdge& e = pair.a.faceEdges[static_cast<std::size_t>(i)];
  EdgeData data;
  data.normal0 = pair.a.faceNormals[static_cast<std::size_t>(e.face0)];
  data.normal1 = pair.a.faceNormals[static_cast<std::size_t>(e.face1)];
  data.arcCross = data.normal1.cross(data.normal0);
  data.start = pair.a.vertices[static_cast<std::size_t>(e.start)];
  data.along = pair.a.vertices[static_cast<std::size_t>(e.end)] - data.start;
  data.length = data.along.norm();
  return data;
}

EdgeData edgeDataOfB(const HullPair& pair, int j) {
  const ConvexHull::FaceEdge& e = pair.b.faceEdges[static_cast<std::size_t>(j)];
  EdgeData data;
  data.normal0 = -pair.normalB(e.face0);
  data.normal1 = -pair.normalB(e.face1);
  data.arcCross = data.normal1.cross(data.normal0);
  data.start = pair.vertexB(e.start);
  data.along = pair.vertexB(e.end) - data.start;
  data.length = data.along.norm();
  return data;
}

// The result of an edge query: the deepest edge axis, or a proof of
// separation (an edge axis farther than the margin).
struct EdgeQuery {
  AxisQuery best;
  bool separated = false;
};

// Tests A's edges `edgesA` against B's `edgesB`, both ascending, in the
// exhaustive test's order: the first pair of the largest separation wins.
// A pair counts if its arcs cross on the Gauss map (a face of the
// Minkowski difference) and the edges are not parallel; its axis points
// away from A.
EdgeQuery queryEdgePairs(const HullPair& pair, const std::vector<int>& edgesA,
                         const std::vector<int>& edgesB) {
  thread_local std::vector<EdgeData> dataB;
  dataB.clear();
  for (const int j : edgesB) dataB.push_back(edgeDataOfB(pair, j));
  EdgeQuery query;
  for (const int i : edgesA) {
    const EdgeData a = edgeDataOfA(pair, i);
    for (std::size_t k = 0; k < dataB.size(); ++k) {
      const EdgeData& b = dataB[k];
      if (!isMinkowskiFace(a.normal0, a.normal1, a.arcCross, b.normal0, b.normal1, b.arcCross))
        continue;
      Vec3 axis = a.along.cross(b.along);
      const double length = axis.norm();
      if (length < kParallelEdgeSine * a.length * b.length) continue;
      axis /= length;
      if (axis.dot(a.start - pair.a.centroid) < 0.0) axis = -axis;
      const double separation = axis.dot(b.start - a.start);
      if (separation > pair.margin) {
        query.separated = true;
        return query;
      }
      if (separation > query.best.separation) query.best = {separation, i, edgesB[k], axis};
    }
  }
  return query;
}

// Faces within 1e-9 m of the running best are examined rather than
// skipped, so that rounding in the bound never hides the deepest face.
constexpr double kBoundSlack = 1e-9;  // m

// The face of `faces` whose plane `points` (placed by pointsToFaces, in
// the faces' frame) lies farthest outside, as queryFaces finds it, but
// examining only the faces that can win. Every face's separation is at
// most its plane's distance to any point of `points`: to the probe, the
// vertex of `points` deepest towards the faces' hull along `towards` (unit,
// faces' frame, from the faces' hull to the points' hull). A face whose
// bound is below a separation already found cannot be the deepest and is
// skipped; the others descend over `points`' vertex graph from the probe
// to the lowest vertex along the face normal. When the hulls overlap
// deeply the probe lies deep inside and leaves many faces; their bounds
// are then tightened with four more probes, deepest along directions
// tilted off `towards`, and each descends from its nearest probe.
AxisQuery queryFacesNear(const ConvexHull& faces, const ConvexHull& points,
                         const Transform& pointsToFaces, const Vec3& towards) {
  const auto probeAlong = [&](const Vec3& direction) {
    return supportVertex(points, pointsToFaces.inverseRotate(-direction));
  };
  const auto placed = [&](int vertex) {
    return Vec3(pointsToFaces.apply(points.vertices[static_cast<std::size_t>(vertex)]));
  };
  const int probe = probeAlong(towards);
  const Vec3 probePoint = placed(probe);
  thread_local std::vector<double> bounds;
  thread_local std::vector<int> starts;
  const std::size_t faceCount = faces.faceNormals.size();
  bounds.resize(faceCount);
  starts.assign(faceCount, probe);
  std::size_t loosest = 0;
  for (std::size_t f = 0; f < faceCount; ++f) {
    bounds[f] = faces.faceNormals[f].dot(probePoint) - faces.faceOffsets[f];
    if (bounds[f] > bounds[loosest]) loosest = f;
  }
  const auto separation = [&](std::size_t f) {
    const Vec3& normal = faces.faceNormals[f];
    const Vec3 local = pointsToFaces.inverseRotate(normal);
    const int lowest = lowestVertexFrom(points, local, starts[f]);
    return local.dot(points.vertices[static_cast<std::size_t>(lowest)]) +
           normal.dot(pointsToFaces.translation) - faces.faceOffsets[f];
  };
  // A separation some face has: the deepest is at least this.
  double reached = separation(loosest);

  thread_local std::vector<int> open;  // the faces the bound leaves
  open.clear();
  for (std::size_t f = 0; f < faceCount; ++f)
    if (bounds[f] + kBoundSlack >= reached) open.push_back(static_cast<int>(f));
  constexpr std::size_t kFewFaces = 16;
  if (open.size() > kFewFaces) {
    constexpr double kTilt = 0.5;
    int smallest = 0;
    towards.cwiseAbs().minCoeff(&smallest);
    const Vec3 u = towards.cross(Vec3::Unit(smallest)).normalized();
    const Vec3 v = towards.cross(u);
    for (const Vec3& direction : {Vec3(towards + kTilt * u), Vec3(towards - kTilt * u),
                                  Vec3(towards + kTilt * v), Vec3(towards - kTilt * v)}) {
      const int extra = probeAlong(direction);
      const Vec3 extraPoint = placed(extra);
      for (const int face : open) {
        const std::size_t f = static_cast<std::size_t>(face);
        const double bound = faces.faceNormals[f].dot(extraPoint) - faces.faceOffsets[f];
        if (bound < bounds[f]) {
          bounds[f] = bound;
          starts[f] = extra;
        }
      }
    }
  }

  AxisQuery best;
  for (const int face : open) {
    const std::size_t f = static_cast<std::size_t>(face);
    if (bounds[f] + kBoundSlack < reached) continue;
    const double s = separation(f);
    if (s > best.separation) best = {s, face, -1, Vec3::Zero()};
    reached = std::max(reached, s);
  }
  return best;
}

// Stamps that mark vertices and edges as seen by one search without
// clearing an array per search.
class Marks {
 public:
  void start(std::size_t size) {
    if (m_stamps.size() < size) m_stamps.resize(size, 0);
    if (++m_current == 0) {  // wrapped: forget every old stamp
      std::fill(m_stamps.begin(), m_stamps.end(), 0);
      m_current = 1;
    }
  }
  // Marks `index`; false if it was marked already.
  bool mark(int index) {
    uint32_t& stamp = m_stamps[static_cast<std::size_t>(index)];
    if (stamp == m_current) return false;
    stamp = m_current;
    return true;
  }

 private:
  std::vector<uint32_t> m_stamps;
  uint32_t m_current = 0;
};

// The largest u · n over the great-circle arc from a to b (unit, not
// antipodal: the normals of two faces that share an edge).
double highestOnArc(const Vec3& a, const Vec3& b, const Vec3& u) {
  double highest = std::max(a.dot(u), b.dot(u));
  const Vec3 plane = a.cross(b);
  const double length2 = plane.squaredNorm();
  if (length2 > 0.0) {
    // u's projection onto the arc's plane; if it falls between a and b,
    // the arc's highest point is in its direction.
    const Vec3 inPlane = u - (u.dot(plane) / length2) * plane;
    if (a.cross(inPlane).dot(plane) >= 0.0 && inPlane.cross(b).dot(plane) >= 0.0)
      highest = std::max(highest, inPlane.norm());
  }
  return highest;
}

// The edges of `hull` whose Gauss-map arcs reach into the cap of unit
// directions n with n · center >= cosine (center in the hull's frame),
// ascending. The arcs divide the sphere into the vertices' normal cones;
// the cones that meet the cap are connected through the arcs that do, so
// a walk from the vertex farthest along `center` (whose cone holds it)
// over those arcs finds them all.
void edgesInCap(const ConvexHull& hull, const Vec3& center, double cosine,
                std::vector<int>& out) {
  thread_local Marks vertexMarks;
  thread_local Marks edgeMarks;
  thread_local std::vector<int> stack;
  vertexMarks.start(hull.vertices.size());
  edgeMarks.start(hull.faceEdges.size());
  out.clear();
  stack.clear();
  const int first = supportVertex(hull, center);
  vertexMarks.mark(first);
  stack.push_back(first);
  // Arcs that miss the cap by rounding only are taken too.
  const double reach = cosine - 1e-12;
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    const std::size_t vertex = static_cast<std::size_t>(v);
    for (int k = hull.vertexEdgeStart[vertex]; k < hull.vertexEdgeStart[vertex + 1]; ++k) {
      const int e = hull.vertexEdges[static_cast<std::size_t>(k)];
      if (!edgeMarks.mark(e)) continue;
      const ConvexHull::FaceEdge& edge = hull.faceEdges[static_cast<std::size_t>(e)];
      if (highestOnArc(hull.faceNormals[static_cast<std::size_t>(edge.face0)],
                       hull.faceNormals[static_cast<std::size_t>(edge.face1)], center) < reach)
        continue;
      out.push_back(e);
      const int other = edge.start == v ? edge.end : edge.start;
      if (vertexMarks.mark(other)) stack.push_back(other);
    }
  }
  std::sort(out.begin(), out.end());
}

// Every edge index of the hull, ascending.
void allEdges(const ConvexHull& hull, std::vector<int>& out) {
  out.resize(hull.faceEdges.size());
  for (std::size_t e = 0; e < out.size(); ++e) out[e] = static_cast<int>(e);
}


// An edge axis matters only if it separates the hulls by more than this:
// more than the margin (then they are apart), or more than the face axes'
// bar for an edge to be chosen.
double edgeAxisBar(const AxisQuery& faceA, const AxisQuery& faceB, double margin) {
  const double faceSeparation = std::max(faceA.separation, faceB.separation);
  return std::min(kRelativeEdgeTolerance * faceSeparation + kAbsoluteTolerance, margin);
}

// The edge–edge contact of an edge axis: the closest points of the two edges.
bool edgeContact(const ConvexHull& hullA, const Transform& poseA, const ConvexHull& hullB,
                 const Transform& poseB, const AxisQuery& edge, const ContactSettings& settings,
                 ContactManifold& out) {
  const ConvexHull::FaceEdge& eA = hullA.faceEdges[static_cast<std::size_t>(edge.first)];
  const ConvexHull::FaceEdge& eB = hullB.faceEdges[static_cast<std::size_t>(edge.second)];
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
  if (point.depth < -settings.margin) return false;
  out.normal = normal;
  out.add(point);
  return true;
}

// The contact from the three axis queries. The feature of the chosen axis
// (with the hysteresis that keeps a resting contact's reference face) gives
// it, and almost always does. On hulls of many small faces it can give
// nothing: the face preferred within the hysteresis can lie beside the
// other hull's deepest part, so that clipping leaves no point, or two
// edges chosen can meet only beyond their ends. Overlapping hulls must
// still touch, so the other features are tried, deepest axis first, and
// last the deepest vertex of B along the deepest axis. An edge axis that
// separates by no more than `needed` (see collideHulls) takes no part: the
// bounded search does not look for those.
bool contactFromAxes(const ConvexHull& hullA, const Transform& poseA, const ConvexHull& hullB,
                     const Transform& poseB, const AxisQuery& faceA, const AxisQuery& faceB,
                     AxisQuery edge, double needed, const ContactSettings& settings,
                     ContactManifold& out) {
  if (!(edge.separation > needed)) edge = AxisQuery{};
  enum class Feature { FaceA, FaceB, Edge };
  const auto generate = [&](Feature feature) {
    out = ContactManifold{};
    switch (feature) {
      case Feature::Edge:
        return edgeContact(hullA, poseA, hullB, poseB, edge, settings, out);
      case Feature::FaceB:
        return faceContact(hullB, poseB, hullA, poseA, faceB.first, false, settings, out);
      case Feature::FaceA:
        break;
    }
    return faceContact(hullA, poseA, hullB, poseB, faceA.first, true, settings, out);
  };
  const double faceSeparation = std::max(faceA.separation, faceB.separation);
  Feature chosen = Feature::FaceA;
  if (edge.first >= 0 &&
      edge.separation > kRelativeEdgeTolerance * faceSeparation + kAbsoluteTolerance) {
    chosen = Feature::Edge;
  } else if (faceB.separation > kRelativeFaceTolerance * faceA.separation + kAbsoluteTolerance) {
    chosen = Feature::FaceB;
  }
  if (generate(chosen)) return true;

  struct Candidate {
    Feature feature;
    const AxisQuery* axis;
  };
  std::array<Candidate, 3> candidates{{{Feature::FaceA, &faceA}, {Feature::FaceB, &faceB},
                                       {Feature::Edge, &edge}}};
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return x.axis->separation > y.axis->separation;
  });
  for (const Candidate& candidate : candidates) {
    if (candidate.feature == chosen || candidate.axis->first < 0) continue;
    if (generate(candidate.feature)) return true;
  }

  // The deepest vertex of B along the deepest axis, against A's support plane.
  const Candidate& deepest = candidates.front();
  Vec3 normal;  // world, A to B
  if (deepest.feature == Feature::Edge) {
    normal = poseA.rotate(edge.axis);
  } else if (deepest.feature == Feature::FaceA) {
    normal = poseA.rotate(hullA.faceNormals[static_cast<std::size_t>(faceA.first)]);
  } else {
    normal = -poseB.rotate(hullB.faceNormals[static_cast<std::size_t>(faceB.first)]);
  }
  const double separation = deepest.axis->separation;
  if (deepest.axis->first < 0 || separation > settings.margin) return false;
  const int vertexB = supportVertex(hullB, poseB.inverseRotate(-normal));
  out = ContactManifold{};
  ContactPoint point;
  point.pointB = poseB.apply(hullB.vertices[static_cast<std::size_t>(vertexB)]);
  point.pointA = point.pointB - separation * normal;
  point.depth = -separation;
  point.featureId = makeFeatureId(FeatureKind::Other, static_cast<uint32_t>(vertexB), 0, 0);
  out.normal = normal;
  out.add(point);
  return true;
}

}  // namespace

bool collideHullsExhaustive(const ConvexHull& hullA, const Transform& poseA,
                            const ConvexHull& hullB, const Transform& poseB,
                            const ContactSettings& settings, ContactManifold& out) {
  const double margin = settings.margin;
  // Everything in A's frame.
  const Transform bToA = poseA.inverse() * poseB;
  // Scratch kept per thread: this runs for every small hull pair.
  thread_local std::vector<Vec3> verticesB;
  thread_local std::vector<Vec3> normalsB;
  thread_local std::vector<double> offsetsB;
  verticesB.clear();
  normalsB.clear();
  offsetsB.clear();
  for (const Vec3& v : hullB.vertices) verticesB.push_back(bToA.apply(v));
  for (const ConvexHull::Face& face : hullB.faces) {
    normalsB.push_back(bToA.rotate(face.normal));
    offsetsB.push_back(face.offset + normalsB.back().dot(bToA.translation));
  }

  const AxisQuery faceA = queryFaces(hullA.faceNormals, hullA.faceOffsets, verticesB);
  if (faceA.separation > margin) return false;
  const AxisQuery faceB = queryFaces(normalsB, offsetsB, hullA.vertices);
  if (faceB.separation > margin) return false;

  const HullPair pair{hullA, hullB, bToA, margin, &normalsB, &verticesB};
  thread_local std::vector<int> edgesA;
  thread_local std::vector<int> edgesB;
  allEdges(hullA, edgesA);
  allEdges(hullB, edgesB);
  const EdgeQuery edge = queryEdgePairs(pair, edgesA, edgesB);
  if (edge.separated) return false;
  return contactFromAxes(hullA, poseA, hullB, poseB, faceA, faceB, edge.best,
                         edgeAxisBar(faceA, faceB, margin), settings, out);
}

// The pieces' separation along `axis` (unit, A's frame): the lowest point
// of B along it minus the highest of A.
double separationAlong(const HullPair& pair, const Vec3& axis) {
  const Vec3 highestA = pair.a.vertices[static_cast<std::size_t>(supportVertex(pair.a, axis))];
  const Vec3 lowestB = pair.bToA.apply(
      pair.b.vertices[static_cast<std::size_t>(supportVertex(pair.b, pair.bToA.inverseRotate(-axis)))]);
  return axis.dot(lowestB - highestA);
}

bool collideHulls(const ConvexHull& hullA, const Transform& poseA, const ConvexHull& hullB,
                  const Transform& poseB, const ContactSettings& settings, ContactManifold& out,
                  SeparationCache* cache) {
  // Below this many edge pairs the exhaustive test is the faster.
  constexpr std::size_t kExhaustiveEdgePairs = 1024;
  if (hullA.faceEdges.size() * hullB.faceEdges.size() <= kExhaustiveEdgePairs)
    return collideHullsExhaustive(hullA, poseA, hullB, poseB, settings, out);

  const double margin = settings.margin;
  const Transform bToA = poseA.inverse() * poseB;
  const HullPair pair{hullA, hullB, bToA, margin};
  const double scale = std::max(hullA.radius, hullB.radius);
  const double distanceSlack = 1e-9 * scale;

  // 0. Temporal coherence: still apart along last step's direction by more
  // than margin + slack? The true distance is at least that separation and
  // GJK's distance at least the true one, so step 1 would reject the pair
  // too (when GJK converges, as it does within its 64 iterations on hulls).
  if (cache && cache->axis != Vec3::Zero() &&
      separationAlong(pair, cache->axis) > margin + distanceSlack)
    return false;

  // 1. How far apart: GJK's distance D is the length of a vector between
  // two points of the hulls, so it bounds the true distance from above, and
  // on convergence from below to within 1e-12 of the size. No axis of the
  // test separates the hulls by more than the true distance.
  const ConvexGeometry geometryA = std::shared_ptr<const ConvexHull>(std::shared_ptr<void>(), &hullA);
  const ConvexGeometry geometryB = std::shared_ptr<const ConvexHull>(std::shared_ptr<void>(), &hullB);
  const PlacedConvex placedA{&geometryA, poseA};
  const PlacedConvex placedB{&geometryB, poseB};
  const GjkResult gjk = gjkDistance(placedA, placedB);
  // Farther apart than the margin: no contact. (The exhaustive test can
  // still find a point within the margin along a face normal when the
  // nearest features are two vertices: there the hulls do not come within
  // the margin, and this path reports nothing.)
  if (gjk.converged && !gjk.overlap && gjk.distance - distanceSlack > margin) {
    if (cache) cache->axis = poseA.inverseRotate((gjk.pointB - gjk.pointA) / gjk.distance);
    return false;
  }
  const bool apart = !gjk.overlap && gjk.distance > distanceSlack;
  // Unit, A's frame, from A towards B.
  Vec3 towardsB = apart ? poseA.inverseRotate((gjk.pointB - gjk.pointA) / gjk.distance)
                        : Vec3(bToA.apply(hullB.centroid) - hullA.centroid);
  if (!(towardsB.norm() > 0.0) || !towardsB.allFinite()) towardsB = Vec3::UnitZ();
  towardsB.normalize();
  if (cache) cache->axis = apart ? towardsB : Vec3::Zero();

  // 2. The face queries, each over the faces that can win.
  const AxisQuery faceA = queryFacesNear(hullA, hullB, bToA, towardsB);
  if (faceA.separation > margin) return false;
  const Transform aToB = bToA.inverse();
  const AxisQuery faceB = queryFacesNear(hullB, hullA, aToB, aToB.rotate(-towardsB));
  if (faceB.separation > margin) return false;

  // 3. The edge query. An edge axis matters only if it separates by more
  // than `needed`: more than the margin (then the hulls are apart), or more
  // than the face axes' bar for an edge to be chosen. Every axis separates
  // by at most `ceiling`, a bound on the largest separation of any axis:
  // GJK's distance while apart or touching, minus EPA's lower bound on the
  // depth while overlapping.
  const double needed = edgeAxisBar(faceA, faceB, margin);
  double ceiling = gjk.overlap ? 0.0 : gjk.distance;
  double tolerance = distanceSlack;
  Vec3 center = towardsB;  // where on the Gauss map the deciding edge axes lie
  AxisQuery edge;
  if (ceiling > needed + tolerance) {
    if (!apart) {
      // Overlapping by more than the bar allows: EPA's polytope lies in the
      // Minkowski difference, so its nearest face bounds the depth from below.
      // EPA stops within its tolerance of the depth; much tighter than 1e-6
      // it can stall on rounding until its support budget ends it (seen on
      // the iiwa's links at 1e-9), and its answer is then not trusted.
      constexpr double kEpaTolerance = 1e-6;
      const std::optional<EpaBound> epa =
          epaDepthBound(placedA, placedB, PenetrationSettings{64, kEpaTolerance});
      if (epa) {
        ceiling = -epa->depth;
        center = poseA.inverseRotate(epa->normal);
        tolerance = 10.0 * kEpaTolerance * scale;
      } else {
        ceiling = std::numeric_limits<double>::infinity();  // no bound: search everything
      }
    }
  }
  if (ceiling > needed + tolerance) {
    // Search caps of the Gauss map around `center`, widening until nothing
    // outside can matter: the deepest pair found reaches the ceiling; or,
    // apart, the cap holds every direction n with n · u > s / D (an axis
    // separating by s has n · (pB − pA) >= s for GJK's closest points pA,
    // pB, which are D apart along u); or the cap is the whole sphere.
    thread_local std::vector<int> edgesA;
    thread_local std::vector<int> edgesB;
    // rad; without a ceiling nothing short of the whole sphere is known to do
    double angle = std::isfinite(ceiling) ? 0.25 : std::numbers::pi;
    for (;;) {
      const bool whole = angle >= std::numbers::pi;
      if (whole) {
        allEdges(hullA, edgesA);
        allEdges(hullB, edgesB);
      } else {
        const double cosine = std::cos(angle);
        edgesInCap(hullA, center, cosine, edgesA);
        edgesInCap(hullB, bToA.inverseRotate(-center), cosine, edgesB);
      }
      const EdgeQuery query = queryEdgePairs(pair, edgesA, edgesB);
      if (query.separated) return false;
      edge = query.best;
      const double bar = std::max(needed, edge.separation);
      if (whole || ceiling <= bar + tolerance) break;
      if (apart && std::cos(angle) <= bar / gjk.distance - 1e-12) break;
      angle *= 2.0;
    }
  }
  return contactFromAxes(hullA, poseA, hullB, poseB, faceA, faceB, edge, needed, settings, out);
}

}  // namespace rbsim
