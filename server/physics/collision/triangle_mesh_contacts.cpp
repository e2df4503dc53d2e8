#include "physics/collision/triangle_mesh_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <variant>

#include "physics/collision/box_features.h"
#include "physics/collision/contact_routines.h"
#include "physics/collision/polygon_clipping.h"
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

// A point's feature id made unique across the triangles of a patch: the
// triangle's index mixed in (a multiplicative hash), so that the solver's
// warm start matches the same triangle's same features from step to step
// whichever manifold of the patch they end up in.
uint32_t patchFeatureId(uint32_t featureId, int triangle) {
  return featureId ^ (static_cast<uint32_t>(triangle) * 0x9E3779B1u);
}

// Manifolds of one piece whose normals agree within kFlatCosine touch one
// plane of the mesh (a box on a floor made of many triangles): when they
// hold more than four points in all, they become one manifold, their
// points pooled and reduced to four as one face's would be, under the
// patch's first (lowest) triangle. The solver then sees the piece on the
// mesh as on a plane: one patch of four points, one friction and twist,
// and not one manifold per triangle under it.
void mergePatches(std::vector<TriangleManifold>& manifolds, std::size_t begin, std::vector<ContactPoint>& pooled,
                  std::vector<int>& group, std::vector<char>& taken) {
  const std::size_t end = manifolds.size();
  taken.assign(end - begin, 0);
  thread_local std::vector<TriangleManifold> result;
  result.clear();
  for (std::size_t i = begin; i < end; ++i) {
    if (taken[i - begin]) continue;
    const Vec3 normal = manifolds[i].manifold.normal;
    group.clear();
    std::size_t points = 0;
    for (std::size_t j = i; j < end; ++j) {
      if (taken[j - begin] || manifolds[j].manifold.normal.dot(normal) < kFlatCosine) continue;
      taken[j - begin] = 1;
      group.push_back(static_cast<int>(j));
      points += static_cast<std::size_t>(manifolds[j].manifold.pointCount);
    }
    // Four points or fewer in all: the manifolds stay as they are (the
    // pooled patch would hold the same points, and a patch of single-point
    // contacts, a cylinder's rim across two triangles, keeps each its own).
    if (points <= 4) {
      // A point two of them report (on an edge or a vertex they share) once,
      // by the lower triangle.
      const std::size_t first = result.size();
      for (const int j : group) {
        const TriangleManifold& member = manifolds[static_cast<std::size_t>(j)];
        TriangleManifold unique{member.triangle, {}};
        unique.manifold.normal = member.manifold.normal;
        for (int k = 0; k < member.manifold.pointCount; ++k) {
          const ContactPoint& point = member.manifold.points[static_cast<std::size_t>(k)];
          if (!reportedBefore(result, first, member.manifold.normal, point)) unique.manifold.add(point);
        }
        if (unique.manifold.pointCount > 0) result.push_back(unique);
      }
      continue;
    }
    TriangleManifold patch = manifolds[i];
    pooled.clear();
    for (const int j : group) {
      const TriangleManifold& member = manifolds[static_cast<std::size_t>(j)];
      for (int k = 0; k < member.manifold.pointCount; ++k) {
        ContactPoint point = member.manifold.points[static_cast<std::size_t>(k)];
        point.featureId = patchFeatureId(point.featureId, member.triangle);
        pooled.push_back(point);
      }
    }
    patch.manifold.pointCount = 0;
    reduceContacts(pooled, patch.manifold.normal, patch.manifold);
    result.push_back(patch);
  }
  // In ascending order of their (first) triangle, as before the merge.
  std::stable_sort(result.begin(), result.end(),
                   [](const TriangleManifold& x, const TriangleManifold& y) { return x.triangle < y.triangle; });
  manifolds.resize(begin);
  manifolds.insert(manifolds.end(), result.begin(), result.end());
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
  thread_local std::vector<int> near;
  near.clear();
  mesh.bvh.forEachOverlap(query, [](int triangle) { near.push_back(triangle); });
  std::sort(near.begin(), near.end());
  // A box meets triangles as the hull it is (box_features.h, the same
  // numbering): made once here, not once per triangle.
  ConvexGeometry boxAsHull;
  PlacedConvex tested = piece;
  if (const auto* box = std::get_if<BoxShape>(piece.geometry); box && !near.empty()) {
    boxAsHull = std::make_shared<const ConvexHull>(boxHull(box->halfExtents));
    tested.geometry = &boxAsHull;
  }
  // A hull's corners, faces and edge directions placed once for all the triangles.
  thread_local PlacedHull placedHull;
  const PlacedHull* placed = nullptr;
  if (const auto* hull = std::get_if<std::shared_ptr<const ConvexHull>>(tested.geometry); hull && !near.empty()) {
    placedHull.place(**hull, tested.pose);
    placed = &placedHull;
  }
  const std::size_t begin = out.size();
  // A polytope's manifolds are merged into patches below, which drops the
  // points two triangles share: they go in as they come.
  const bool polytope = std::holds_alternative<BoxShape>(*piece.geometry) ||
                        std::holds_alternative<std::shared_ptr<const ConvexHull>>(*piece.geometry);
  for (const int t : near) {
    ContactManifold manifold;
    if (!collideTriangleConvex(mesh.triangle(t, meshPose), tested, settings, manifold, true, placed)) continue;
    if (polytope) {
      out.push_back({t, manifold});
      continue;
    }
    ContactManifold unique;
    unique.normal = manifold.normal;
    for (int k = 0; k < manifold.pointCount; ++k) {
      const ContactPoint& point = manifold.points[static_cast<std::size_t>(k)];
      if (!reportedBefore(out, begin, manifold.normal, point)) unique.add(point);
    }
    if (unique.pointCount > 0) out.push_back({t, unique});
  }
  // Only a polytope's patches are merged: their points are its corners,
  // which the reduction picks the same way step after step. A round
  // piece's cap (a cylinder's polygon of rim points, all as far from the
  // centre) would leave the choice among ties to the micrometres a
  // landing rocks it by, and its manifold's points would swap.
  if (polytope) {
    thread_local std::vector<ContactPoint> pooled;
    thread_local std::vector<int> group;
    thread_local std::vector<char> taken;
    mergePatches(out, begin, pooled, group, taken);
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
