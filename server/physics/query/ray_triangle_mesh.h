#pragma once
// The first triangle of a trimesh that a ray meets, through the mesh's BVH.
// Rays see a triangle from both sides: a range sensor sees a wall from
// either side, and an open surface has no inside to start in. The normal
// reported is the triangle's face normal turned to face the ray.

#include <optional>

#include "physics/collision/triangle_mesh_collider.h"
#include "physics/query/ray_segment.h"

namespace rbsim {

struct TriangleRayHit {
  int triangle = 0;
  double fraction = 0.0;
  Vec3 normal = Vec3::Zero();  // unit, in the mesh's frame, against the ray
};

// Where the segment origin + t delta meets triangle (a, b, c), t in
// [0, maxFraction] (Möller and Trumbore, "Fast, minimum storage
// ray/triangle intersection", 1997). Edges and corners count as the
// triangle's; a segment in the triangle's plane meets it nowhere.
std::optional<double> segmentTriangleFraction(const Vec3& origin, const Vec3& delta, const Vec3& a,
                                              const Vec3& b, const Vec3& c, double maxFraction);

// The least (fraction, triangle) hit of the segment (in the mesh's frame).
std::optional<TriangleRayHit> castTriangleMesh(const TriangleMeshCollider& mesh,
                                               const RaySegment& segment, double maxFraction);

}  // namespace rbsim
