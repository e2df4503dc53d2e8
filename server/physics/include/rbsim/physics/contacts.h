#pragma once
// The contacts of a step as the world reports them (World::contacts): per
// touching pair of pieces, the normal, the points and the impulses the
// solver found. Also the solver's warm-start cache for the next step.

#include <cstdint>

#include "rbsim/physics/math_types.h"

namespace rbsim {

// One solved contact point, kept for warm starting the next step and for
// reporting (RBSIM_CONTACTS).
struct SolvedContactPoint {
  Vec3 point = Vec3::Zero();         // m, world, midway between the surfaces
  double depth = 0.0;                // m
  double normalImpulse = 0.0;        // N·s, accumulated this step
  Vec3 tangentImpulse = Vec3::Zero();  // N·s, world: the patch's friction shared by normal load
  // m/s, negative: approaching. At the step's start state; for a contact
  // that a collision reached through a chain of touching bodies, as it
  // reached it (the solver's propagation pass).
  double relativeNormalVelocity = 0.0;
  bool sticking = false;
  uint32_t featureId = 0;
};

// Contact classification by the relative normal velocity at a point
// (v_rel = n · (vB(p) − vA(p)), negative when closing).
enum class ContactKind { Colliding, Resting, Separating };
inline ContactKind classifyContact(double relativeNormalVelocity, double epsilon) {
  if (relativeNormalVelocity < -epsilon) return ContactKind::Colliding;
  if (relativeNormalVelocity > epsilon) return ContactKind::Separating;
  return ContactKind::Resting;
}

struct SolvedManifold {
  int32_t serialA = 0;
  int32_t serialB = 0;
  int pieceA = 0;
  int pieceB = 0;
  int bodyA = 0;  // dense indices at the time of the step
  int bodyB = 0;
  Vec3 normal = Vec3::UnitZ();
  Vec3 frictionImpulse = Vec3::Zero();  // N·s, world, tangential, at the patch centroid
  double twistImpulse = 0.0;            // N·m·s about the normal
  bool sticking = false;                // the patch did not slip
  int pointCount = 0;
  SolvedContactPoint points[4];
};

}  // namespace rbsim
