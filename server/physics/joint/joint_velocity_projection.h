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

#include <cstddef>
#include <vector>

#include "physics/joint/joint_solver.h"
#include "physics/solver/velocity_projection.h"

namespace rbsim {

// The projection of one group of joints (joint_solver.h's JointGroup).
class JointGroupProjection {
 public:
  // `links` name their sides by index into `bodies` (start poses, inverse
  // mass and inertia), and `solverIndex` maps those to the solver's bodies.
  // K₀ is taken from `kept` (may be null) when one of its factors was made
  // from exactly these rows and bodies (the joint step's of the last step,
  // ending where this one starts), else made here (with the elimination
  // order of one of its factors of the same joints, when it has one).
  JointGroupProjection(const std::vector<JointLink>& links, const std::vector<JointBody>& bodies,
                       std::vector<std::size_t> solverIndex, const JointSolver* kept = nullptr);
  void project(std::vector<SolverBody>& bodies) const;

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
  std::vector<std::size_t> m_solverIndex;
  RowSystem m_system;                  // K₀ of the equality rows
  // Column j of A: the limit rows' rates per unit impulse along limit row
  // j, with the joints' rows holding; made when limit j first pushes (most
  // limits at a bound are never moved into), on a scratch copy of the
  // group's bodies.
  Eigen::VectorXd responseColumn(std::size_t j) const;
  mutable Eigen::MatrixXd m_limitResponse;
  mutable std::vector<char> m_haveColumn;
  // With each column, the velocities a unit push along limit j leaves with
  // the joints holding (linear, angular per body of the group).
  mutable std::vector<std::vector<Vec3>> m_columnVelocities;
  mutable std::vector<SolverBody> m_scratch;  // by group body
  std::vector<std::size_t> m_scratchIndex;    // 0, 1, …: the scratch's own numbering
  // projectJoints' scratch: the rows' impulses, and their sums per body.
  mutable Eigen::VectorXd m_impulse;
  mutable std::vector<Vec3> m_linearImpulse, m_angularImpulse;
};

// Every group of joints in contact, each projected on its own (K₀ is block
// diagonal over the groups: the same projection, but a limit's response
// and the limits' complementarity problem are the size of one ragdoll, not
// of all of them).
class JointVelocityProjection final : public VelocityProjection {
 public:
  // As JointGroupProjection's, for all the groups `links` make.
  JointVelocityProjection(const std::vector<JointLink>& links, const std::vector<JointBody>& bodies,
                          const std::vector<std::size_t>& solverIndex, const JointSolver* kept = nullptr);
  void project(std::vector<SolverBody>& bodies) const override;

 private:
  std::vector<JointGroupProjection> m_groups;
};

}  // namespace rbsim
