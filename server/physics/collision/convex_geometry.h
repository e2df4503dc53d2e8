#pragma once
// The convex geometries collision detection works on, each in its own frame
// (centred at its origin; cylinder and capsule along z), and their support
// functions: support(d) is a point of the solid that is farthest along d.

#include <memory>
#include <variant>

#include "physics/collision/aabb.h"
#include "physics/collision/convex_hull.h"
#include "rbsim/physics/shapes.h"
#include "rbsim/physics/transform.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

using ConvexGeometry = std::variant<SphereShape, BoxShape, CapsuleShape, CylinderShape,
                                    std::shared_ptr<const ConvexHull>>;

// Farthest point along `direction` (need not be unit; a zero direction gives
// some point of the solid), in the geometry's frame.
Vec3 supportPoint(const ConvexGeometry& geometry, const Vec3& direction);

// Bounding box in the geometry's frame.
Aabb geometryBounds(const ConvexGeometry& geometry);
// The tight bounding box of the geometry placed by `pose` (geometry frame ->
// target frame). Exact for every shape: each side is the support along an
// axis, so a rotated sphere keeps its box of side 2r.
Aabb placedBounds(const ConvexGeometry& geometry, const Transform& pose);
// Half the diagonal of geometryBounds: the length scale for tolerances.
double geometrySize(const ConvexGeometry& geometry);
// A point strictly inside the solid (the origin for primitives, the mean of
// the vertices for a hull), in the geometry's frame: MPR's centre.
Vec3 interiorPoint(const ConvexGeometry& geometry);

// For sphere and capsule, GJK works on the core (a point or a segment) and
// adds this radius afterwards, which is exact and converges faster. 0 for the others.
double coreRadius(const ConvexGeometry& geometry);
// The support point of the core (the geometry shrunk by coreRadius).
Vec3 coreSupportPoint(const ConvexGeometry& geometry, const Vec3& direction);

}  // namespace rbsim
