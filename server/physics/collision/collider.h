#pragma once
// The collision geometry of one body, in body space: convex pieces (one for
// a primitive, several for a compound or a multi-part mesh), a half-space,
// or the triangles of a trimesh.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "physics/collision/aabb.h"
#include "physics/collision/convex_geometry.h"
#include "physics/collision/triangle_mesh_collider.h"
#include "rbsim/physics/expected.h"
#include "rbsim/physics/shapes.h"
#include "rbsim/physics/transform.h"

namespace rbsim {

struct ConvexPiece {
  ConvexGeometry geometry;
  Transform placement;  // geometry frame -> body frame
  Aabb bounds;          // in the body frame
};

struct Collider {
  std::vector<ConvexPiece> pieces;  // empty for a plane or a trimesh
  std::optional<PlaneShape> plane;  // a half-space, in the body frame
  // A trimesh's triangles (static bodies only). Contacts name a triangle
  // where they would name a piece (BodyContact::pieceA or pieceB).
  std::shared_ptr<const TriangleMeshCollider> triangles;
  Aabb bounds = Aabb::empty();      // body frame; everything for a plane
  // Per piece, the compound part it came from (a mesh part may give several
  // pieces, one per connected component); empty for any other shape, whose
  // pieces are all part 0. What a ray cast reports as the part it hit.
  std::vector<int> partOfPiece;
};

// The compound part of `piece` (0 for shapes that are not compounds).
inline int partOfPiece(const Collider& collider, std::size_t piece) {
  return collider.partOfPiece.empty() ? 0 : collider.partOfPiece[piece];
}

// Builds the collider of `shape`, whose frame sits at `shapeToBody` in body
// space. Meshes become the convex hulls of their connected components
// (triangles sharing a vertex index or a vertex position), in the order of
// their first vertex. A compound's parts give their pieces in part order.
// Errors (bad sizes, a component without volume) name
// `sourceName` and, for meshes, the file and the component.
Expected<Collider> buildCollider(const Shape& shape, const Transform& shapeToBody,
                                 const std::string& sourceName);

// No point of the collider lies farther than this from the body origin (m):
// the farthest corner of its box. 0 for a plane, which is static.
double colliderRadius(const Collider& collider);

// A convex piece placed in the world: what the narrow phase works on.
struct PlacedConvex {
  const ConvexGeometry* geometry = nullptr;
  Transform pose;  // geometry frame -> world

  Vec3 support(const Vec3& worldDirection) const {
    return pose.apply(supportPoint(*geometry, pose.inverseRotate(worldDirection)));
  }
};

}  // namespace rbsim
