#include "physics/query/ray_triangle_mesh.h"

#include <cmath>
#include <limits>

namespace rbsim {

std::optional<double> segmentTriangleFraction(const Vec3& origin, const Vec3& delta, const Vec3& a,
                                              const Vec3& b, const Vec3& c, double maxFraction) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 p = delta.cross(ac);
  const double determinant = ab.dot(p);
  // Parallel to the plane (within round-off of the triangle's size).
  if (!(std::abs(determinant) > 1e-14 * ab.norm() * ac.norm() * delta.norm())) return std::nullopt;
  const double inverse = 1.0 / determinant;
  const Vec3 s = origin - a;
  const double u = s.dot(p) * inverse;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Vec3 q = s.cross(ab);
  const double v = delta.dot(q) * inverse;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = ac.dot(q) * inverse;
  if (!(t >= 0.0 && t <= maxFraction)) return std::nullopt;
  return t;
}

std::optional<TriangleRayHit> castTriangleMesh(const TriangleMeshCollider& mesh,
                                               const RaySegment& segment, double maxFraction) {
  std::optional<TriangleRayHit> best;
  double reach = maxFraction;
  mesh.bvh.traverse(
      [&](const Aabb& box) {
        return segmentEntersBox(segment, box, reach) != std::numeric_limits<double>::infinity();
      },
      [&](int t) {
        const auto& corners = mesh.triangles[static_cast<std::size_t>(t)];
        const auto fraction = segmentTriangleFraction(
            segment.origin, segment.delta, mesh.vertices[static_cast<std::size_t>(corners[0])],
            mesh.vertices[static_cast<std::size_t>(corners[1])],
            mesh.vertices[static_cast<std::size_t>(corners[2])], reach);
        if (!fraction) return;
        // Ties go to the smaller triangle, whatever order the walk takes.
        if (best && (*fraction > best->fraction || (*fraction == best->fraction && t > best->triangle)))
          return;
        const Vec3& n = mesh.normals[static_cast<std::size_t>(t)];
        best = TriangleRayHit{t, *fraction, n.dot(segment.delta) > 0.0 ? Vec3(-n) : n};
        reach = *fraction;
      });
  return best;
}

}  // namespace rbsim
