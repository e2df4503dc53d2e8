#pragma once
// Impulse-based contact response for all contacts of one step: sequential
// impulses (projected Gauss–Seidel on the velocity constraints) with
// accumulated, clamped impulses and warm starting, as in Catto's "Iterative
// Dynamics with Temporal Coherence" (GDC 2005) and Box2D/Bullet. One contact's
// impulse is that of Baraff, "Rigid Body Simulation" (SIGGRAPH course notes).
//
//  - Normal: Baraff's impulse j = −(1+e) v_rel / (1/Ma + 1/Mb + n·(Ia⁻¹(ra×n))×ra
//    + n·(Ib⁻¹(rb×n))×rb), applied iteratively over all points at once:
//    each iteration adds Δj = −m_n (v_rel − v_target) and clamps the
//    accumulated j at 0 (contacts push, never pull). The target normal
//    velocity is −e v_rel⁻ for colliding contacts (touching and approaching
//    faster than the restitution threshold; the world hands them over at
//    their time of impact), 0 for resting ones, and −gap/dt for speculative
//    ones (a gap that must not close by more than it is).
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
//  - Chains of touching bodies (Newton's cradle, a ball dropped on a ball
//    resting on the ground): a simultaneous solve of their restitution
//    targets shares the impact among all of them, where real impacts pass
//    from body to body. When a colliding contact touches a body that has
//    another touching contact with restitution, the collisions are first
//    resolved pair by pair with the velocities of the moment (the
//    propagation model of Guendelman, Bridson and Fedkiw 2003, §5), and the
//    solve then holds what they left (see propagateCollisions).
//  - Stacks: the points of one manifold are solved together, as a block
//    (see NormalBlock below), so a face contact is pushed evenly instead of
//    corner after corner; and the last velocity sweep uses shock propagation
//    (Guendelman, Bridson and Fedkiw 2003; Erleben 2005): the lower body of
//    each contact is held still, so a tall stack's top cannot rock its base.
//    With corner-by-corner sweeps a 20-box tower rocked and its top drifted
//    8 mm; with the block it stands within a micrometre.
//  - Order: each sweep goes batch by batch (sweep_batches.h), a batch being
//    contacts that share no moving body, so that threads can share it; the
//    shock sweep goes level by level upwards, coloured within each level,
//    so that one sweep carries the weight from the ground to the top.
//    Within a batch the order does not matter, so every thread count gives
//    the same bits. (Coloured Gauss–Seidel, as Box2D v3 and PhysX solve; a
//    stack's contacts alternate between two colours, which converges as
//    fast as the bottom-up order for such chains: Young's consistently
//    ordered matrices.)

#include <cstdint>
#include <vector>

#include "physics/collision/body_contact.h"
#include "rbsim/physics/math_types.h"
#include "physics/parallel/task_pool.h"
#include "rbsim/physics/contact_settings.h"
#include "physics/solver/material.h"
#include "physics/solver/sweep_batches.h"
#include "physics/solver/velocity_row.h"
#include "rbsim/physics/contacts.h"

