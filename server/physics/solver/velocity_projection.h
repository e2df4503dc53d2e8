#pragma once
// Equality constraints on velocities that the contact solver enforces
// between its sweeps (the joints: joint/joint_velocity_projection.h), so that
// the contact and joint impulses of one step are solved together: a chain
// lying on the floor is held by the floor and by its joints at once, not by
// one undoing the other.

#include <vector>

#include "physics/solver/contact_solver.h"

namespace rbsim {

class VelocityProjection {
 public:
  virtual ~VelocityProjection() = default;
  // Changes the bodies' velocities so that the constraints hold exactly.
  virtual void project(std::vector<SolverBody>& bodies) const = 0;
};

}  // namespace rbsim
