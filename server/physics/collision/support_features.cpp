#include "physics/collision/support_features.h"

#include <cmath>
#include <cstddef>
#include <memory>
#include <numbers>
#include <type_traits>
#include <variant>

#include "physics/collision/box_features.h"
#include "physics/collision/contact_routines.h"

namespace rbsim {

namespace {

// Features in the solid's own frame, mapped to the world at the end.
struct LocalFeature {
  std::vector<Vec3> vertices;
  Vec3 normal = Vec3::Zero();
  uint32_t id = 0;
};

LocalFeature sphereFeature(const SphereShape& sphere, const Vec3& d) {
  return {{sphere.radius * d}, Vec3::Zero(), 0};
}

LocalFeature capsuleFeature(const CapsuleShape& capsule, const Vec3& d) {
  const Vec3 top(0.0, 0.0, capsule.halfLength);
  if (std::abs(d.z()) <= kFlatSine) {
    const Vec3 side = Vec3(d.x(), d.y(), 0.0).normalized() * capsule.radius;
    return {{side - top, side + top}, Vec3::Zero(), 0};
  }
  const Vec3 end = d.z() > 0.0 ? top : Vec3(-top);
  return {{end + capsule.radius * d}, Vec3::Zero(), d.z() > 0.0 ? 2u : 1u};
}

LocalFeature boxFeature(const BoxShape& box, const Vec3& d) {
  const Vec3& h = box.halfExtents;
  int axis = 0;
  d.cwiseAbs().maxCoeff(&axis);
  if (std::abs(d[axis]) >= kFlatCosine) {
    const int face = boxFaceIndex(axis, d[axis] < 0.0);
    LocalFeature feature{{}, boxFaceNormal(face), static_cast<uint32_t>(face)};
    for (const int v : boxFaceVertices(face)) feature.vertices.push_back(boxVertex(h, v));
    return feature;
  }
  const int vertex = (d.x() >= 0.0 ? 1 : 0) | (d.y() >= 0.0 ? 2 : 0) | (d.z() >= 0.0 ? 4 : 0);
  int edgeAxis = 0;
  d.cwiseAbs().minCoeff(&edgeAxis);
  if (std::abs(d[edgeAxis]) <= kFlatSine) {
    const int low = vertex & ~(1 << edgeAxis);
    return {{boxVertex(h, low), boxVertex(h, low | 1 << edgeAxis)},
            Vec3::Zero(),
            6u + static_cast<uint32_t>(8 * edgeAxis + low)};
  }
  return {{boxVertex(h, vertex)}, Vec3::Zero(), 30u + static_cast<uint32_t>(vertex)};
}

LocalFeature cylinderFeature(const CylinderShape& cylinder, const Vec3& d) {
  if (std::abs(d.z()) >= kFlatCosine) {
    const bool top = d.z() > 0.0;
    LocalFeature feature{{}, top ? Vec3::UnitZ() : Vec3(-Vec3::UnitZ()), top ? 1u : 0u};
    for (int k = 0; k < kCylinderCapSides; ++k) {
      feature.vertices.push_back(cylinderCapVertex(cylinder, top, k));
    }
    return feature;
  }
  const Vec3 radial = Vec3(d.x(), d.y(), 0.0).normalized() * cylinder.radius;
  const Vec3 top(0.0, 0.0, cylinder.halfLength);
  if (std::abs(d.z()) <= kFlatSine) return {{radial - top, radial + top}, Vec3::Zero(), 2};
  return {{radial + (d.z() > 0.0 ? top : Vec3(-top))}, Vec3::Zero(), d.z() > 0.0 ? 4u : 3u};
}

LocalFeature hullFeature(const ConvexHull& hull, const Vec3& d) {
  std::size_t face = 0;
  for (std::size_t f = 1; f < hull.faces.size(); ++f) {
    if (hull.faces[f].normal.dot(d) > hull.faces[face].normal.dot(d)) face = f;
  }
  if (hull.faces[face].normal.dot(d) >= kFlatCosine) {
    LocalFeature feature{{}, hull.faces[face].normal, static_cast<uint32_t>(face)};
    for (const int v : hull.faces[face].vertices) {
      feature.vertices.push_back(hull.vertices[static_cast<std::size_t>(v)]);
    }
    return feature;
  }
  std::size_t vertex = 0;
  for (std::size_t v = 1; v < hull.vertices.size(); ++v) {
    if (hull.vertices[v].dot(d) > hull.vertices[vertex].dot(d)) vertex = v;
  }
  const auto faces = static_cast<uint32_t>(hull.faces.size());
  std::size_t bestEdge = hull.edges.size();
  double bestSine = kFlatSine;
  for (std::size_t e = 0; e < hull.edges.size(); ++e) {
    const auto& edge = hull.edges[e];
    if (static_cast<std::size_t>(edge[0]) != vertex &&
        static_cast<std::size_t>(edge[1]) != vertex) {
      continue;
    }
    const Vec3 along = hull.vertices[static_cast<std::size_t>(edge[1])] -
                       hull.vertices[static_cast<std::size_t>(edge[0])];
    const double sine = std::abs(along.dot(d)) / along.norm();
    if (sine <= bestSine) {
      bestSine = sine;
      bestEdge = e;
    }
  }
  if (bestEdge < hull.edges.size()) {
    const auto& edge = hull.edges[bestEdge];
    return {{hull.vertices[static_cast<std::size_t>(edge[0])],
             hull.vertices[static_cast<std::size_t>(edge[1])]},
            Vec3::Zero(),
            faces + static_cast<uint32_t>(bestEdge)};
  }
  return {{hull.vertices[vertex]},
          Vec3::Zero(),
          faces + static_cast<uint32_t>(hull.edges.size() + vertex)};
}

}  // namespace

Vec3 cylinderCapVertex(const CylinderShape& cylinder, bool top, int k) {
  // Counter-clockwise about +z on top, about −z (clockwise about +z) below.
  const double angle = (top ? 2.0 : -2.0) * std::numbers::pi * k / kCylinderCapSides;
  return {cylinder.radius * std::cos(angle), cylinder.radius * std::sin(angle),
          top ? cylinder.halfLength : -cylinder.halfLength};
}

SupportFeature supportFeature(const PlacedConvex& solid, const Vec3& direction) {
  const Vec3 local = solid.pose.inverseRotate(direction);
  const LocalFeature feature = std::visit(
      [&](const auto& geometry) -> LocalFeature {
        using Geometry = std::decay_t<decltype(geometry)>;
        if constexpr (std::is_same_v<Geometry, SphereShape>) {
          return sphereFeature(geometry, local);
        } else if constexpr (std::is_same_v<Geometry, CapsuleShape>) {
          return capsuleFeature(geometry, local);
        } else if constexpr (std::is_same_v<Geometry, BoxShape>) {
          return boxFeature(geometry, local);
        } else if constexpr (std::is_same_v<Geometry, CylinderShape>) {
          return cylinderFeature(geometry, local);
        } else {
          return hullFeature(*geometry, local);
        }
      },
      *solid.geometry);
  SupportFeature world;
  world.vertices.reserve(feature.vertices.size());
  for (const Vec3& v : feature.vertices) world.vertices.push_back(solid.pose.apply(v));
  world.normal = solid.pose.rotate(feature.normal);
  world.id = feature.id;
  return world;
}

}  // namespace rbsim
