#include "physics/collision/box_features.h"

#include <utility>

namespace rbsim {

Vec3 boxVertex(const Vec3& halfExtents, int index) {
  return {(index & 1) != 0 ? halfExtents.x() : -halfExtents.x(),
          (index & 2) != 0 ? halfExtents.y() : -halfExtents.y(),
          (index & 4) != 0 ? halfExtents.z() : -halfExtents.z()};
}

Vec3 boxFaceNormal(int face) {
  Vec3 normal = Vec3::Zero();
  normal[face / 2] = face % 2 == 0 ? 1.0 : -1.0;
  return normal;
}

std::array<int, 4> boxFaceVertices(int face) {
  // (u, v, axis) is a cyclic, right-handed triple, so u × v = axis: the
  // corners (−,−), (+,−), (+,+), (−,+) in (u, v) run counter-clockwise
  // about +axis, and in reverse about −axis.
  const int axis = face / 2;
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  const int base = face % 2 == 0 ? 1 << axis : 0;
  const std::array<int, 4> positive{base, base | 1 << u, base | 1 << u | 1 << v, base | 1 << v};
  if (face % 2 == 0) return positive;
  return {positive[0], positive[3], positive[2], positive[1]};
}

ConvexHull boxHull(const Vec3& halfExtents) {
  ConvexHull hull;
  hull.vertices.reserve(8);
  for (int i = 0; i < 8; ++i) hull.vertices.push_back(boxVertex(halfExtents, i));
  hull.faces.reserve(6);
  for (int face = 0; face < 6; ++face) {
    const std::array<int, 4> corners = boxFaceVertices(face);
    ConvexHull::Face hullFace;
    hullFace.normal = boxFaceNormal(face);
    hullFace.offset = halfExtents[face / 2];
    hullFace.vertices.assign(corners.begin(), corners.end());
    hull.faces.push_back(std::move(hullFace));
  }
  for (int i = 0; i < 8; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      if ((i & 1 << axis) == 0) hull.edges.push_back({i, i | 1 << axis});
    }
  }
  computeHullTopology(hull);
  return hull;
}

}  // namespace rbsim
