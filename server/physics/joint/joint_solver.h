#pragma once
// The position-level joint step (docs/joints_design.md): RATTLE in maximal
// coordinates (Andersen 1983; Leimkuhler and Reich, "Simulating Hamiltonian
// Dynamics", 2004, ch. 7), with every joint of the step solved together.
//
// The world gives each jointed body its momenta after the first half kick
// (and after the contact impulses, when it touches something). Then:
//  1. drift: x = x₀ + h P/m, q turned by h I₀⁻¹ L (the pose update of the
//     semi-implicit integrator, body/integrator.h);
//  2. SHAKE: constraint impulses along the rows of J at the step's start
//     change P and L until C(x) = C(x₀) at the drifted poses. Each
//     iteration solves J₀ M₀⁻¹ J₀ᵀ Δλ = −ΔC / h exactly (a block Cholesky
//     factorisation made once per step, joint/row_system.h), so a heavy tip on a long
//     chain costs no more iterations than a pendulum; the iteration is a
//     quasi-Newton one that converges in a few steps;
//  3. positions only: the contacts' split-impulse pseudo-velocities and any
//     error C(x₀) that came from outside (a state set by a client, a joint
//     created open) are removed by moving positions along the joints' rows,
//     without touching the momenta, so correcting an error adds no energy;
//  4. the world's second half kick, then projectVelocities: J(x₁) v = 0
//     exactly, so the velocities leave tangent to the joints.
// Projecting along the start's rows (not the current iterate's, as
// position-based dynamics does) is what makes it second order and
// symplectic: a frictionless pendulum keeps its energy, its period is
// right to O(h²).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <array>
#include <vector>

#include "physics/joint/joint_constraint.h"
#include "physics/joint/row_system.h"
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

// A body the joint step moves.
struct JointBody {
  // At the step's start.
  Vec3 startPosition = Vec3::Zero();
  Quaternion startOrientation = Quaternion::identity();
  Mat3 startInverseInertia = Mat3::Zero();  // world, 1/(kg·m²)
  double inverseMass = 0.0;                 // 1/kg
  // The momenta at the step's start, before its first half kick: the rates
  // joint damping's first half acts on (RATTLE's islands; unused in
  // contact).
  Vec3 startLinearMomentum = Vec3::Zero();   // kg·m/s
  Vec3 startAngularMomentum = Vec3::Zero();  // kg·m²/s
  // Solved for.
  Vec3 linearMomentum = Vec3::Zero();   // kg·m/s
  Vec3 angularMomentum = Vec3::Zero();  // kg·m²/s
  // Split-impulse pseudo-velocities from the contact solver (positions only).
  Vec3 pseudoLinear = Vec3::Zero();   // m/s
  Vec3 pseudoAngular = Vec3::Zero();  // rad/s
  // The result of solvePositions.
  Vec3 position = Vec3::Zero();
  Quaternion orientation = Quaternion::identity();
};

// One joint of the step: its constraint and its sides, each a JointBody
// (index) or a fixed pose (-1: the world or a static body).
//
// Or a mimic coupling (`leader` set): `joint` is the follower and A, B its
// sides, C and D the leader's. Its one row holds
//   C = errorFrom + Δq_follower − multiplier · Δq_leader = 0,
// Δq each joint's coordinate change since `followerFrom`, `leaderFrom` (the
// coordinates at the world step's start, where the coupling's error was
// `errorFrom`): counting changes rather than coordinates keeps a gear of
// continuous joints exact past the ±2π where a revolute's coordinate wraps.
// Its Jacobian is the follower's axis row less `multiplier` times the
// leader's.
struct JointLink {
  const JointConstraint* joint = nullptr;
  int bodyA = -1;
  int bodyB = -1;
  JointSidePose fixedA;
  JointSidePose fixedB;

  const JointConstraint* leader = nullptr;
  int bodyC = -1;
  int bodyD = -1;
  JointSidePose fixedC;
  JointSidePose fixedD;
  double followerFrom = 0.0, leaderFrom = 0.0, errorFrom = 0.0;  // rad or m
  // In an island that touches something: its group's factors are made
  // exact every step (JointSolverSettings::keepRatio).
  bool inContact = false;
  // An island in contact (the contact path's semi-implicit step): the
  // axis's laws act over the whole step before the contact solve
  // (JointSolver::actuateBeforeContacts), so that the contacts answer them,
  // and neither before the drift nor after it.
  bool wholeKick = false;

  bool isCoupling() const { return leader != nullptr; }
};

// The poses of a link's sides (A, B, and a coupling's C, D).
using LinkPoses = std::array<JointSidePose, 4>;