namespace rbsim {

// Velocities of one body as the solver sees them. Static bodies have zero
// inverse mass and inertia.
struct SolverBody {
  Vec3 linearVelocity = Vec3::Zero();     // m/s, world
  Vec3 angularVelocity = Vec3::Zero();    // rad/s, world
  // Velocities of the state the step starts from, before this step's forces
  // (for a colliding body: at its time of impact): what classifies a contact
  // as colliding, resting or separating.
  Vec3 startLinearVelocity = Vec3::Zero();   // m/s
  Vec3 startAngularVelocity = Vec3::Zero();  // rad/s
  Vec3 pseudoLinear = Vec3::Zero();       // m/s: split-impulse position correction
  Vec3 pseudoAngular = Vec3::Zero();      // rad/s
  Mat3 inverseInertia = Mat3::Zero();     // 1/(kg·m²), world
  double inverseMass = 0.0;               // 1/kg
  Vec3 position = Vec3::Zero();           // m: centre of mass when the impulses act
};

// Which bodies, pieces, normal and point count of a detected contact:
// everything of its solved manifold but the impulses.
SolvedManifold manifoldIdentity(const BodyContact& contact, int32_t serialA, int32_t serialB);

class ContactSolver {
 public:
  // `bodies` holds one SolverBody per world body (dense index). Solves the
  // velocity constraints (bodies[].linear/angularVelocity are updated) and
  // the split-impulse position constraints (bodies[].pseudo* are set).
  // `previous` is last step's result, sorted as `contacts`: matching points
  // (same bodies, pieces and feature id) start from their old impulses.
  // `levels` (per body: contacts away from a static body; empty: none) turns
  // on shock propagation in the last velocity sweep. `equalities` (may be
  // null: none) are projected after the warm start and after every sweep.
  // The work of each contact alone (its rows, masses and targets; its
  // result) is shared among the pool's threads, and so is each batch of a
  // sweep (sweep_batches.h: contacts that share no moving body). The
  // result is the same for every thread count.
  void solve(const std::vector<BodyContact>& contacts, const std::vector<PairMaterial>& materials,
             std::vector<SolverBody>& bodies, const std::vector<int32_t>& serials,
             const std::vector<SolvedManifold>& previous, const ContactSolverSettings& settings,
             double dt, std::vector<SolvedManifold>& result, TaskPool& pool,
             const std::vector<int>& levels = {}, const class VelocityProjection* equalities = nullptr);

