// Triangle–convex contacts (see triangle_contacts.h for the one-sided rule
// and the internal-edge correction). Three ways to the contact normal:
//  - a sphere: the closest point of the triangle to its centre (exact);
//  - a box or a hull: the separating-axis test over the triangle's front
//    normal, the hull's face normals and the cross products of their edges
//    (Ericson, "Real-Time Collision Detection", §5.2.1; Gregorius, GDC
//    2013), with the hysteresis of hull_contacts.cpp;
//  - a capsule or a cylinder: the signed distance (GJK, or libccd's
//    penetration depth) to the triangle as a flat hull.
// A normal along the triangle's front then gets the whole manifold by
// clipping the piece's support feature against the triangle (Gregorius,
// GDC 2015), a hull face's by clipping the triangle against that face; an
// edge pair or a round piece gets the one point its closest points give.

#include "physics/collision/triangle_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <type_traits>
#include <variant>
#include <vector>

#include "physics/collision/active_edges.h"
#include "physics/collision/box_features.h"
#include "physics/collision/closest_points.h"
#include "physics/collision/contact_routines.h"
#include "physics/collision/polygon_clipping.h"
#include "physics/collision/signed_distance.h"
#include "physics/collision/support_features.h"

namespace rbsim {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Where the normal came from.
enum class AxisKind { TriangleFront, PieceFace, EdgePair, ClosestPoints };

struct ChosenAxis {
  AxisKind kind = AxisKind::TriangleFront;
  double separation = -kInfinity;  // m, along normal
  Vec3 normal = Vec3::UnitZ();     // unit, world, from the triangle to the piece
  int triangleEdge = -1;           // EdgePair
  int pieceFeature = -1;           // PieceFace: the hull face; EdgePair: the hull edge
  Vec3 pointA = Vec3::Zero();      // ClosestPoints: on the triangle
  Vec3 pointB = Vec3::Zero();      // ClosestPoints: on the piece
  // m: the largest separation of any axis tested; beyond the margin, apart.
  double largestSeparation = -kInfinity;
};

double frontSeparation(const ContactTriangle& triangle, const PlacedConvex& piece) {
  const Vec3& n = triangle.normal;
  return n.dot(piece.support(-n) - triangle.vertices[0]);
}

// Is the triangle's feature that faces `direction` (unit, world) one whose
// own normals count? Its face always; an edge or a vertex when active.
bool facesActiveFeature(const ContactTriangle& triangle, const Vec3& direction) {
  if (direction.dot(triangle.normal) >= kFlatCosine) return true;
  std::array<double, 3> height{};
  for (std::size_t k = 0; k < 3; ++k) height[k] = direction.dot(triangle.vertices[k]);
  const double highest = std::max({height[0], height[1], height[2]});
  for (int e = 0; e < 3; ++e) {
    const std::size_t from = static_cast<std::size_t>(e);
    const std::size_t to = static_cast<std::size_t>((e + 1) % 3);
    const double slack = kFlatSine * (triangle.vertices[to] - triangle.vertices[from]).norm();
    if (highest - height[from] <= slack && highest - height[to] <= slack)
      return (triangle.activeEdges & (1u << e)) != 0;
  }
  const int top = static_cast<int>(std::max_element(height.begin(), height.end()) - height.begin());
  return isActiveVertex(triangle.activeEdges, top);
}

// The separating-axis test of a hull (a box as boxHull) against the triangle.
ChosenAxis hullAxis(const ContactTriangle& triangle, const PlacedHull& placed) {
  const std::vector<Vec3>& corners = placed.corners;
  const auto lowestOfHull = [&](const Vec3& axis) {
    double lowest = kInfinity;
    for (const Vec3& c : corners) lowest = std::min(lowest, axis.dot(c));
    return lowest;
  };
  const auto span = [](const std::array<Vec3, 3>& points, const Vec3& axis) {
    const double a = axis.dot(points[0]), b = axis.dot(points[1]), c = axis.dot(points[2]);
    return std::pair{std::min({a, b, c}), std::max({a, b, c})};
  };

  ChosenAxis front;
  front.normal = triangle.normal;
  front.separation = lowestOfHull(triangle.normal) - triangle.normal.dot(triangle.vertices[0]);

  ChosenAxis face;
  face.kind = AxisKind::PieceFace;
  for (std::size_t f = 0; f < placed.faceNormals.size(); ++f) {
    const Vec3& m = placed.faceNormals[f];
    const double separation = span(triangle.vertices, m).first - placed.faceOffsets[f];
    if (separation > face.separation) {
      face.separation = separation;
      face.normal = -m;
      face.pieceFeature = static_cast<int>(f);
    }
  }

  // Parallel edges of the hull give the same axes: one edge per direction.
  ChosenAxis edge;
  edge.kind = AxisKind::EdgePair;
  for (int i = 0; i < 3; ++i) {
    const Vec3 along = triangle.vertices[static_cast<std::size_t>((i + 1) % 3)] -
                       triangle.vertices[static_cast<std::size_t>(i)];
    for (std::size_t d = 0; d < placed.edgeDirections.size(); ++d) {
      const Vec3& other = placed.edgeDirections[d];
      Vec3 axis = along.cross(other);
      const double length = axis.norm();
      if (!(length > kParallelEdgeSine * along.norm() * other.norm())) continue;
      axis /= length;
      // Both orientations of the line; the larger separation is the line's.
      const auto [low, high] = span(triangle.vertices, axis);
      double lowestOfHullHere = kInfinity;
      double highestOfHull = -kInfinity;
      for (const Vec3& c : corners) {
        const double height = axis.dot(c);
        lowestOfHullHere = std::min(lowestOfHullHere, height);
        highestOfHull = std::max(highestOfHull, height);
      }
      const double alongAxis = lowestOfHullHere - high;
      const double againstAxis = low - highestOfHull;
      const double separation = std::max(alongAxis, againstAxis);
      if (separation > edge.separation) {
        edge.separation = separation;
        edge.normal = alongAxis >= againstAxis ? axis : Vec3(-axis);
        edge.triangleEdge = i;
        edge.pieceFeature = placed.edgeOfDirection[d];
      }
    }
  }
  // The triangle's front unless another axis is clearly shallower (or
  // separates): near-ties must not flip the normal from step to step.
  ChosenAxis best = front;
  if (face.separation > kRelativeFaceTolerance * front.separation + kAbsoluteTolerance ||
      (face.separation > 0.0 && face.separation > front.separation))
    best = face;
  if (edge.separation > kRelativeEdgeTolerance * best.separation + kAbsoluteTolerance ||
      (edge.separation > 0.0 && edge.separation > best.separation))
    best = edge;
  // Any separating axis proves the pair apart.
  best.largestSeparation = std::max({front.separation, face.separation, edge.separation});
  return best;
}

ChosenAxis sphereAxis(const ContactTriangle& triangle, const Vec3& centre, double radius) {
  ChosenAxis axis;
  axis.kind = AxisKind::ClosestPoints;
  const Vec3 closest = closestPointOnConvexPolygon(centre, triangle.vertices, triangle.normal);
  const Vec3 offset = centre - closest;
  const double distance = offset.norm();
  axis.normal = distance > 0.0 ? Vec3(offset / distance) : triangle.normal;
  axis.separation = distance - radius;
  axis.pointA = closest;
  axis.pointB = centre - radius * axis.normal;
  axis.largestSeparation = axis.separation;
  return axis;
}

ChosenAxis distanceAxis(const ContactTriangle& triangle, const PlacedConvex& piece) {
  const auto hull = std::make_shared<const ConvexHull>(triangleHull(triangle));
  const ConvexGeometry geometry = hull;
  const SignedDistance query = signedDistance({&geometry, Transform::identity()}, piece);
  ChosenAxis axis;
  axis.kind = AxisKind::ClosestPoints;
  axis.separation = query.distance;
  axis.normal = query.normal;
  axis.pointA = query.pointA;
  axis.pointB = query.pointB;
  if (!query.normal.allFinite() || !std::isfinite(query.distance)) {
    axis.kind = AxisKind::TriangleFront;  // no direction: fall back on the face
    axis.normal = triangle.normal;
    axis.separation = frontSeparation(triangle, piece);
  }
  axis.largestSeparation = axis.separation;
  return axis;
}

// The front face as the reference: the piece's support feature clipped to
// the triangle. Nothing when the feature lies beyond the triangle's sides
// (a neighbour then holds the contact).
bool frontContact(const ContactTriangle& triangle, const PlacedConvex& piece, double margin,
                  ContactManifold& out) {
  const SupportFeature incident = supportFeature(piece, -triangle.normal);
  std::vector<ContactPoint> candidates;
  clipIncidentFeature(triangle.vertices, triangle.normal, incident.vertices, true,
                      makeFeatureId(FeatureKind::FaceOfA, 0, incident.id, 0), margin, candidates);
  if (candidates.empty()) return false;
  reduceContacts(candidates, triangle.normal, out);
  out.normal = triangle.normal;
  return true;
}

bool sphereFrontContact(const ContactTriangle& triangle, const Vec3& centre, double radius,
                        double margin, ContactManifold& out) {
  const Vec3& n = triangle.normal;
  const Vec3 lowest = centre - radius * n;
  const double height = n.dot(lowest - triangle.vertices[0]);
  const Vec3 foot = lowest - height * n;
  // Beyond the triangle's sides the neighbour holds the contact.
  for (std::size_t k = 0; k < 3; ++k) {
    const Vec3& a = triangle.vertices[k];
    const Vec3& b = triangle.vertices[(k + 1) % 3];
    if ((b - a).cross(n).dot(foot - a) > 0.0) return false;
  }
  if (height > margin) return false;
  ContactPoint point;
  point.pointA = foot;
  point.pointB = lowest;
  point.depth = -height;
  point.featureId = makeFeatureId(FeatureKind::FaceOfA, 0, 0, 0);
  out.normal = n;
  out.add(point);
  return true;
}

// The piece's hull: its own, or its box's made in `box`.
const ConvexHull* pieceHull(const PlacedConvex& piece, ConvexHull& box) {
  if (const auto* b = std::get_if<BoxShape>(piece.geometry)) {
    box = boxHull(b->halfExtents);
    return &box;
  }
  return std::get<std::shared_ptr<const ConvexHull>>(*piece.geometry).get();
}

}  // namespace