// A link's rows: a joint's rowCount(), a coupling's one.
int linkRowCount(const JointLink& link);
// Its errors C(x) at the poses (linkRowCount values); `basis` as the
// joint's (a coupling ignores it).
void linkErrors(const JointLink& link, const LinkPoses& poses, const JointConstraint::Basis& basis, double* out);
// Its rows of J at the poses, appended to `out` as rows of link `index`
// with the link's sides (a coupling's sides merged where two are one body).
void appendLinkRows(const JointLink& link, int index, const LinkPoses& poses, const JointConstraint::Basis& basis,
                    std::vector<JointSolverRow>& out);
// A coupling's error: errorFrom + Δq_follower − multiplier · Δq_leader.
double couplingError(const JointLink& link, const LinkPoses& poses);

struct JointSolverSettings {
  double tolerance = 1e-12;  // m and rad: largest |C| left
  int maxIterations = 30;
  // A group whose joint graph is unchanged keeps the factor of K from an
  // earlier step (K is only the quasi-Newton matrix: the iterations stop on
  // C itself) for as long as every iteration with it leaves at most this
  // fraction of the error (or of the rates, in the velocity projection);
  // the first that leaves more makes K afresh and goes on with it. Adaptive,
  // never a fixed lag: a slowly moving grid keeps one factor for many steps,
  // a whipped chain refactors at once. 0: a factor is kept only when its
  // inputs are bit-identical. Not for a group in contact (the contact
  // sweeps' projection needs its K₀ exact) or with an axis that acts (its
  // laws need the joints' reply exact).
  double keepRatio = 0.1;
};

// What the step did, per link: the impulses on side B (for JointState) and
// the error left.
struct JointLinkResult {
  Vec3 linearImpulse = Vec3::Zero();   // N·s, on B
  Vec3 angularImpulse = Vec3::Zero();  // N·m·s, on B about its anchor
  double error = 0.0;                  // largest |C| at the end poses
  double axisImpulse = 0.0;            // the motor's or drive's, along the axis (N·s or N·m·s); a coupling's along the follower's
  int atLimit = 0;                     // -1, +1: held at the lower or upper limit
  double couplingError = 0.0;          // a coupling's signed error at the end poses
};

class JointSolver;

// The step of one group of joints (bodies joined to each other, directly
// or through others): JointSolver below gives it each group.
class JointGroupSolver {
 public:
  // Steps 1–3: the bodies' end poses (position, orientation) and the
  // momenta with the constraint impulses of the step. False when the
  // momentum projection did not close the joints to the tolerance (the
  // step is then too long for it: the caller sub-steps).
  bool solvePositions(const std::vector<JointLink>& links, std::vector<JointBody>& bodies, double h,
                      const JointSolverSettings& settings, std::vector<JointLinkResult>& results);
  // Step 4: with the bodies at their end poses (`inverseInertia` there, one
  // per body) and their momenta after the second half kick, removes every
  // velocity along the joints' rows, and into a limit that `results` (of
  // solvePositions) says is held; then the second half of the motors',
  // drives', damping's and friction's impulses over the step h.
  void projectVelocities(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                         const std::vector<Mat3>& inverseInertia, double h, std::vector<JointLinkResult>& results);
  // The contact path's actuation: for the links with wholeKick, the
  // motors', drives', damping's and friction's impulses over the whole
  // step h at the start poses (the drive's spring where the drift will
  // take it), with the joints' rows kept, into the momenta, before the
  // contact solve sees them. `results` gets them (B's couple about its
  // anchor).
  // `kept` (may be null): a solver whose factors may already be K₀'s.
  void actuateBeforeContacts(const std::vector<JointLink>& links, std::vector<JointBody>& bodies, double h,
                             std::vector<JointLinkResult>& results, const JointSolver* kept = nullptr);

  // The factor the group's last step left: K at the end poses of its
  // velocity projection (the joints' rows only), which is the next step's
  // K₀ when that starts where this one ended.
  const RowSystem& system() const { return m_system; }
  RowSystem& system() { return m_system; }

