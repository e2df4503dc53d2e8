#pragma once
// One contact point of the penalty model, in a form that can be evaluated at
// any state of its two bodies within a step.
//
// The detector finds the manifolds once, at the step start. Each point is then
// kept as two material points, one fixed in each body (pA on A, pB on B), and
// the manifold normal n, so that at a stage state the depth and its rate are
//   d = d₀ + n · ((pA − pB) − (pA₀ − pB₀)),   ḋ = −n · (vB(pB) − vA(pA)),
// with v(p) = v + ω × (p − x): ḋ is the exact time derivative of d.
// The normal is held fixed in the world over the step. For a plane, or any
// static body, that is exact: a static face does not turn. Between two moving
// bodies it turns by |ω| dt in a step, which changes d by O((|ω| dt)² d),
// below the error of keeping the detected features over the step.

#include "rbsim/physics/math_types.h"
#include "rbsim/physics/world_settings.h"

namespace rbsim {

// Where a body is and how it moves at one state (a stage of a step).
struct BodyMotion {
  Vec3 position = Vec3::Zero();         // m, centre of mass, world
  Mat3 rotation = Mat3::Identity();     // body -> world
  Vec3 linearVelocity = Vec3::Zero();   // m/s, world
  Vec3 angularVelocity = Vec3::Zero();  // rad/s, world

  Vec3 velocityAt(const Vec3& worldPoint) const {
    return linearVelocity + angularVelocity.cross(worldPoint - position);
  }
};

struct PenaltyPoint {
  int bodyA = 0;  // dense indices of the manifold's bodies (normal from A to B)
  int bodyB = 0;
  Vec3 localA = Vec3::Zero();    // m, pA in A's body frame
  Vec3 localB = Vec3::Zero();    // m, pB in B's body frame
  Vec3 normal = Vec3::UnitZ();   // unit, world, from A to B
  double depthOffset = 0.0;      // m: d = depthOffset + n · (pA − pB)
  double stiffness = 0.0;        // N/m: the manifold's k, this point's share
  double damping = 0.0;          // N·s/m: the manifold's c, this point's share
  double frictionDamping = 0.0;  // N·s/m: tangential viscosity, this point's share
  double friction = 0.0;         // Coulomb coefficient of the pair
};

// The detected point (world points pA₀ on A and pB₀ on B at the step start,
// depth d₀) as material points of bodies at `motionA` and `motionB`.
PenaltyPoint makePenaltyPoint(int bodyA, int bodyB, const BodyMotion& motionA,
                              const BodyMotion& motionB, const Vec3& pointA, const Vec3& pointB,
                              double depth, const Vec3& normal);

// The point at a state of its bodies.
struct PenaltyGap {
  Vec3 pointA = Vec3::Zero();            // m, world
  Vec3 pointB = Vec3::Zero();            // m, world
  double depth = 0.0;                    // m, d (> 0: penetrating)
  Vec3 relativeVelocity = Vec3::Zero();  // m/s, vB(pB) − vA(pA)
  double normalVelocity = 0.0;           // m/s, n · relativeVelocity = −ḋ
};
PenaltyGap penaltyGap(const PenaltyPoint& point, const BodyMotion& motionA,
                      const BodyMotion& motionB);

// k d + c ḋ: the linear spring–damper force, whatever its sign.
inline double linearPenaltyForce(const PenaltyPoint& point, const PenaltyGap& gap) {
  return point.stiffness * gap.depth - point.damping * gap.normalVelocity;
}

// Whether the law pushes at this gap: d > 0, and for the clamped law also
// k d + c ḋ > 0. The normal force is linearPenaltyForce where it does, zero
// elsewhere: a function of the state that jumps where this changes (at
// touch-down c ḋ ≠ 0), which the RK4 path steps to exactly.
bool penaltyPushes(PenaltyLaw law, const PenaltyPoint& point, const PenaltyGap& gap);

// The force on B (the opposite acts on A), both through the midpoint of pA
// and pB so that the pair exerts no net torque. `pushing` says whether the
// normal law applies (see penaltyPushes). Tangentially a viscous force,
// capped at the Coulomb limit μ max(0, F_n).
struct PenaltyForce {
  Vec3 point = Vec3::Zero();     // m, world, where it acts
  double normal = 0.0;           // N, along the normal (negative: pulling, unclamped law)
  Vec3 friction = Vec3::Zero();  // N, world, tangential
  Vec3 onB = Vec3::Zero();       // N, world: normal · n + friction, the whole force on B
};
PenaltyForce penaltyForce(const PenaltyPoint& point, const PenaltyGap& gap, bool pushing);

}  // namespace rbsim
