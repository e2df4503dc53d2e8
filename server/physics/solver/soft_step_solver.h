#pragma once
// The soft-step contact solver: sub-steps with soft contact constraints and
// a relax pass, after E. Catto, "Solver2D" (2024) and Box2D v3's solver.
//
// The step of length dt is cut into n sub-steps of h = dt/n. Contacts are
// detected once, at the step's start; within the step each point keeps its
// anchors (fixed in world orientation) and its separation follows the
// bodies' motion to first order, s = s0 + n·(ΔxB − ΔxA) + (rB×n)·ΔθB −
// (rA×n)·ΔθA, so the sub-steps need no new collision pass. Each sub-step:
//   1. velocities gain a sub-step's share of the step's forces;
//   2. warm start: the impulses of the last sub-step are applied again
//      (they are what holds a resting body against one sub-step's gravity);
//   3. solve: one Gauss–Seidel sweep in which a penetrating point's impulse
//      is that of a soft constraint, a damped spring of frequency f and
//      damping ratio ζ made implicit over h (Catto's "soft step"):
//         ω = 2πf, a1 = 2ζ + hω, a2 = hω a1, a3 = 1/(1 + a2),
//         bias = max(ω/a1 · s, −v_push), mass scale a2 a3, impulse scale a3;
//      a point still apart (s > 0) may close its gap within h but no further
//      (speculative contact), rigidly;
//   4. positions: Δx += h v, Δθ += h ω;
//   5. relax: one sweep without the bias, rigid, which takes out the
//      velocity the position correction added, so that pushing a body out
//      adds no energy (the role split impulses play in the
//      sequential-impulse solver).
// The stiffness follows from the sub-step rather than from an iteration
// count: f = min(contact_hertz, 1/(8h)), so the correction is stable at any
// mass ratio, and twice as stiff against static bodies. Friction is the
// patch friction of the sequential-impulse solver (contact_solver.h): two
// tangential impulses and a torsional one at the manifold's centroid,
// bounded by μ times the manifold's normal impulse, solved before the normal
// rows in every sweep.
//
// Collisions are not this solver's: the world hands contacts that collide
// within the step, and islands with joints, to the sequential-impulse
// solver, which answers them at their time of impact with −e v_rel there.
// Here every point is resting or speculative, and none bounces.
//
// Sweeps go batch by batch (sweep_batches.h), so that every thread count
// gives the same bits.

#include <cstdint>
#include <vector>

#include "physics/collision/body_contact.h"
#include "physics/parallel/task_pool.h"
#include "physics/solver/contact_solver.h"
#include "physics/solver/lanes.h"
#include "physics/solver/material.h"
#include "physics/solver/sweep_batches.h"
#include "physics/solver/velocity_row.h"
#include "rbsim/physics/contact_settings.h"
#include "rbsim/physics/contacts.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

// The constants of a soft constraint made implicit over one sub-step.
struct Softness {
  double biasRate = 0.0;      // 1/s: bias velocity per metre of penetration
  double massScale = 1.0;     // share of the rigid impulse
  double impulseScale = 0.0;  // share of the accumulated impulse taken back
};
// Spring of `hertz` with `dampingRatio`, implicit over `h` (hertz 0: rigid).
Softness softness(double hertz, double dampingRatio, double h);

class SoftStepSolver {
 public:
  // Steps the bodies of `contacts` over dt in settings.substeps sub-steps.
  // `bodies` holds one SolverBody per world body (dense index); for every
  // moving body of a contact it must have the step's start velocities
  // (start*) and the velocities after the whole step's forces (linear/
  // angularVelocity). On return linear/angularVelocity are the velocities
  // at the step's end, and pseudoLinear/pseudoAngular are set so that
  // velocity + pseudo is the mean velocity over the step: integrating the
  // pose with it over dt gives the sub-steps' position (zero for a body no
  // impulse reached: it flew free, and the world's integrator moves it). `previous` is last
  // step's result, sorted as `contacts`; `result` gets this step's, its
  // impulses summed over the sub-steps (N·s over the step).
  void solve(const std::vector<BodyContact>& contacts, const std::vector<PairMaterial>& materials,
             std::vector<SolverBody>& bodies, const std::vector<int32_t>& serials,
             const std::vector<SolvedManifold>& previous, const ContactSolverSettings& settings,
             double dt, std::vector<SolvedManifold>& result, TaskPool& pool);

 private:
  struct Point {
    Vec3 armA = Vec3::Zero();       // rA×n, world, fixed over the step
    Vec3 armB = Vec3::Zero();       // rB×n
    Vec3 responseA = Vec3::Zero();  // IA⁻¹ (rA×n)
    Vec3 responseB = Vec3::Zero();  // IB⁻¹ (rB×n)
    double normalMass = 0.0;        // kg
    double baseSeparation = 0.0;    // m at the step's start (< 0: overlap)
    double impulse = 0.0;           // N·s, accumulated in the current sub-step
    double total = 0.0;             // N·s over the step
    double relativeNormalVelocity = 0.0;  // m/s at the step's start (reported)
    double depth = 0.0;             // m, as detected
    uint32_t featureId = 0;
  };
  struct Manifold {
    int bodyA = 0, bodyB = 0;
    double inverseMassA = 0.0, inverseMassB = 0.0;
    Vec3 normal = Vec3::UnitZ(), tangent1 = Vec3::UnitX(), tangent2 = Vec3::UnitY();
    int pointCount = 0;
    Point points[4];
    Softness soft;                 // of the penetrating points' solve
    VelocityRow tangentRows[2];    // along t1, t2 at the centroid
    VelocityRow twistRow;          // rotation about n
    double tangentMass[2] = {0.0, 0.0};
    double twistMass = 0.0;
    double tangentImpulse[2] = {0.0, 0.0};  // accumulated in the current sub-step
    double twistImpulse = 0.0;
    double tangentTotal[2] = {0.0, 0.0};    // over the step
    double twistTotal = 0.0;
    double twistRadius = 0.0;
    double friction = 0.5;
  };
  // Position change of a moving body since the step's start.
  struct Motion {
    Vec3 linear = Vec3::Zero();   // m
    Vec3 angular = Vec3::Zero();  // rad (rotation vector, first order)
    Vec3 forceLinear = Vec3::Zero();   // m/s gained from the forces per sub-step
    Vec3 forceAngular = Vec3::Zero();  // rad/s
  };