 private:
  // The normal impulses of a manifold's points are solved as one block, in
  // reduced coordinates. With c the centroid of the points and g_i =
  // (p_i − c)×n, the normal velocity at point i is exactly
  //     vn_i = a_i·u,   a_i = (1, g_i·e1, g_i·e2),
  // u = (normal velocity at c, relative rotation about e1, about e2), where
  // e1, e2 are the principal axes of Σ g_i g_iᵀ in the tangent plane (the
  // tilt axes; one or none for points on a line or a single point). The
  // manifold's reduced impulse is λ = Σ x_i a_i and u changes by K Δλ, K
  // the 3×3 (or smaller) effective inverse mass. Each sweep first tries the
  // exact solution of the whole manifold: Δλ = K⁻¹(u_goal − u), spread over
  // the points as the affine (least-norm) pressure x_i = λ0/n + Σ w_ik λk/σk,
  // accepted if every x_i >= 0; otherwise (a corner lifting, a box tipping)
  // projected Gauss–Seidel over the points, still in the reduced space.
  // Solving a face contact's points one after the other instead leaves a
  // rocking torque that a tall stack turns into sideways drift.
  struct PointConstraint {
    Vec3 direction = Vec3::UnitX();  // a_i = (1, w_i1, w_i2), w_ik = g_i·e_k in m (0 along a dropped axis)
    Vec3 pressure = Vec3::Zero();    // x_i = pressure·λ: the point's affine share (1/n, w_i1/σ1, w_i2/σ2)
    double normalMass = 0.0;         // kg: 1 / (a_iᵀ K a_i); 0: neither body can move along it
    double shockNormalMass = 0.0;    // kg: the same with the lower body held still
    double normalImpulse = 0.0;      // N·s, accumulated
    double collisionImpulse = 0.0;   // N·s the propagation pass gave it: spent, the sweeps add to it
    double targetVelocity = 0.0;     // m/s: v_n the normal impulse aims for
    double pseudoImpulse = 0.0;      // N·s of the split-impulse solve
    double positionTarget = 0.0;     // m/s: pseudo-velocity that removes the penetration
    double depth = 0.0;              // m
    double relativeNormalVelocity = 0.0;  // m/s at the step's start, or as a chain collision met it (classification, warm start)
    uint32_t featureId = 0;
  };
  // Which body of a contact the shock sweep holds still (the lower one).
  // Not to be confused with the numerical guard's frozen bodies, which are
  // out of the simulation altogether (rbsim/physics/freeze_reason.h).
  enum class ShockHold { None, A, B };
  // Which rows of the shock sweep feel body A and body B.
  static bool movesA(ShockHold hold) { return hold != ShockHold::A; }
  static bool movesB(ShockHold hold) { return hold != ShockHold::B; }
  struct NormalBlock {
    int size = 1;                         // 1 + number of tilt axes
    double tiltMoment[2] = {0.0, 0.0};    // m²: σ_k = Σ w_ik²
    Mat3 coupling = Mat3::Zero();         // K (size × size used)
    Mat3 inverse = Mat3::Zero();          // K⁻¹, zero outside size × size
    Mat3 shockCoupling = Mat3::Zero();    // with the lower body held still
    Mat3 shockInverse = Mat3::Zero();
    // Try the block solution: K invertible, and
    // targets that one motion meets at every point (a_i·u_goal = t_i). Then a
    // feasible block solution (x >= 0, every vn_i on target) is the solution
    // of the manifold's complementarity problem. Mixed targets (a gap that
    // may close beside a penetration, a bounce beside a rest) go to
    // Gauss–Seidel.
    bool velocityExact = false;
    bool shockExact = false;
    bool positionExact = false;
    Vec3 velocityGoal = Vec3::Zero();  // least-squares reduced targets of the velocity solve
    Vec3 positionGoal = Vec3::Zero();  // and of the split-impulse solve
  };
  struct ManifoldConstraint {
    int bodyA = 0, bodyB = 0;
    double inverseMassA = 0.0, inverseMassB = 0.0;
    ShockHold held = ShockHold::None;  // the lower body, held still by the shock sweep
    Vec3 normal, tangent1, tangent2;
    int pointCount = 0;
    PointConstraint points[4];
    VelocityRow normalRow;      // along n at the centroid
    VelocityRow tiltRows[2];    // rotation about e1, e2
    VelocityRow tangentRows[2]; // along t1, t2 at the centroid: the friction patch
    VelocityRow twistRow;       // rotation about n: torsional friction
    NormalBlock block;
    double tangentMass[2] = {0.0, 0.0};
    double shockTangentMass[2] = {0.0, 0.0};
    double tangentImpulse[2] = {0.0, 0.0};
    double twistMass = 0.0;             // kg·m²
    double shockTwistMass = 0.0;
    double twistImpulse = 0.0;
    double twistRadius = 0.0;           // m: mean distance of the points from the centroid
    double friction = 0.5;              // μ this step: static if it was sticking, else kinetic
    double restitution = 0.0;           // e of the pair
    double gap = 0.0;                   // m: the smallest gap among the points (< 0: overlap)
    bool propagated = false;            // the propagation pass gave it an impulse this step
    bool blockInvertible = false;       // K could be inverted
    bool shockBlockInvertible = false;  // K with the held body still could be inverted
  };
  // The impulses a shock sweep must not keep (see solve()).
  struct AccumulatedImpulses {
    double normal[4];
    double tangent[2];
    double twist;
  };

