#pragma once
// Support features: the face, edge or point of a convex solid that faces a
// direction. Contact generation without a dedicated routine clips the two
// support features against each other, so that a face resting on a face
// gets a whole manifold and not the single point of a distance query
// (Gregorius, "Robust contact creation for physics simulations", GDC 2015;
// Jolt's GetSupportingFace plays the same role).

#include <cstdint>
#include <vector>

#include "physics/collision/collider.h"
#include "rbsim/physics/shapes.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct SupportFeature {
  // World: one vertex is a point, two a segment, three or more a convex
  // polygon counter-clockwise seen from outside the solid.
  std::vector<Vec3> vertices;
  Vec3 normal = Vec3::Zero();  // a polygon's unit outward normal
  uint32_t id = 0;             // which feature of the solid, for feature ids
};

// The feature of `solid` farthest along the unit world `direction`: a face
// whose normal is within about 3° of it (kFlatCosine), else an edge
// perpendicular to it within as much, else the support point. For rounded
// solids the features lie on the surface (a capsule's side gives the line
// it would rest on). A cylinder's cap is a regular polygon of
// kCylinderCapSides vertices, fixed in the cylinder's frame so that the
// points (and their ids) stay put while it rests.
SupportFeature supportFeature(const PlacedConvex& solid, const Vec3& direction);

inline constexpr int kCylinderCapSides = 8;
// Vertex k of the polygon standing for the top (or bottom) cap, in the
// cylinder's frame, counter-clockwise seen from outside.
Vec3 cylinderCapVertex(const CylinderShape& cylinder, bool top, int k);

}  // namespace rbsim
