#pragma once
// For tests only: mass properties of a closed mesh estimated by sampling.

#include "rbsim/physics/triangle_mesh.h"
#include "rbsim/physics/mass_properties.h"

namespace rbsim {

// Monte Carlo estimate by sampling points uniformly in the bounding box and
// testing them against the mesh: an independent cross-check of the exact
// integrals. Each field comes with its standard error.
struct MonteCarloMassProperties {
  MassProperties estimate;
  MassProperties standardError;  // one standard error of each field (inertia element-wise)
  int samples = 0;
  int insideSamples = 0;
};
MonteCarloMassProperties monteCarloMassProperties(const TriangleMesh& mesh, double density,
                                                  int samples, unsigned long long seed);

}  // namespace rbsim
