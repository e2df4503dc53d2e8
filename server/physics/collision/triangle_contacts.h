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

#include <vector>

#include "physics/collision/collider.h"
#include "physics/collision/contact_manifold.h"
#include "physics/collision/convex_hull.h"
#include "physics/collision/triangle_mesh_collider.h"
#include "rbsim/physics/contact_settings.h"

namespace rbsim {

// A hull (or a box as boxHull) placed in the world, with what the
// separating-axis test asks of it for every triangle it meets: its corners,
// its faces' planes and one direction per set of parallel edges (a box's
// twelve edges have three). Made once per piece and step
// (triangle_mesh_contacts.cpp), not once per triangle.
struct PlacedHull {
  const ConvexHull* hull = nullptr;
  Transform pose;
  std::vector<Vec3> corners;        // m, world
  std::vector<Vec3> faceNormals;    // unit, world, outward
  std::vector<double> faceOffsets;  // m: faceNormals[f] · p on face f
  std::vector<Vec3> edgeDirections; // world, not normalised: one edge of each direction
  std::vector<int> edgeOfDirection; // the hull edge each direction is taken from (the first)

  void place(const ConvexHull& hull, const Transform& pose);
};

// Writes the manifold with its normal from the triangle to the piece, as
// the other narrow-phase routines do (contact_routines.h): depth =
// normal · (pointA − pointB), pointA on the triangle. Returns whether it
// wrote any point. `correctInternalEdges` false keeps every edge's own
// normal (the geometry alone), for tests that show what the correction does.
// `placed`, when given, is the piece's hull placed (PlacedHull::place with
// the piece's hull, or its box's, and pose): the same answer, sooner.
bool collideTriangleConvex(const ContactTriangle& triangle, const PlacedConvex& convex,
                           const ContactSettings& settings, ContactManifold& out,
                           bool correctInternalEdges = true, const PlacedHull* placed = nullptr);

// The triangle as a flat convex hull (front and back faces), in the
// triangle's frame, for GJK and the signed-distance queries.
ConvexHull triangleHull(const ContactTriangle& triangle);

}  // namespace rbsim