ConvexHull triangleHull(const ContactTriangle& triangle) {
  ConvexHull hull;
  hull.vertices.assign(triangle.vertices.begin(), triangle.vertices.end());
  const double offset = triangle.normal.dot(triangle.vertices[0]);
  hull.faces.push_back({triangle.normal, offset, {0, 1, 2}});
  hull.faces.push_back({-triangle.normal, -offset, {0, 2, 1}});
  hull.edges = {{0, 1}, {1, 2}, {0, 2}};
  computeHullTopology(hull);
  return hull;
}

void PlacedHull::place(const ConvexHull& source, const Transform& at) {
  hull = &source;
  pose = at;
  corners.clear();
  for (const Vec3& v : source.vertices) corners.push_back(pose.apply(v));
  faceNormals.clear();
  faceOffsets.clear();
  for (std::size_t f = 0; f < source.faceNormals.size(); ++f) {
    const Vec3 m = pose.rotate(source.faceNormals[f]);
    faceNormals.push_back(m);
    faceOffsets.push_back(source.faceOffsets[f] + m.dot(pose.translation));
  }
  edgeDirections.clear();
  edgeOfDirection.clear();
  for (std::size_t e = 0; e < source.edges.size(); ++e) {
    const Vec3 direction = corners[static_cast<std::size_t>(source.edges[e][1])] -
                           corners[static_cast<std::size_t>(source.edges[e][0])];
    const double length = direction.norm();
    bool seen = false;
    for (const Vec3& kept : edgeDirections) {
      if (direction.cross(kept).norm() <= 1e-12 * length * kept.norm()) {
        seen = true;
        break;
      }
    }
    if (seen) continue;
    edgeDirections.push_back(direction);
    edgeOfDirection.push_back(static_cast<int>(e));
  }
}

