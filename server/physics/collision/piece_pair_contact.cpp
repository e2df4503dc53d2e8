#include "physics/collision/piece_pair_contact.h"

#include <cstddef>

#include "physics/collision/broad_phase.h"
#include "physics/collision/contact_routines.h"
#include "physics/collision/triangle_mesh_contacts.h"

namespace rbsim {

namespace {

PlacedConvex placed(const Collider& collider, int piece, const Transform& pose) {
  const ConvexPiece& p = collider.pieces[static_cast<std::size_t>(piece)];
  return {&p.geometry, pose * p.placement};
}

}  // namespace

bool collidePiecePair(const Collider& a, int pieceA, const Transform& poseA, const Collider& b,
                      int pieceB, const Transform& poseB, const ContactSettings& settings,
                      ContactManifold& out) {
  out = {};
  if (a.plane && b.plane) return false;  // two half-spaces have no manifold
  // A trimesh's piece is a triangle; a trimesh meets only convex pieces.
  if (a.triangles) {
    if (b.triangles || b.plane) return false;
    return collideTriangleOfMesh(*a.triangles, pieceA, poseA, placed(b, pieceB, poseB), settings,
                                 out);
  }
  if (b.triangles) {
    if (a.plane) return false;
    if (!collideTriangleOfMesh(*b.triangles, pieceB, poseB, placed(a, pieceA, poseA), settings,
                               out))
      return false;
    flipManifold(out);
    return true;
  }
  if (a.plane) {
    const HalfSpace plane = worldHalfSpace(*a.plane, poseA);
    return collidePlaneConvex(plane.normal, plane.offset, placed(b, pieceB, poseB), settings, out);
  }
  if (b.plane) {
    // The narrow phase puts the plane first: swap the roles back afterwards.
    const HalfSpace plane = worldHalfSpace(*b.plane, poseB);
    if (!collidePlaneConvex(plane.normal, plane.offset, placed(a, pieceA, poseA), settings, out))
      return false;
    flipManifold(out);
    return true;
  }
  return collideConvex(placed(a, pieceA, poseA), placed(b, pieceB, poseB), settings, out);
}

}  // namespace rbsim
