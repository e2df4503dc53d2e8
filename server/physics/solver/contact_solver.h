#pragma once
// Impulse-based contact response for all contacts of one step: sequential
// impulses (projected Gauss–Seidel on the velocity constraints) with
// accumulated, clamped impulses and warm starting, as in Catto's "Iterative
// Dynamics with Temporal Coherence" (GDC 2005) and Box2D/Bullet.
//
//  - Normal: the seed's impulse j = −(1+e) v_rel / (1/Ma + 1/Mb + n·(Ia⁻¹(ra×n))×ra
//    + n·(Ib⁻¹(rb×n))×rb), applied iteratively over all points at once:
//    each iteration adds Δj = −m_n (v_rel − v_target) and clamps the
//    accumulated j at 0 (contacts push, never pull). The target normal
//    velocity is −e v_rel⁻ for colliding contacts (approach faster than the
//    restitution threshold), 0 for resting ones.
//  - Friction: Coulomb, per manifold rather than per point ("patch"
//    friction, as in PhysX and Box2D v3's anchor friction): two tangential
//    impulses at the centroid of the manifold's points clamped to the disc
//    |jt| <= μ Σjn, and a torsional impulse about the normal clamped to
//    μ r Σjn (r: the points' mean distance from the centroid). Friction per
//    corner, warm-started, locks in self-balancing patterns that leak energy
//    into tall stacks whenever a corner's load shifts; a patch cannot hold
//    such a pattern. μ is the static coefficient for a patch that was
//    sticking in the previous step, the kinetic one for a sliding patch.
//  - Position error: split impulses (Catto 2012; Bullet's split-impulse
//    mode). A separate pseudo-velocity solve pushes penetrations beyond the
//    slop out, and only positions see it: correcting the error adds no
//    kinetic energy, so resting stacks do not jitter or pop.
//  - Stacks: the last velocity sweep uses shock propagation (Guendelman,
//    Bridson and Fedkiw 2003; Erleben 2005): the lower body of each contact
//    is held still, so a tall stack's top cannot rock its base. Without it
//    Gauss–Seidel at 10 sweeps leaves a 20-box tower rocking.

#include <cstdint>
#include <vector>

#include "physics/collision/body_contact.h"
#include "physics/math/types.h"
#include "physics/solver/contact_solver_settings.h"
#include "physics/solver/material.h"

namespace rbsim {

// Velocities of one body as the solver sees them. Static bodies have zero
// inverse mass and inertia.
struct SolverBody {
  Vec3 linearVelocity = Vec3::Zero();     // m/s, world
  Vec3 angularVelocity = Vec3::Zero();    // rad/s, world
  // Velocities of the state the step starts from, before this step's forces:
  // what classifies a contact as colliding, resting or separating.
  Vec3 startLinearVelocity = Vec3::Zero();   // m/s
  Vec3 startAngularVelocity = Vec3::Zero();  // rad/s
  Vec3 pseudoLinear = Vec3::Zero();       // m/s: split-impulse position correction
  Vec3 pseudoAngular = Vec3::Zero();      // rad/s
  Mat3 inverseInertia = Mat3::Zero();     // 1/(kg·m²), world
  double inverseMass = 0.0;               // 1/kg
  Vec3 position = Vec3::Zero();           // m: centre of mass at the step start
};

// One solved contact point, kept for warm starting the next step and for
// reporting (RBSIM_CONTACTS).
struct SolvedContactPoint {
  Vec3 point = Vec3::Zero();         // m, world, midway between the surfaces
  double depth = 0.0;                // m
  double normalImpulse = 0.0;        // N·s, accumulated this step
  Vec3 tangentImpulse = Vec3::Zero();  // N·s, world: the patch's friction shared by normal load
  double relativeNormalVelocity = 0.0;  // m/s at the step's start state (negative: approaching)
  bool sticking = false;
  uint32_t featureId = 0;
};

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

  // Which bodies, pieces, normal and point count: everything but the impulses.
  static SolvedManifold identityOf(const BodyContact& contact, int32_t serialA, int32_t serialB) {
    SolvedManifold m;
    m.serialA = serialA;
    m.serialB = serialB;
    m.pieceA = contact.pieceA;
    m.pieceB = contact.pieceB;
    m.bodyA = contact.bodyA;
    m.bodyB = contact.bodyB;
    m.normal = contact.manifold.normal;
    m.pointCount = contact.manifold.pointCount;
    return m;
  }
};

class ContactSolver {
 public:
  // `bodies` holds one SolverBody per world body (dense index). Solves the
  // velocity constraints (bodies[].linear/angularVelocity are updated) and
  // the split-impulse position constraints (bodies[].pseudo* are set).
  // `previous` is last step's result, sorted as `contacts`: matching points
  // (same bodies, pieces and feature id) start from their old impulses.
  // `levels` (per body: contacts away from a static body; empty: none) turns
  // on shock propagation in the last velocity sweep.
  void solve(const std::vector<BodyContact>& contacts, const std::vector<PairMaterial>& materials,
             std::vector<SolverBody>& bodies, const std::vector<int32_t>& serials,
             const std::vector<SolvedManifold>& previous, const ContactSolverSettings& settings,
             double dt, std::vector<SolvedManifold>& result, const std::vector<int>& levels = {});

 private:
  struct PointConstraint {
    Vec3 rA, rB;               // m: from each centre of mass to the contact point
    double normalMass = 0.0;   // kg: 1 / (effective inverse mass along n)
    double shockNormalMass = 0.0;  // kg: the same with the lower body held still
    double normalImpulse = 0.0;
    double targetVelocity = 0.0;     // m/s: v_n the normal impulse aims for
    double pseudoImpulse = 0.0;      // N·s of the split-impulse solve
    double depth = 0.0;              // m
    double relativeNormalVelocity = 0.0;  // m/s at the step's start state (for classification)
    uint32_t featureId = 0;
  };
  enum class Frozen { None, A, B };  // which body a shock sweep holds still
  struct ManifoldConstraint {
    int bodyA = 0, bodyB = 0;
    Frozen frozen = Frozen::None;
    Vec3 normal, tangent1, tangent2;
    int pointCount = 0;
    PointConstraint points[4];
    // Patch friction at the centroid of the points.
    Vec3 rA, rB;                        // m: centre of mass to centroid
    double tangentMass[2] = {0.0, 0.0};
    double shockTangentMass[2] = {0.0, 0.0};
    double tangentImpulse[2] = {0.0, 0.0};
    double twistMass = 0.0;             // kg·m²
    double shockTwistMass = 0.0;
    double twistImpulse = 0.0;
    double twistRadius = 0.0;           // m: mean distance of the points from the centroid
    double friction = 0.5;              // μ this step: static if it was sticking, else kinetic
  };

  void prepare(const std::vector<BodyContact>& contacts, const std::vector<PairMaterial>& materials,
               const std::vector<SolverBody>& bodies, const std::vector<int32_t>& serials,
               const std::vector<SolvedManifold>& previous, const ContactSolverSettings& settings,
               double dt, const std::vector<int>& levels);
  void warmStart(std::vector<SolverBody>& bodies) const;
  // One Gauss–Seidel sweep over all contacts; a shock sweep holds the lower
  // body of each contact still.
  void solveVelocities(std::vector<SolverBody>& bodies, bool shock);
  void solvePositions(std::vector<SolverBody>& bodies, const ContactSolverSettings& settings,
                      double dt);

  std::vector<ManifoldConstraint> m_constraints;
};

}  // namespace rbsim
