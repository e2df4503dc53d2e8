#pragma once
// Shape casts against a world's bodies: a solid swept along a segment,
// without turning, and the first body it would touch (World::castShape and
// castShapeAll, world.h; docs/queries.md). SI units, world frame.
//
// What a cast may hit is what a ray may (ray_cast.h): every body with
// collision geometry, static ones and planes too, but not frozen bodies nor
// bodies that do not collide, filtered by a RayFilter. A cast that starts
// touching or overlapping a body hits it at fraction 0, with the normal
// opposite to the sweep, as a ray that starts inside a solid does.

#include <variant>

#include "rbsim/physics/ids.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/shapes.h"

namespace rbsim {

// The solids a cast may sweep: the primitives, in their own frames as in a
// world file (cylinder and capsule along their z axis).
using CastShape = std::variant<SphereShape, BoxShape, CapsuleShape, CylinderShape>;

struct ShapeCast {
  CastShape shape = SphereShape{};
  Vec3 from = Vec3::Zero();                         // m, world: the shape frame's origin at the start
  Vec3 to = Vec3::UnitX();                          // m, world: and at the end of the sweep
  Quaternion orientation = Quaternion::identity();  // shape -> world, the whole sweep long
};

struct ShapeCastHit {
  BodyId body;
  // The body's compound part and convex piece that were hit, as for a ray (RayHit).
  int part = 0;
  int piece = 0;
  double fraction = 0.0;       // along from → to, in [0, 1]: where the shape first touches the body
  double distance = 0.0;       // m the shape travelled: fraction |to − from|
  Vec3 point = Vec3::Zero();   // m, world: the point of the body the shape touches there
  Vec3 normal = Vec3::Zero();  // unit, world, out of the body's surface at `point` (opposite the sweep when it starts touching)
};

}  // namespace rbsim