  void prepare(const std::vector<BodyContact>& contacts, const std::vector<PairMaterial>& materials,
               const std::vector<SolverBody>& bodies, const std::vector<int32_t>& serials,
               const std::vector<SolvedManifold>& previous, const ContactSolverSettings& settings,
               double dt, const std::vector<int>& levels, TaskPool& pool);
  void prepareOne(std::size_t m, const BodyContact& contact, const PairMaterial& material,
                  const std::vector<SolverBody>& bodies, const SolvedManifold* old,
                  const ContactSolverSettings& settings, double dt, const std::vector<int>& levels);
  // The solved manifold of constraint m, as the world keeps it.
  SolvedManifold resultOf(std::size_t m, const BodyContact& contact, const std::vector<SolverBody>& bodies,
                          const std::vector<int32_t>& serials, const ContactSolverSettings& settings) const;
  // prepare()'s steps for one manifold, in this order (each says why below).
  struct BlockInverses {
    bool regular = false;  // K could be inverted
    bool shock = false;    // K with the held body still could be inverted
  };
  static ShockHold chooseShockHold(ManifoldConstraint& c, const SolverBody& a, const SolverBody& b,
                                   const std::vector<int>& levels);
  static Vec3 setPatchRows(ManifoldConstraint& c, const ContactManifold& manifold,
                           const SolverBody& a, const SolverBody& b);
  static void setTiltAxes(ManifoldConstraint& c, const ContactManifold& manifold,
                          const Vec3& centroid, const SolverBody& a, const SolverBody& b);
  static BlockInverses setNormalBlockCoupling(ManifoldConstraint& c, const SolverBody& a,
                                              const SolverBody& b, ShockHold hold);
  static void setPointTargets(ManifoldConstraint& c, const ContactManifold& manifold,
                              const SolverBody& a, const SolverBody& b, double restitution,
                              const SolvedManifold* old, const ContactSolverSettings& settings,
                              double dt);
  static void setBlockGoals(ManifoldConstraint& c, const BlockInverses& inverses,
                            const ContactSolverSettings& settings, double dt);
  static void setFrictionPatch(ManifoldConstraint& c, const SolverBody& a, const SolverBody& b,
                               ShockHold hold, const PairMaterial& material,
                               const SolvedManifold* old, bool warmStarting);
  // The sweeps' batches: of the regular sweeps, and of the shock sweep
  // (level by level upwards, from `levels`; when `shock`).
  void batchSweeps(const std::vector<SolverBody>& bodies, const std::vector<int>& levels, bool shock);
  void warmStart(std::vector<SolverBody>& bodies, TaskPool& pool);
  void warmStartOne(const ManifoldConstraint& c, std::vector<SolverBody>& bodies) const;
  // The propagation pass (see the header's comment; a no-op unless a
  // colliding contact has a moving body with another contact that bounces):
  // sweeps over the contacts with restitution, giving each one that
  // approaches faster than the threshold and whose gap closes within the
  // step the impulse along its normal that makes it leave at −e v_rel,
  // v_rel as it is then (with the equalities projected after each, and the
  // pair settled again, so that a jointed body's effective mass is the one
  // its joints give it). Its impulses are kept apart (collisionImpulse:
  // reported, and friction's budget, but not the sweeps' to take back); the
  // sweeps then treat every contact of the chain as resting on the
  // velocities the pass left. Runs before the warm start; a contact it
  // changed is not warm-started.
  void propagateCollisions(std::vector<SolverBody>& bodies, const ContactSolverSettings& settings,
                           double dt, const VelocityProjection* equalities);
  // One Gauss–Seidel sweep over all contacts; a shock sweep holds the lower
  // body of each contact still.
  void solveVelocities(std::vector<SolverBody>& bodies, bool shock, TaskPool& pool);
  static void solveVelocity(ManifoldConstraint& c, std::vector<SolverBody>& bodies, bool shock);
  void solvePositions(std::vector<SolverBody>& bodies, int iterations, TaskPool& pool);
  static void solvePosition(ManifoldConstraint& c, std::vector<SolverBody>& bodies);
  // The normal block of one manifold (see above): updates the points'
  // `impulse` towards their `target` velocities given the reduced velocity
  // u, and returns the reduced impulse Δλ to apply to the rows.
  static Vec3 solveNormalBlock(ManifoldConstraint& c, const Vec3& u, bool exact, bool shock,
                               double PointConstraint::*impulse, double PointConstraint::*target,
                               const Vec3& goal);

  std::vector<ManifoldConstraint> m_constraints;
  std::vector<AccumulatedImpulses> m_saved;  // scratch of the shock sweep
  std::vector<const SolvedManifold*> m_previousOf;  // scratch of prepare(): last step's manifold of each contact
  SweepBatcher m_batcher;
  SweepBatches m_sweep;       // the regular velocity sweeps, the warm start and the position sweeps
  SweepBatches m_shockSweep;  // the shock sweep
  std::vector<ConstraintBodies> m_constraintBodies;  // scratch of batchSweeps()
  std::vector<char> m_moves;
  std::vector<int> m_shockStage;
};

}  // namespace rbsim