 private:
  using Row = JointSolverRow;
  // Where a projection drifts the bodies from, with which velocities, and
  // the impulses it has added (per body, along the start's rows): the
  // velocity drifted with is velocity + M₀⁻¹ impulse.
  struct Drift {
    std::vector<Vec3> fromPosition;
    std::vector<Quaternion> fromOrientation;
    std::vector<Vec3> linearVelocity, angularVelocity;
    std::vector<Vec3> linearImpulse, angularImpulse;
    // The bodies' angular momenta (world), when the drift turns each body
    // as a free rigid body does: L fixed, ω = I(t)⁻¹ L taken at mid-drift
    // (second order for a body tumbling with unequal moments). Empty: ω
    // fixed over the drift (the position corrections' pseudo-velocities).
    std::vector<Vec3> angularMomentum;
  };
  // Empties a drift, its storage kept.
  static void clearDrift(Drift& drift);
  // Impulses along the start's rows until the drifted poses have the
  // errors `targets` (null: none); into `total`, per row.
  // The largest error left is in `largest`.
  void project(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
               const std::vector<JointConstraint::Basis>& bases, const std::vector<double>* targets, Drift& drift,
               double h, const JointSolverSettings& settings, double& largest, Eigen::VectorXd& total);

  // The impulses along the joints' axes (before the drift): motors,
  // drives, damping and friction, with the joints' rows kept.
  // Half of the step's impulses, at the start's poses before the drift or
  // at the end's after the second half kick (atEnd), with the inverse
  // inertias there.
  // With beforeContacts, the wholeKick links' whole step instead (the
  // others' are left alone).
  void actuateAxes(const std::vector<JointLink>& links, std::vector<JointBody>& bodies, double h,
                   const std::vector<Mat3>& inverseInertia, bool atEnd, std::vector<JointLinkResult>& results,
                   bool beforeContacts = false);
  // The second half at the end, into `results` (B's couple about its anchor).
  void actuateAxesAtEnd(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                        const std::vector<Mat3>& inverseInertia, double h, std::vector<JointLinkResult>& results);
  // K of the joints' rows of m_rows at the start poses, factorised (or
  // kept, bit-identical), and the border of the limits' rows after them.
  void factorAtStart(const std::vector<JointBody>& bodies);
  // The border alone, at the start poses, when the limits' rows changed.
  void borderAtStart(const std::vector<JointBody>& bodies);
  // The bodies' start inverse inertias, in the workspace.
  std::vector<Mat3>& startInverseInertias(const std::vector<JointBody>& bodies);
  // Whether m_system may stay a factor of an earlier step's K for the rows
  // now in m_rows (their pattern the same): keepRatio, no contact, no axis.
  bool mayKeep(const std::vector<JointLink>& links, const JointSolverSettings& settings) const;
  // Removes the rates along m_rows from the momenta (with K as m_system
  // and the border hold it).
  void removeJointRates(std::vector<JointBody>& bodies, const std::vector<Mat3>& inverseInertia) const;

  // Limit rows after the rows m_system holds (m_rows past m_system.size(),
  // the joints' m_jointRows): SHAKE's held limits at the start poses, the
  // velocity projection's at the end poses. m_system keeps the joints' rows
  // alone (the factor the next step starts with, and a change of the
  // limits' active set makes none), and these are solved through the Schur
  // complement on them,
  //   S = K_LL − K_LJ K_JJ⁻¹ K_JL,
  // one solve with K_JJ per limit row, no factorisation.
  //
  // Its numbers are kept by the count of limit rows: each Eigen object then
  // keeps its size from step to step (the count changes as limits engage
  // and let go), so it neither allocates nor lays its numbers out anew.
  // (in the workspace, shared by the groups)
  struct BorderNumbers {
    Eigen::MatrixXd coupling;  // K_JL
    Eigen::MatrixXd response;  // K_JJ⁻¹ K_JL
    Eigen::MatrixXd schurMatrix;  // S, before it is factorised
    Eigen::LLT<Eigen::MatrixXd> schur;
    Eigen::VectorXd column;  // makeBorder's
    mutable Eigen::VectorXd jointPart, limitPart;  // solveRows'
    bool reserved = false;  // sized ahead (Workspace::reserve)
  };
  struct Border {
    bool ok = true;
  };
  // The border of m_rows past m_system.size() for bodies of these inverse
  // inertias; false when K is not positive definite on the rows.
  bool makeBorder(const std::vector<JointBody>& bodies, const std::vector<Mat3>& inverseInertia);
  // K⁻¹ x over m_rows, with m_system and the border.
  void solveRows(Eigen::VectorXd& x) const;
  // Whether solveRows can solve: m_system's factor (if it has rows) and the
  // border's.
  bool systemOk() const {
    return (m_system.size() == 0 || m_system.ok()) && m_border.ok && !m_rows.empty();
  }

