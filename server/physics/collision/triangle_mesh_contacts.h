#pragma once
// A convex piece against a whole trimesh: the BVH gives the triangles near
// the piece, the triangle narrow phase (triangle_contacts.h) one manifold
// per triangle. A point that two triangles both report (a sphere resting on
// the edge they share, a box corner on a shared vertex) is kept once, by
// the triangle of the smaller index. Then the manifolds whose normals agree
// (within about 3°: one plane of the mesh under the piece) are merged into
// one of at most four points, named by the patch's lowest triangle, as a
// face resting on a plane would give.

#include <vector>

#include "physics/collision/collider.h"
#include "physics/collision/contact_manifold.h"
#include "physics/collision/signed_distance.h"
#include "physics/collision/triangle_mesh_collider.h"
#include "rbsim/physics/contact_settings.h"

namespace rbsim {

struct TriangleManifold {
  int triangle = 0;
  ContactManifold manifold;  // normal from the mesh to the piece
};

// Appends the manifolds of `piece` against the mesh placed at `meshPose`
// (body -> world), one per patch, in ascending order of their first
// triangle; only triangles whose boxes come within the margin of the
// piece's box are tried. A point's featureId has its triangle's index
// mixed in, so that it stays unique within a merged patch.
void collideTriangleMeshPiece(const TriangleMeshCollider& mesh, const Transform& meshPose,
                              const PlacedConvex& piece, const ContactSettings& settings,
                              std::vector<TriangleManifold>& out);

// The manifold of one triangle, as collideTriangleMeshPiece gives it
// (without dropping points its neighbours share): what the impact search
// asks for a (triangle, piece) pair.
bool collideTriangleOfMesh(const TriangleMeshCollider& mesh, int triangle,
                           const Transform& meshPose, const PlacedConvex& piece,
                           const ContactSettings& settings, ContactManifold& out);

// The smallest signed distance from the piece to the mesh's triangles
// (each a flat, two-sided hull here), normal from the mesh to the piece;
// +infinity for an empty mesh. Triangles whose boxes lie farther from the
// piece's box than the best distance so far are skipped.
SignedDistance triangleMeshDistance(const TriangleMeshCollider& mesh, const Transform& meshPose,
                                    const PlacedConvex& piece, const DistanceSettings& settings);

}  // namespace rbsim
