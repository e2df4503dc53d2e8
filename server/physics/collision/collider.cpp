#include "physics/collision/collider.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <type_traits>

namespace rbsim {

namespace {

bool isPositiveFinite(double value) {
  return std::isfinite(value) && value > 0.0;
}

// Union–find with path halving; joins keep the smaller root so that the
// component numbering only depends on the mesh.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t count) : m_parent(count) {
    std::iota(m_parent.begin(), m_parent.end(), 0);
  }
  std::size_t find(std::size_t i) {
    while (m_parent[i] != i) i = m_parent[i] = m_parent[m_parent[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) m_parent[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> m_parent;
};

// The vertices of each connected component of the mesh, components ordered
// by their first vertex. Two triangles are connected when they share a
// vertex index or a vertex position (a mesh loaded without welding must not
// fall apart into single triangles).
Expected<std::vector<std::vector<Vec3>>> meshComponents(const TriangleMesh& mesh,
                                                        const std::string& sourceName) {
  const std::size_t n = mesh.vertices.size();
  DisjointSets sets(n);
  std::vector<bool> used(n, false);
  for (const auto& triangle : mesh.triangles) {
    for (int v : triangle) {
      if (v < 0 || static_cast<std::size_t>(v) >= n) {
        return Error{sourceName + ": a triangle refers to vertex " + std::to_string(v) +
                     ", out of range"};
      }
      used[static_cast<std::size_t>(v)] = true;
    }
    sets.join(static_cast<std::size_t>(triangle[0]), static_cast<std::size_t>(triangle[1]));
    sets.join(static_cast<std::size_t>(triangle[0]), static_cast<std::size_t>(triangle[2]));
  }
  const auto lexLess = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::map<Vec3, std::size_t, decltype(lexLess)> firstAtPosition(lexLess);
  for (std::size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    const auto [it, inserted] = firstAtPosition.emplace(mesh.vertices[i], i);
    if (!inserted) sets.join(i, it->second);
  }
  std::map<std::size_t, std::size_t> componentOfRoot;
  std::vector<std::vector<Vec3>> components;
  for (std::size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    const auto [it, inserted] = componentOfRoot.emplace(sets.find(i), components.size());
    if (inserted) components.emplace_back();
    components[it->second].push_back(mesh.vertices[i]);
  }
  if (components.empty()) return Error{sourceName + ": the mesh has no triangles"};
  return components;
}

ConvexPiece makePiece(ConvexGeometry geometry, const Transform& placement) {
  ConvexPiece piece{std::move(geometry), placement, Aabb::empty()};
  piece.bounds = placedBounds(piece.geometry, placement);
  return piece;
}

}  // namespace

Expected<Collider> buildCollider(const Shape& shape, const Transform& shapeToBody,
                                 const std::string& sourceName) {
  Collider collider;
  const auto addPrimitive = [&](ConvexGeometry geometry) -> Expected<Collider> {
    collider.pieces.push_back(makePiece(std::move(geometry), shapeToBody));
    collider.bounds = collider.pieces.back().bounds;
    return collider;
  };
  return std::visit(
      [&](const auto& s) -> Expected<Collider> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, SphereShape>) {
          if (!isPositiveFinite(s.radius))
            return Error{sourceName + ": sphere radius must be positive"};
          return addPrimitive(s);
        } else if constexpr (std::is_same_v<T, BoxShape>) {
          if (!s.halfExtents.allFinite() || !(s.halfExtents.minCoeff() > 0.0))
            return Error{sourceName + ": box half extents must be positive"};
          return addPrimitive(s);
        } else if constexpr (std::is_same_v<T, CapsuleShape>) {
          if (!isPositiveFinite(s.radius) || !(std::isfinite(s.halfLength) && s.halfLength >= 0.0))
            return Error{sourceName +
                         ": capsule radius must be positive and half length not negative"};
          return addPrimitive(s);
        } else if constexpr (std::is_same_v<T, CylinderShape>) {
          if (!isPositiveFinite(s.radius) || !isPositiveFinite(s.halfLength))
            return Error{sourceName + ": cylinder radius and half length must be positive"};
          return addPrimitive(s);
        } else if constexpr (std::is_same_v<T, MeshShape>) {
          const std::string where = sourceName + " (mesh '" + s.file + "')";
          if (!s.mesh) return Error{where + ": the mesh was not loaded"};
          const auto components = meshComponents(*s.mesh, where);
          if (!components) return components.error();
          const bool several = components->size() > 1;
          for (std::size_t i = 0; i < components->size(); ++i) {
            const std::string name = several ? where + " component " + std::to_string(i) : where;
            auto hull = buildConvexHull((*components)[i], name);
            if (!hull) return hull.error();
            collider.pieces.push_back(makePiece(
                std::make_shared<const ConvexHull>(std::move(hull).value()), shapeToBody));
            collider.bounds = collider.bounds.merged(collider.pieces.back().bounds);
          }
          return collider;
        } else if constexpr (std::is_same_v<T, CompoundShape>) {
          if (s.parts.empty()) return Error{sourceName + ": a compound needs at least one part"};
          // Each part's pieces, in part order, placed through the part's pose.
          for (std::size_t i = 0; i < s.parts.size(); ++i) {
            const CompoundPart& part = s.parts[i];
            const Transform partToBody =
                shapeToBody * Transform::fromPose(part.position, part.orientation.normalized());
            auto partCollider = buildCollider(toShape(part.shape), partToBody,
                                              sourceName + " compound part " + std::to_string(i));
            if (!partCollider) return partCollider.error();
            for (ConvexPiece& piece : partCollider->pieces) {
              collider.pieces.push_back(std::move(piece));
              collider.partOfPiece.push_back(static_cast<int>(i));
            }
            collider.bounds = collider.bounds.merged(partCollider->bounds);
          }
          return collider;
        } else if constexpr (std::is_same_v<T, TriangleMeshShape>) {
          const std::string where = sourceName + " (trimesh '" + s.file + "')";
          if (!s.mesh) return Error{where + ": the mesh was not loaded"};
          auto triangles = buildTriangleMeshCollider(*s.mesh, shapeToBody, where);
          if (!triangles) return triangles.error();
          collider.triangles = std::move(triangles).value();
          collider.bounds = collider.triangles->bvh.bounds();
          return collider;
        } else {
          static_assert(std::is_same_v<T, PlaneShape>);
          const double length = s.normal.norm();
          if (!s.normal.allFinite() || !(length > 0.0) || !std::isfinite(s.offset))
            return Error{sourceName + ": plane normal must be finite and non-zero"};
          // n · p_shape <= d with p_shape = Rᵀ (p_body − t) gives
          // (R n) · p_body <= d + (R n) · t; then scale to a unit normal.
          const Vec3 normal = shapeToBody.rotate(s.normal) / length;
          collider.plane =
              PlaneShape{normal, s.offset / length + normal.dot(shapeToBody.translation)};
          collider.bounds = Aabb::everything();
          return collider;
        }
      },
      shape);
}

double colliderRadius(const Collider& collider) {
  if (collider.plane) return 0.0;
  return collider.bounds.min.cwiseAbs().cwiseMax(collider.bounds.max.cwiseAbs()).norm();
}

}  // namespace rbsim
