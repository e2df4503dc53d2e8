#pragma once
// The collision geometry of a trimesh shape: its triangles in the body
// frame, their front normals and active edges, and a BVH over them, all
// built once when the body is made.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "physics/collision/triangle_mesh_bvh.h"
#include "rbsim/physics/expected.h"
#include "rbsim/physics/transform.h"
#include "rbsim/physics/triangle_mesh.h"

namespace rbsim {

// One triangle placed in the world (or any frame), as the narrow phase
// takes it. Its front is the side the vertices run counter-clockwise
// around; behind it is solid.
struct ContactTriangle {
  std::array<Vec3, 3> vertices;
  Vec3 normal = Vec3::UnitZ();  // unit, out of the front
  uint8_t activeEdges = 0x7;    // bit e: edge from vertex e to e + 1 (active_edges.h)
};

struct TriangleMeshCollider {
  std::vector<Vec3> vertices;                 // m, body frame
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from the front
  std::vector<Vec3> normals;                  // per triangle: unit, body frame, front
  std::vector<uint8_t> activeEdges;           // per triangle (findActiveEdges)
  TriangleMeshBvh bvh;                        // body frame

  int triangleCount() const { return static_cast<int>(triangles.size()); }
  // Triangle t placed by `pose` (body -> target frame).
  ContactTriangle triangle(int t, const Transform& pose) const;
};

// The collider of `mesh` placed at `shapeToBody`. Errors (no triangles, an
// index out of range, a zero-area triangle) name `sourceName` and the
// triangle.
Expected<std::shared_ptr<const TriangleMeshCollider>> buildTriangleMeshCollider(
    const TriangleMesh& mesh, const Transform& shapeToBody, const std::string& sourceName);

}  // namespace rbsim
