#include "physics/collision/triangle_mesh_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "physics/collision/box_features.h"
#include "physics/collision/contact_routines.h"
#include "physics/collision/triangle_contacts.h"

namespace rbsim {

namespace {

// Two triangles' points closer than this on the piece are one point (m).
constexpr double kSamePoint = 1e-9;

// Is `point` (on the piece) already among the kept manifolds', with about
// the same normal?
bool reportedBefore(const std::vector<TriangleManifold>& kept, std::size_t begin,
                    const Vec3& normal, const ContactPoint& point) {
  for (std::size_t m = begin; m < kept.size(); ++m) {
    const ContactManifold& manifold = kept[m].manifold;
    if (manifold.normal.dot(normal) < kFlatCosine) continue;
    for (int k = 0; k < manifold.pointCount; ++k) {
      if ((manifold.points[static_cast<std::size_t>(k)].pointB - point.pointB).norm() <= kSamePoint)
        return true;
    }
  }
  return false;
}

// The distance from box x to box y (0 when they overlap).
double boxDistance(const Aabb& x, const Aabb& y) {
  const Vec3 gap = (x.min - y.max).cwiseMax(y.min - x.max).cwiseMax(Vec3::Zero());
  return gap.norm();
}

}  // namespace

void collideTriangleMeshPiece(const TriangleMeshCollider& mesh, const Transform& meshPose,
                              const PlacedConvex& piece, const ContactSettings& settings,
                              std::vector<TriangleManifold>& out) {
  const Transform pieceInMesh = meshPose.inverse() * piece.pose;
  const Aabb query = placedBounds(*piece.geometry, pieceInMesh).fattened(settings.margin);
  std::vector<int> near;
  mesh.bvh.forEachOverlap(query, [&near](int triangle) { near.push_back(triangle); });
  std::sort(near.begin(), near.end());
  // A box meets triangles as the hull it is (box_features.h, the same
  // numbering): made once here, not once per triangle.
  ConvexGeometry boxAsHull;
  PlacedConvex tested = piece;
  if (const auto* box = std::get_if<BoxShape>(piece.geometry); box && !near.empty()) {
    boxAsHull = std::make_shared<const ConvexHull>(boxHull(box->halfExtents));
    tested.geometry = &boxAsHull;
  }
  const std::size_t begin = out.size();
  for (const int t : near) {
    ContactManifold manifold;
    if (!collideTriangleConvex(mesh.triangle(t, meshPose), tested, settings, manifold)) continue;
    ContactManifold unique;
    unique.normal = manifold.normal;
    for (int k = 0; k < manifold.pointCount; ++k) {
      const ContactPoint& point = manifold.points[static_cast<std::size_t>(k)];
      if (!reportedBefore(out, begin, manifold.normal, point)) unique.add(point);
    }
    if (unique.pointCount > 0) out.push_back({t, unique});
  }
}

bool collideTriangleOfMesh(const TriangleMeshCollider& mesh, int triangle,
                           const Transform& meshPose, const PlacedConvex& piece,
                           const ContactSettings& settings, ContactManifold& out) {
  out = {};
  if (triangle < 0 || triangle >= mesh.triangleCount()) return false;
  return collideTriangleConvex(mesh.triangle(triangle, meshPose), piece, settings, out);
}

SignedDistance triangleMeshDistance(const TriangleMeshCollider& mesh, const Transform& meshPose,
                                    const PlacedConvex& piece, const DistanceSettings& settings) {
  SignedDistance best;
  best.distance = std::numeric_limits<double>::infinity();
  const Transform pieceInMesh = meshPose.inverse() * piece.pose;
  const Aabb pieceBox = placedBounds(*piece.geometry, pieceInMesh);
  mesh.bvh.traverse(
      [&](const Aabb& box) { return boxDistance(box, pieceBox) < best.distance; },
      [&](int t) {
        const auto hull = std::make_shared<const ConvexHull>(triangleHull(mesh.triangle(t, meshPose)));
        const ConvexGeometry geometry = hull;
        const SignedDistance d = signedDistance({&geometry, Transform::identity()}, piece, settings);
        if (d.distance < best.distance) best = d;
      });
  return best;
}

}  // namespace rbsim