bool collideTriangleConvex(const ContactTriangle& triangle, const PlacedConvex& piece,
                           const ContactSettings& settings, ContactManifold& out,
                           bool correctInternalEdges, const PlacedHull* placed) {
  out = ContactManifold{};
  const double margin = settings.margin;
  const Transform& pose = piece.pose;
  const SphereShape* sphere = std::get_if<SphereShape>(piece.geometry);
  // Behind the triangle's plane the piece is inside the solid, or on the
  // far side of an open surface: not this triangle's contact.
  if (sphere != nullptr &&
      triangle.normal.dot(pose.translation - triangle.vertices[0]) < 0.0)
    return false;

  ChosenAxis axis = std::visit(
      [&](const auto& geometry) -> ChosenAxis {
        using Geometry = std::decay_t<decltype(geometry)>;
        if constexpr (std::is_same_v<Geometry, SphereShape>) {
          return sphereAxis(triangle, pose.translation, geometry.radius);
        } else if constexpr (std::is_same_v<Geometry, BoxShape> ||
                             std::is_same_v<Geometry, std::shared_ptr<const ConvexHull>>) {
          if (placed != nullptr) return hullAxis(triangle, *placed);
          PlacedHull local;
          if constexpr (std::is_same_v<Geometry, BoxShape>) {
            const ConvexHull box = boxHull(geometry.halfExtents);
            local.place(box, pose);
            return hullAxis(triangle, local);
          } else {
            local.place(*geometry, pose);
            return hullAxis(triangle, local);
          }
        } else {
          return distanceAxis(triangle, piece);
        }
      },
      *piece.geometry);
  if (axis.largestSeparation > margin) return false;

  // A normal from the triangle's face, or corrected to it.
  const bool fromFront = axis.kind == AxisKind::TriangleFront ||
                         axis.normal.dot(triangle.normal) >= kFlatCosine;
  // A piece that meets the triangle from behind (a box under a floor
  // pushing up through it) is not corrected onto the front: that would
  // pull it through. Normals along the triangle's plane (the ghost
  // contacts of a flat floor's edges) may be.
  if (!fromFront && axis.normal.dot(triangle.normal) < -kFlatSine) return false;
  const bool internal =
      !fromFront && correctInternalEdges && !facesActiveFeature(triangle, axis.normal);
  if (fromFront || internal) {
    if (sphere != nullptr)
      return sphereFrontContact(triangle, pose.translation, sphere->radius, margin, out);
    return frontContact(triangle, piece, margin, out);
  }
  // One-sided: a normal into the triangle's back is the neighbour's to give.
  if (axis.normal.dot(triangle.normal) < 0.0) return false;

  switch (axis.kind) {
    case AxisKind::PieceFace: {
      ConvexHull box;
      const ConvexHull* hull = pieceHull(piece, box);
      const ConvexHull::Face& face = hull->faces[static_cast<std::size_t>(axis.pieceFeature)];
      std::vector<Vec3> reference;
      for (const int v : face.vertices)
        reference.push_back(pose.apply(hull->vertices[static_cast<std::size_t>(v)]));
      std::vector<ContactPoint> candidates;
      clipIncidentFeature(reference, -axis.normal, triangle.vertices, false,
                          makeFeatureId(FeatureKind::FaceOfB, static_cast<uint32_t>(axis.pieceFeature),
                                        0, 0),
                          margin, candidates);
      if (candidates.empty()) return false;
      reduceContacts(candidates, -axis.normal, out);
      out.normal = axis.normal;
      return true;
    }
    case AxisKind::EdgePair: {
      ConvexHull box;
      const ConvexHull* hull = pieceHull(piece, box);
      const std::size_t i = static_cast<std::size_t>(axis.triangleEdge);
      const Vec3& p = triangle.vertices[i];
      const Vec3& q = triangle.vertices[(i + 1) % 3];
      // Of the hull's edges parallel to the chosen one, the one deepest
      // towards the triangle (the supporting edge).
      const auto& chosen = hull->edges[static_cast<std::size_t>(axis.pieceFeature)];
      const Vec3 direction = (hull->vertices[static_cast<std::size_t>(chosen[1])] -
                              hull->vertices[static_cast<std::size_t>(chosen[0])])
                                 .normalized();
      std::size_t best = static_cast<std::size_t>(axis.pieceFeature);
      double bestHeight = kInfinity;
      for (std::size_t e = 0; e < hull->edges.size(); ++e) {
        const Vec3& s = hull->vertices[static_cast<std::size_t>(hull->edges[e][0])];
        const Vec3& t = hull->vertices[static_cast<std::size_t>(hull->edges[e][1])];
        if (std::abs((t - s).normalized().dot(direction)) < 1.0 - 1e-9) continue;
        const double height =
            std::max(axis.normal.dot(pose.apply(s)), axis.normal.dot(pose.apply(t)));
        if (height < bestHeight) {
          bestHeight = height;
          best = e;
        }
      }
      const Vec3 s = pose.apply(hull->vertices[static_cast<std::size_t>(hull->edges[best][0])]);
      const Vec3 t = pose.apply(hull->vertices[static_cast<std::size_t>(hull->edges[best][1])]);
      const SegmentClosestPoints closest = closestPointsOfSegments(p, q, s, t);
      ContactPoint point;
      point.pointA = closest.onFirst;
      point.pointB = closest.onSecond;
      point.depth = axis.normal.dot(point.pointA - point.pointB);
      if (point.depth < -margin) return false;
      point.featureId = makeFeatureId(FeatureKind::EdgeEdge, static_cast<uint32_t>(i),
                                      static_cast<uint32_t>(best), 0);
      out.normal = axis.normal;
      out.add(point);
      return true;
    }
    case AxisKind::ClosestPoints:
    case AxisKind::TriangleFront: {
      ContactPoint point;
      point.pointA = axis.pointA;
      point.pointB = axis.pointB;
      point.depth = -axis.separation;
      point.featureId = makeFeatureId(FeatureKind::Other, 0, 0, 0);
      out.normal = axis.normal;
      out.add(point);
      return true;
    }
  }
  return false;
}

}  // namespace rbsim
