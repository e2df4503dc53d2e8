#pragma once
// The joints' velocity rows inside the contact solve: after every contact
// sweep, the velocities of the jointed bodies are projected exactly onto
// J₀ v = 0 (J₀ the joints' rows at the step's start, K₀ = J₀ M₀⁻¹ J₀ᵀ
// factorised), and off the limits the joints sit at: a joint at a bound
// at the step's start (a knee straight, a foot at its ankle's stop) gets
// its limit row, held only while it pushes (an active set: a row that would
// pull is dropped and the projection made again). Alternating the contact
// sweeps with this exact projection is block Gauss–Seidel between the
// contact set and the joint set: the step's velocities satisfy both, and
// the position projection that follows (joint/joint_solver.h) only closes
// the drift's O(h²).

#include <cstddef>
#include <vector>

#include "physics/joint/joint_solver.h"
#include "physics/solver/velocity_projection.h"

namespace rbsim {

class JointVelocityProjection final : public VelocityProjection {
 public:
  // `links` name their sides by index into `bodies` (start poses, inverse
  // mass and inertia), and `solverIndex` maps those to the solver's bodies.
  JointVelocityProjection(const std::vector<JointLink>& links, const std::vector<JointBody>& bodies,
                          std::vector<std::size_t> solverIndex);
  void project(std::vector<SolverBody>& bodies) const override;

 private:
  // A limit at its bound at the step's start: its row and which bound
  // (-1 lower, +1 upper).
  struct Limit {
    JointSolverRow row;
    int side = 0;
  };
  // The rows' rates from the solver's velocities, and impulses along them.
  double rate(const JointSolverRow& row, const std::vector<SolverBody>& bodies) const;
  void push(const JointSolverRow& row, double lambda, std::vector<SolverBody>& bodies) const;
  // Factors K for the equality rows and the limits marked active, unless
  // it is factored for them already.
  void factorFor(const std::vector<char>& active) const;

  std::vector<JointSolverRow> m_rows;  // the joints' equality rows
  std::vector<Limit> m_limits;
  std::vector<JointBody> m_bodies;     // for factorising with limits
  std::vector<Mat3> m_inverseInertia;
  std::vector<std::size_t> m_solverIndex;
  // The system of the last active set (the next sweep usually has the same).
  mutable RowSystem m_system;
  mutable std::vector<char> m_factoredActive;
  mutable bool m_factored = false;
};

}  // namespace rbsim
