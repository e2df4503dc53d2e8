#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "rbsim/physics/mass_properties.h"

namespace rbsim {

PrincipalAxes principalAxes(const Mat3& inertia) {
  PrincipalAxes result;
  const double offDiagonal =
      std::max({std::abs(inertia(0, 1)), std::abs(inertia(0, 2)), std::abs(inertia(1, 2))});
  // Exact diagonal tensors (every primitive) keep their own axes: with two
  // equal moments any axis in that plane is principal, and the solver would
  // pick an arbitrary one.
  if (offDiagonal <= 1e-12 * std::abs(inertia.trace())) {
    result.moments = inertia.diagonal();
    return result;
  }
  // The solver reads only the lower triangle; symmetrise so that a slightly
  // asymmetric input (round-off) is treated evenly.
  const Mat3 symmetric = 0.5 * (inertia + inertia.transpose());
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(symmetric);
  result.moments = solver.eigenvalues();  // ascending
  result.axes = solver.eigenvectors();
  // Eigenvectors come with arbitrary signs; flipping one column turns a
  // reflection into a proper rotation without changing axes·diag·axesᵀ.
  if (result.axes.determinant() < 0.0) result.axes.col(2) = -result.axes.col(2);
  return result;
}

Mat3 shiftInertia(const Mat3& inertiaAboutCenter, double mass, const Vec3& offset) {
  return inertiaAboutCenter +
         mass * (offset.squaredNorm() * Mat3::Identity() - offset * offset.transpose());
}

}  // namespace rbsim
