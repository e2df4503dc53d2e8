#pragma once
// Everything needed to create a body: a plain value, filled with defaults.

#include <optional>
#include <string>

#include "rbsim/physics/collision_filter.h"
#include "rbsim/physics/material.h"
#include "rbsim/physics/mass_properties.h"  // inertiaTensorProblem: checks a tensor given as data
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/shapes.h"

namespace rbsim {

struct BodyDef {
  std::string name;  // unique within a world
  Shape shape = SphereShape{};

  // Give at most one of mass and density; with neither, density defaults to
  // kDefaultDensity. Ignored for static bodies.
  std::optional<double> mass;     // kg
  std::optional<double> density;  // kg/m³

  // Mass properties given as data (URDF <inertial>, CAD) instead of computed
  // from the shape, which then only collides. `inertia` is the tensor about
  // the centre of mass in the axes of the shape's frame (its own entries:
  // off-diagonals are minus the products of inertia) and requires `mass`;
  // `centerOfMass` is in the shape's frame and requires `inertia` (unset:
  // the frame's origin). Neither is allowed on a static body.
  std::optional<Mat3> inertia;       // kg·m²
  std::optional<Vec3> centerOfMass;  // m

  // Pose of the shape's frame (the frame its dimensions or mesh vertices are
  // given in) in the world. The body frame itself has its origin at the
  // centre of mass and its axes along the principal axes of inertia (Baraff's
  // "body space"); for the primitives the two frames coincide.
  Vec3 position = Vec3::Zero();                         // m
  Quaternion orientation = Quaternion::identity();      // shape -> world
  Vec3 linearVelocity = Vec3::Zero();                   // m/s, of the centre of mass, world frame
  Vec3 angularVelocity = Vec3::Zero();                  // rad/s, world frame

  bool isStatic = false;  // immovable: infinite mass, never integrated

  // Exponential decay rates of linear and angular momentum: dP/dt = -c P.
  // Unset means the world's default.
  std::optional<double> linearDamping;   // 1/s
  std::optional<double> angularDamping;  // 1/s

  // Restitution and friction; unset fields take the world's contact defaults.
  MaterialSpec material;
  // Continuous collision detection for this body: a fast body is stopped at
  // its time of impact instead of passing through thin geometry (costs a
  // sweep per step; for small fast bodies).
  bool continuousCollision = false;
  // Whether the body collides at all. One that does not (a robot link
  // without <collision> geometry) is never in a contact: collision
  // detection and the continuous collision sweeps leave it out, and its
  // shape only draws it (and gives its mass properties when none are
  // given). It is integrated, jointed, pushed and put to sleep like any
  // other body.
  bool collides = true;
  // Which bodies it may collide with (rbsim/physics/collision_filter.h):
  // its collision group and mask, Bullet's convention. The defaults collide
  // with everything.
  CollisionFilter collisionFilter;

  static constexpr double kDefaultDensity = 1000.0;  // kg/m³, water
};

}  // namespace rbsim
