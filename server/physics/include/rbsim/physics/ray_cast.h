#pragma once
// Ray casts against a world's bodies: what a ray is, which bodies it may
// hit and what a hit reports (World::castRay and its kin, world.h;
// docs/queries.md). SI units, world frame.
//
// A ray is the segment from `from` to `to`: a range sensor's beam from its
// origin out to its maximum range. Every body with collision geometry can
// be hit, static ones and planes too, but not frozen bodies (out of the
// simulation) nor bodies that do not collide (BodyDef::collides false).
// Solids are closed and solid: a ray that starts inside one, or on its
// surface, hits it at fraction 0, at its start, with the normal opposite
// to the ray (as Jolt does for convex shapes treated as solid): a sensor
// buried in a body reads 0. A trimesh is a surface, not a solid: a ray
// meets its triangles from either side, where it crosses them, with the
// face normal turned against the ray.

#include <cstdint>

#include "rbsim/physics/collision_filter.h"
#include "rbsim/physics/ids.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct Ray {
  Vec3 from = Vec3::Zero();  // m, world
  Vec3 to = Vec3::UnitX();   // m, world; a ray with to == from (or not finite) hits nothing

  // The ray from `origin` along `direction` (any non-zero length) for `length` m.
  static Ray along(const Vec3& origin, const Vec3& direction, double length) {
    return {origin, origin + direction.normalized() * length};
  }
};

// Which bodies a ray may hit.
struct RayFilter {
  // The ray's own collision group and mask, by the bodies' rule
  // (collision_filter.h): a body is hit only when the two filters allow
  // each other, (ray.group & body.mask) != 0 && (body.group & ray.mask) != 0,
  // as Bullet's ray callbacks do. The default hits every body whose mask
  // holds category 1, which by default is every body.
  CollisionFilter filter;
  // A body never hit (a sensor's own); null: none.
  BodyId excluded;
};

struct RayHit {
  BodyId body;
  // The body's compound part that was hit (0 for other shapes), and its
  // convex piece: a compound's parts in order, a mesh's connected
  // components in order of their first vertex (for a compound of
  // primitives, the piece is the part); for a trimesh, the piece is the
  // triangle hit (its index in the mesh file's order).
  int part = 0;
  int piece = 0;
  double fraction = 0.0;       // along from → to, in [0, 1]
  double distance = 0.0;       // m from `from`: fraction |to − from|
  Vec3 point = Vec3::Zero();   // m, world: from + fraction (to − from)
  Vec3 normal = Vec3::Zero();  // unit, world, out of the surface hit (opposite the ray when it starts inside)
};

}  // namespace rbsim
