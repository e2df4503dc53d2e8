#pragma once
// The narrow phase between one triangle of a trimesh and one convex piece.
//
// Triangles are one-sided: behind a triangle is solid, and a contact whose
// normal would push the piece through the triangle's back (normal · face
// normal < 0) is not reported; the neighbouring triangle whose front faces
// the piece reports it instead. Internal edges: when the normal comes from
// an edge or vertex of the triangle that is not active (active_edges.h), the
// triangle's face normal replaces it, so that a body sliding over a flat
// floor of many triangles meets one plane and not the edges between them.

#include "physics/collision/collider.h"
#include "physics/collision/contact_manifold.h"
#include "physics/collision/convex_hull.h"
#include "physics/collision/triangle_mesh_collider.h"
#include "rbsim/physics/contact_settings.h"

namespace rbsim {

// Writes the manifold with its normal from the triangle to the piece, as
// the other narrow-phase routines do (contact_routines.h): depth =
// normal · (pointA − pointB), pointA on the triangle. Returns whether it
// wrote any point. `correctInternalEdges` false keeps every edge's own
// normal (the geometry alone), for tests that show what the correction does.
bool collideTriangleConvex(const ContactTriangle& triangle, const PlacedConvex& convex,
                           const ContactSettings& settings, ContactManifold& out,
                           bool correctInternalEdges = true);

// The triangle as a flat convex hull (front and back faces), in the
// triangle's frame, for GJK and the signed-distance queries.
ConvexHull triangleHull(const ContactTriangle& triangle);

}  // namespace rbsim
