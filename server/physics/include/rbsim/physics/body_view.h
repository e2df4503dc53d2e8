#pragma once
// What a user sees of a body: its description, fixed at creation, and a
// read-only view of its moving state. Bodies themselves are internal to the
// physics library; World hands out views (World::body, World::bodies) and
// takes every change through its own functions (applyWrench, setBodyState,
// ...), so that sleep, the numerical guard and load tracking stay in step
// with what was changed.
//
// A view is valid until the world it came from creates or removes a body,
// or is assigned, moved or destroyed (like an iterator into a vector).

#include <cstdint>
#include <memory>
#include <string>

#include "rbsim/physics/collision_filter.h"
#include "rbsim/physics/freeze_reason.h"
#include "rbsim/physics/material.h"
#include "rbsim/physics/rigid_state.h"
#include "rbsim/physics/mass_properties.h"
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/shapes.h"

namespace rbsim {

// The body's collision geometry. The collision layer (collision/collider.h)
// builds and reads it; a body only carries it, so it is only named here.
struct Collider;

// What a body is, fixed at creation. Shared (immutably) between copies of a
// world, so copying a world for a look-ahead or a checkpoint is cheap.
struct BodyDescription {
  std::string name;
  Shape shape;                  // in the shape's own frame, as the user gave it
  bool isStatic = false;
  // In the shape's frame. A static body's are what its shape would weigh
  // at the default density (they place its body frame); the dynamics never
  // read them, BodyView::mass() is 0, and reports say 0.
  MassProperties massProperties;
  // True when the mass, centre of mass and inertia were given (BodyDef::
  // inertia) rather than computed from the shape; the volume is the shape's
  // either way.
  bool massPropertiesGiven = false;
  // Placement of the shape's frame in body space (origin at the centre of
  // mass, axes along the principal axes): p_body = shapeRotation p_shape + shapeTranslation.
  Mat3 shapeRotation = Mat3::Identity();
  Vec3 shapeTranslation = Vec3::Zero();  // m
  Vec3 shapeToBodyPoint(const Vec3& shapePoint) const {
    return shapeRotation * shapePoint + shapeTranslation;
  }
  Vec3 shapeToBodyVector(const Vec3& shapeVector) const { return shapeRotation * shapeVector; }
  Vec3 bodyToShapePoint(const Vec3& bodyPoint) const {
    return shapeRotation.transpose() * (bodyPoint - shapeTranslation);
  }
  // For mesh shapes: the mesh re-expressed in body space. Null otherwise.
  std::shared_ptr<const TriangleMesh> bodySpaceMesh;
  // Collision geometry in body space; null for a body that collides with
  // nothing (`collides` false), which detection and the sweeps then skip.
  std::shared_ptr<const Collider> collider;
  Material material;                 // resolved against the world's defaults
  bool continuousCollision = false;  // swept against fast motion (see BodyDef)
  bool collides = true;              // false: no collider, never in a contact (see BodyDef)
  CollisionFilter collisionFilter;   // its group and mask (see BodyDef)
};

class Body;

class BodyView {
 public:
  BodyView(const Body& body, bool pushed) : m_body(&body), m_pushed(pushed) {}

  const BodyDescription& description() const;
  const std::string& name() const;
  // Never reused within a world: the n-th body created has serial n (from 1).
  // Creation order is ascending serial order.
  int32_t serial() const;
  bool isStatic() const;

  const BodyDynamics& dynamics() const;  // mass, principal moments, damping
  double mass() const;         // kg (0 for static)
  double inverseMass() const;  // 1/kg

  // The 13 state numbers (x, q, P, L) and what follows from them.
  const RigidState& state() const;
  const Vec3& position() const;           // m, centre of mass, world
  const Quaternion& orientation() const;  // body -> world
  const Vec3& linearMomentum() const;     // kg·m/s, world
  const Vec3& angularMomentum() const;    // kg·m²/s, world, about the centre of mass
  const Mat3& rotation() const;             // body -> world
  const Mat3& inverseInertiaWorld() const;  // R Ibody⁻¹ Rᵀ
  Mat3 inertiaWorld() const;                // R Ibody Rᵀ
  const Vec3& linearVelocity() const;   // m/s, world
  const Vec3& angularVelocity() const;  // rad/s, world
  // Velocity of the material point at a world position: v + ω × (p − x).
  Vec3 velocityAtPoint(const Vec3& worldPoint) const;
  Vec3 bodyToWorld(const Vec3& bodyPoint) const;
  Vec3 worldToBody(const Vec3& worldPoint) const;
  double kineticEnergy() const;  // J

  // Asleep: at rest with its whole island, not integrated until something
  // touches or pushes it.
  bool isSleeping() const;
  // Frozen by the numerical guard: held still at its last good pose.
  bool isFrozen() const;
  FreezeReason freezeReason() const;
  // A load (wrench) is waiting for the coming step.
  bool isPushed() const;

 private:
  const Body* m_body;
  bool m_pushed;
};

}  // namespace rbsim