  // A limit held this step: its row follows the joints' rows in m_rows.
  struct LimitRow {
    int link = 0;
    double bound = 0.0;  // rad or m
    int side = 0;        // -1 lower, +1 upper
  };
  // How far a limit is held beyond its bound this step (0, or the excess a
  // joint started with: the momentum projection holds it there).
  double heldBeyond(const LimitRow& limit) const {
    const double beyond = m_startBeyond[static_cast<std::size_t>(limit.link)];
    return beyond * limit.side > 0.0 ? beyond : 0.0;
  }
  // The most a joint that started beyond a limit is brought back in a step:
  // a few steps for the published descriptions' zero poses (a leg's calf
  // 0.9 rad beyond), little enough for what its links touch to follow.
  static double limitReturn(const JointConstraint& joint) {
    return joint.def.type == JointType::Revolute || joint.def.type == JointType::Spherical ? 0.1 : 0.01;  // rad, m
  }
  std::vector<Row> m_rows;
  std::size_t m_jointRows = 0;  // the joints' rows at the front of m_rows; limits' rows follow
  std::vector<LimitRow> m_limits;
  std::vector<double> m_startBeyond;  // by link: the coordinate's excess over a bound at the start, signed
  RowSystem m_system;  // K₀ = J₀ M₀⁻¹ J₀ᵀ of the step; K₁ after the velocity projection
  // Whether m_system is K of m_rows now (else an earlier step's, kept while
  // it converges: JointSolverSettings::keepRatio).
  bool m_systemExact = true;
  double m_keepRatio = 0.0;  // the settings' of the step (for projectVelocities)
  // Of the step's projections: how many solves the last one made, and
  // whether one found the kept factor too slow and made K₀.
  int m_projectIterations = 0;
  bool m_refreshed = false;
  // Whether the velocity projection keeps m_system rather than making K₁:
  // for a group that may keep a factor, when this step's momentum
  // projection ran on a kept factor without making K₀, or on an exact K₀
  // in one iteration (the group moves slowly enough that an earlier K
  // serves). A group whose K₀ needs several iterations (a whipped chain)
  // makes K₁ at every end, as if it might not keep one.
  bool m_keepAtEnd = false;
  Border m_border;

 public:
  // The step's scratch, kept from step to step so that a steady step
  // allocates nothing (issue 39): cleared or resized, never freed. Nothing
  // in it carries over from one call to the next, so the groups of a
  // JointSolver, solved one after another, share one (and its lists grow
  // to the largest group's, not to each group's).
  struct Workspace {
    // By the rows' count and then the limit rows': the count of joint rows
    // (a group's) and of limit rows together fix every size in it, so
    // groups of different sizes sharing the workspace do not resize one
    // another's.
    std::vector<std::vector<BorderNumbers>> bordersBySize;
    std::vector<JointConstraint::Basis> bases;  // by link, at the start poses
    std::vector<double> targets, allTargets, positionTargets;
    std::vector<Mat3> startInverseInertia;
    std::vector<double> inverseMass;
    std::vector<Vec3> kickedLinear, kickedAngular;
    Drift momenta, pseudo;
    std::vector<LimitRow> keptLimits;
    std::vector<Vec3> fromPosition;
    std::vector<Quaternion> fromOrientation;
    std::vector<Row> limitRows;  // set aside while K of the joints' rows is made
    std::vector<int> endLimits;
    // Eigen vectors by their size (joint_solver.cpp's sizedVector).
    std::vector<Eigen::VectorXd> totalBySize, pseudoTotalBySize;
    std::vector<double> totalRows;
    // project's
    std::vector<Eigen::VectorXd> residualBySize, impulseBySize;
    std::vector<Mat3> rotation, turns;
    std::vector<JointSolverRow> currentRows;
    // projectVelocities'
    std::vector<Eigen::VectorXd> rateBySize, stepBySize, rateImpulseBySize;
    std::vector<Vec3> linear, angular;  // rowRates'
    // Sizes every number a group of `jointRows` joint rows and up to
    // `limits` limit rows (at most kReserved) will use, so that a step
    // holding more limits than any before allocates nothing.
    static constexpr std::size_t kReserved = 32;
    void reserve(std::size_t jointRows, std::size_t limits);
    BorderNumbers& border(std::size_t rows, std::size_t limits) {
      if (bordersBySize.size() <= rows) bordersBySize.resize(rows + 1);
      std::vector<BorderNumbers>& byLimits = bordersBySize[rows];
      if (byLimits.size() <= limits) byLimits.resize(limits + 1);
      return byLimits[limits];
    }
  };
  // The workspace the next calls use (null: the solver's own). JointSolver
  // sets its shared one before each call (a copied solver's would be the
  // original's).
  void useWorkspace(Workspace* work) { m_shared = work; }

 private:
  Workspace& work() const { return m_shared != nullptr ? *m_shared : m_own; }
  Workspace* m_shared = nullptr;
  mutable Workspace m_own;
};

