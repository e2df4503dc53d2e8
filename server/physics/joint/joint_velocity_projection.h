#pragma once
// The joints' velocity rows inside the contact solve: after every contact
// sweep, the velocities of the jointed bodies are projected exactly onto
// J₀ v = 0 (J₀ the joints' rows at the step's start, K₀ = J₀ M₀⁻¹ J₀ᵀ
// factorised once), and off the limits the joints sit at: a joint at a bound
// at the step's start (a knee straight, a foot at its ankle's stop) gets
// its limit row, which may only push. The limits are a small linear
// complementarity problem on their rows with the joints holding (A = the
// limit rows' response through K₀, made as the limits need it), solved
// exactly by pivoting; the joints' reply to the limits' pushes comes with
// A's columns (a column is the velocities a unit push leaves with the
// joints holding). Alternating the
// contact sweeps with this exact projection is block Gauss–Seidel between
// the contact set and the joint set: the step's velocities satisfy both,
// and the position projection that follows (joint/joint_solver.h) only
// closes the drift's O(h²).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "physics/joint/joint_solver.h"
#include "physics/solver/velocity_projection.h"

namespace rbsim {

// project's complementarity problem's numbers, by its size (n, the limits
// at a bound, and k, those pushing in a round), so that each Eigen object
// keeps its size, and so its storage and its numbers' layout, from step to
// step: no allocation, and the same bits as objects made afresh. Shared by
// the groups (projected one after another), so that it holds the sizes of
// the largest group, not of each.
struct JointLimitScratch {
  struct Lcp {
    Eigen::MatrixXd m;  // n × n
    Eigen::VectorXd q, s, mu, u;
  };
  struct PushingSet {
    Eigen::MatrixXd mPP;  // k × k
    Eigen::VectorXd qP, solved;
    Eigen::LDLT<Eigen::MatrixXd> ldlt;
  };
  std::vector<Lcp> lcpBySize;
  std::vector<PushingSet> pushingBySize;
  std::vector<char> pushing, haveM;
  std::vector<Eigen::Index> set;
  // Makes the numbers of every size up to n limits (at most kReserved: a
  // group with more limits allocates for each new size it meets), so that
  // a step with more limits at a bound than any before allocates nothing.
  static constexpr std::size_t kReserved = 32;
  void reserve(std::size_t n);
};

// The projection of one group of joints (joint_solver.h's JointGroup).
// Made again at every step into the storage of the last (the world keeps
// it: a steady step allocates nothing, issue 39).
class JointGroupProjection {
 public:
  // `links` name their sides by index into `bodies` (start poses, inverse
  // mass and inertia), and `solverIndex` maps those to the solver's bodies.
  // K₀ is taken from `kept` (may be null) when one of its factors was made
  // from exactly these rows and bodies (the joint step's of the last step,
  // ending where this one starts), else made here (with the elimination
  // order of one of its factors of the same joints, when it has one, or
  // of this projection's last, which it keeps).
  void make(const std::vector<JointLink>& links, const std::vector<JointBody>& bodies,
            const std::vector<std::size_t>& solverIndex, const JointSolver* kept = nullptr);
  void project(std::vector<SolverBody>& bodies, JointLimitScratch& scratch) const;
  // How many limits the group has (at most this many may be at a bound).
  std::size_t limitCapacity() const { return m_limitCapacity; }

 private:
  // A limit at its bound at the step's start: its row and which bound
  // (-1 lower, +1 upper).
  struct Limit {
    JointSolverRow row;
    int side = 0;
  };
  // A row's rate from the velocities of `bodies`, an impulse along a row,
  // and the removal of the rates along the joints' rows (K₀); `index` maps
  // the group's bodies to those of `bodies` (the solver's, or the scratch).
  double rate(const JointSolverRow& row, const std::vector<SolverBody>& bodies,
              const std::vector<std::size_t>& index) const;
  void push(const JointSolverRow& row, double lambda, std::vector<SolverBody>& bodies,
            const std::vector<std::size_t>& index) const;
  void projectJoints(std::vector<SolverBody>& bodies, const std::vector<std::size_t>& index) const;

  std::vector<JointSolverRow> m_rows;  // the joints' equality rows
  std::vector<Limit> m_limits;
  std::size_t m_limitCapacity = 0;
  std::vector<std::size_t> m_solverIndex;
  RowSystem m_system;                  // K₀ of the equality rows
  // Column j of A: the limit rows' rates per unit impulse along limit row
  // j, with the joints' rows holding; made when limit j first pushes (most
  // limits at a bound are never moved into), on a scratch copy of the
  // group's bodies. Its n numbers (n limits) are at m_limitResponse[n j].
  const double* responseColumn(std::size_t j) const;
  mutable std::vector<double> m_limitResponse;
  mutable std::vector<char> m_haveColumn;
  // With each column, the velocities a unit push along limit j leaves with
  // the joints holding (linear, angular per body of the group).
  mutable std::vector<std::vector<Vec3>> m_columnVelocities;
  mutable std::vector<SolverBody> m_scratch;  // by group body
  std::vector<std::size_t> m_scratchIndex;    // 0, 1, …: the scratch's own numbering
  // projectJoints' scratch: the rows' impulses, and their sums per body.
  mutable Eigen::VectorXd m_impulse;
  mutable std::vector<Vec3> m_linearImpulse, m_angularImpulse;
  // make's: the bodies' start inverse masses and inertias.
  std::vector<double> m_inverseMass;
  std::vector<Mat3> m_inverseInertia;
};

// Every group of joints in contact, each projected on its own (K₀ is block
// diagonal over the groups: the same projection, but a limit's response
// and the limits' complementarity problem are the size of one ragdoll, not
// of all of them).
// Kept by the world and made again at every step (make), into the storage
// of the last.
class JointVelocityProjection final : public VelocityProjection {
 public:
  // As JointGroupProjection's, for all the groups `links` make.
  void make(const std::vector<JointLink>& links, const std::vector<JointBody>& bodies,
            const std::vector<std::size_t>& solverIndex, const JointSolver* kept = nullptr);
  void project(std::vector<SolverBody>& bodies) const override;

 private:
  std::vector<JointGroupProjection> m_groups;  // the first m_count are this step's
  std::size_t m_count = 0;
  JointGrouping m_grouping;
  std::vector<JointLink> m_groupLinks;
  std::vector<JointBody> m_groupBodies;
  std::vector<std::size_t> m_groupIndex;
  mutable JointLimitScratch m_limitScratch;
};

}  // namespace rbsim