  void prepareOne(std::size_t m, const BodyContact& contact, const PairMaterial& material,
                  const std::vector<SolverBody>& bodies, const SolvedManifold* old,
                  const ContactSolverSettings& settings, const Softness& soft,
                  const Softness& staticSoft);
  static void shareUnmatchedLoad(Manifold& c, const SolvedManifold& old, const bool matched[4],
                                 double perSubstep, const PairMaterial& material,
                                 const ContactSolverSettings& settings);
  // The sweeps' form of up to kLanes manifolds of one batch (no moving body
  // shared), structure-of-arrays (lanes.h): the sweeps solve a group's
  // manifolds side by side with the same instructions. A batch that shares
  // bodies (the colouring's overflow) gets one manifold per group. Unused
  // lanes have no mass and no impulse, and their bodies are never written.
  struct PointLanes {
    LaneVec3 armA, armB, responseA, responseB;
    Lanes normalMass = Lanes::Zero(), baseSeparation = Lanes::Zero();
    Lanes impulse = Lanes::Zero(), total = Lanes::Zero();
  };
  struct Group {
    int count = 0;
    int manifold[kLanes] = {0, 0, 0, 0};  // index in m_manifolds
    int bodyA[kLanes] = {0, 0, 0, 0}, bodyB[kLanes] = {0, 0, 0, 0};
    bool movesA[kLanes] = {false, false, false, false}, movesB[kLanes] = {false, false, false, false};
    Lanes inverseMassA = Lanes::Zero(), inverseMassB = Lanes::Zero();
    LaneVec3 normal;
    PointLanes points[4];
    LaneVec3 tangent[2], tangentArmA[2], tangentArmB[2], tangentResponseA[2], tangentResponseB[2];
    LaneVec3 twistResponseA, twistResponseB;  // the twist row's arm is the normal
    Lanes tangentMass[2] = {Lanes::Zero(), Lanes::Zero()}, twistMass = Lanes::Zero();
    Lanes tangentImpulse[2] = {Lanes::Zero(), Lanes::Zero()}, twistImpulse = Lanes::Zero();
    Lanes tangentTotal[2] = {Lanes::Zero(), Lanes::Zero()}, twistTotal = Lanes::Zero();
    Lanes friction = Lanes::Zero(), twistRadius = Lanes::Zero();
    Lanes biasRate = Lanes::Zero(), massScale = Lanes::Ones(), impulseScale = Lanes::Zero();
  };
  // A group's bodies' velocities (and, for the solve, motions), one lane each.
  struct GroupVelocities {
    LaneVec3 vA, wA, vB, wB;
  };

  // Cuts the batches into groups and copies the prepared manifolds in.
  void packGroups();
  void storeLane(Group& g, int lane, const Manifold& c);
  // Copies the step's impulses back to the manifolds, for the results.
  void unpackGroups();
  // Calls solve(group) for every group, batch after batch, each batch's
  // groups shared among the pool's threads.
  template <class Solve>
  void sweepGroups(TaskPool& pool, Solve&& solve);
  GroupVelocities gather(const Group& g, const std::vector<SolverBody>& bodies) const;
  static void scatter(const Group& g, const GroupVelocities& v, std::vector<SolverBody>& bodies);
  void warmStartGroup(Group& g, std::vector<SolverBody>& bodies) const;
  // One sweep's work on a group: friction, then the normal points, soft
  // with the bias (useBias: the solve) or rigid without it (the relax,
  // which ends the sub-step and adds its impulses to the step's totals).
  void solveGroup(Group& g, std::vector<SolverBody>& bodies, bool useBias, double inverseH,
                  double maxPush) const;
  SolvedManifold resultOf(std::size_t m, const BodyContact& contact,
                          const std::vector<SolverBody>& bodies, const std::vector<int32_t>& serials,
                          const ContactSolverSettings& settings) const;

  std::vector<Manifold> m_manifolds;
  std::vector<Motion> m_motion;            // per world body (dense index)
  std::vector<int> m_moving;               // the moving bodies of the contacts, ascending
  std::vector<const SolvedManifold*> m_previousOf;
  SweepBatcher m_batcher;
  SweepBatches m_sweep;
  std::vector<ConstraintBodies> m_constraintBodies;
  std::vector<char> m_moves;
  std::vector<char> m_pushed;  // per world body: some contact's impulse reached it this step
  std::vector<Group> m_groups;
  std::vector<int> m_batchGroups;  // batch b: groups m_batchGroups[b] .. m_batchGroups[b + 1] − 1
};

}  // namespace rbsim
