#include "physics/collision/triangle_mesh_collider.h"

#include "physics/collision/active_edges.h"

namespace rbsim {

ContactTriangle TriangleMeshCollider::triangle(int t, const Transform& pose) const {
  const std::array<int, 3>& indices = triangles[static_cast<std::size_t>(t)];
  ContactTriangle placed;
  for (std::size_t k = 0; k < 3; ++k)
    placed.vertices[k] = pose.apply(vertices[static_cast<std::size_t>(indices[k])]);
  placed.normal = pose.rotate(normals[static_cast<std::size_t>(t)]);
  placed.activeEdges = activeEdges[static_cast<std::size_t>(t)];
  return placed;
}

Expected<std::shared_ptr<const TriangleMeshCollider>> buildTriangleMeshCollider(
    const TriangleMesh& mesh, const Transform& shapeToBody, const std::string& sourceName) {
  if (auto valid = validateSurfaceMesh(mesh, sourceName); !valid) return valid.error();
  // A reflection would turn every triangle's front to its back.
  if (!(shapeToBody.rotation.determinant() > 0.0))
    return Error{sourceName + ": the shape's placement must be a proper rotation"};
  auto collider = std::make_shared<TriangleMeshCollider>();
  collider->vertices.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) collider->vertices.push_back(shapeToBody.apply(v));
  collider->triangles = mesh.triangles;
  std::vector<Aabb> boxes;
  boxes.reserve(mesh.triangles.size());
  collider->normals.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Vec3& a = collider->vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = collider->vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = collider->vertices[static_cast<std::size_t>(t[2])];
    collider->normals.push_back((b - a).cross(c - a).normalized());
    Aabb box = Aabb::empty();
    box.include(a);
    box.include(b);
    box.include(c);
    boxes.push_back(box);
  }
  collider->activeEdges = findActiveEdges(collider->vertices, collider->triangles);
  collider->bvh = TriangleMeshBvh(boxes);
  return std::shared_ptr<const TriangleMeshCollider>(std::move(collider));
}

}  // namespace rbsim
