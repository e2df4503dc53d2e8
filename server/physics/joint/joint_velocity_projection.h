#pragma once
// The joints' velocity rows inside the contact solve: after every contact
// sweep, the velocities of the jointed bodies are projected exactly onto
// J₀ v = 0 (J₀ the joints' rows at the step's start, K₀ = J₀ M₀⁻¹ J₀ᵀ
// factorised once). Alternating the contact sweeps with this exact
// projection is block Gauss–Seidel between the contact set and the joint
// set: the step's velocities satisfy both, and the position projection that
// follows (joint/joint_solver.h) only closes the drift's O(h²).

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
  std::vector<JointSolverRow> m_rows;
  std::vector<std::size_t> m_solverIndex;
  RowSystem m_system;
};

}  // namespace rbsim