// Bodies joined to each other by links, directly or through others, and
// those links: indices into a step's bodies and links.
struct JointGroup {
  std::vector<int> bodies;
  std::vector<int> links;
};
// The groups of a step's bodies and the links between them, in the order
// of their first body (a body no link joins is a group of its own), made
// again at every step into the same storage: a steady step allocates
// nothing (the groups' lists are cleared, not freed).
class JointGrouping {
 public:
  void make(const std::vector<JointLink>& links, std::size_t bodyCount);
  std::size_t size() const { return m_count; }
  const JointGroup& operator[](std::size_t g) const { return m_groups[g]; }
  // Each body's index in its group.
  const std::vector<int>& localIndex() const { return m_localIndex; }

 private:
  std::vector<JointGroup> m_groups;  // the first m_count are this step's; the rest keep their storage
  std::size_t m_count = 0;
  std::vector<int> m_localIndex;
  std::vector<int> m_parent, m_groupOfRoot;  // union–find
};
// The link with its sides numbered as in their group.
JointLink inGroup(JointLink link, const std::vector<int>& localIndex);

// The joint step of a world's joints: each group of joints joined through
// their bodies (a ragdoll, a chain, a door) is solved alone, with its own
// system and its own limits' active set: K is block diagonal over the
// groups, so this is the same step, but a limit that engages in one
// ragdoll re-solves that ragdoll, not all of them, and each group's
// iteration stops when its own joints are closed. Groups are numbered by
// their first body, so a group keeps its solver (and its system's
// analysis) from step to step while the joints stay.
class JointSolver {
 public:
  // As JointGroupSolver's, for every group; true when every group closed.
  bool solvePositions(const std::vector<JointLink>& links, std::vector<JointBody>& bodies, double h,
                      const JointSolverSettings& settings, std::vector<JointLinkResult>& results);
  // As JointGroupSolver's; the links and bodies of the last solvePositions.
  void projectVelocities(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                         const std::vector<Mat3>& inverseInertia, double h, std::vector<JointLinkResult>& results);
  // As JointGroupSolver's, for every group (with solvers of their own, so
  // that the step's keep their systems' analysis).
  void actuateBeforeContacts(const std::vector<JointLink>& links, std::vector<JointBody>& bodies, double h,
                             std::vector<JointLinkResult>& results);
  // A factor one of the groups' solvers holds (system()) made from exactly
  // these inputs, or null: the contact sweeps' projection of a group in
  // contact finds its K₀ here, made at the end of the last step. With
  // `orSamePattern`, else one made for rows of the same joints and bodies:
  // a copy of it factorises these rows keeping its elimination order and
  // symbolic analysis (RowSystem::factor), the same bits as a fresh one.
  const RowSystem* keptFactor(const std::vector<JointSolverRow>& rows, const std::vector<double>& inverseMass,
                              const std::vector<Mat3>& inverseInertia, bool orSamePattern = false) const;

  // The inputs of each group's factor (RowSystem::Inputs), by group: a
  // factor kept across steps (JointSolverSettings::keepRatio) is part of the
  // state the next steps depend on, so a checkpoint holds them, and
  // restoreFactors makes the same factors from them (world/snapshot.cpp).
  std::vector<RowSystem::Inputs> factorInputs() const;
  void restoreFactors(const std::vector<RowSystem::Inputs>& inputs);

 private:
  // The groups' solvers' shared workspace (they are solved one after another).
  JointGroupSolver::Workspace m_workspace;
  std::vector<JointGroupSolver> m_kickSolvers;  // by group, for actuateBeforeContacts
  JointGrouping m_kickGroups;
  JointGrouping m_groups;
  std::vector<JointGroupSolver> m_solvers;  // by group
  // A group's links, bodies and results in its own numbering.
  std::vector<JointLink> m_groupLinks;
  std::vector<JointBody> m_groupBodies;
  std::vector<Mat3> m_groupInertia;
  std::vector<JointLinkResult> m_groupResults;
};

// The bodies' inverse masses, for RowSystem::factor; into `out` (its
// storage kept), which it returns.
std::vector<double> inverseMasses(const std::vector<JointBody>& bodies);
std::vector<double>& inverseMasses(const std::vector<JointBody>& bodies, std::vector<double>& out);

// The side poses of a link from the bodies' current poses (or start poses).
JointSidePose sidePose(const JointLink& link, const std::vector<JointBody>& bodies, bool sideB,
                       bool atStart);
// All of a link's side poses so (C and D only for a coupling).
LinkPoses linkPoses(const JointLink& link, const std::vector<JointBody>& bodies, bool atStart);

}  // namespace rbsim
