#include <algorithm>
#include <cmath>

#include "rbsim/physics/exact_text.h"
#include "rbsim/physics/mass_properties.h"

namespace rbsim {

namespace {

// Appended piece by piece: GCC 12 reports a false -Warray-bounds inside
// `const char* + std::string&&` here once it is inlined.
std::string momentsText(const Vec3& moments) {
  std::string text = "(";
  text += exactText(moments.x());
  text += ", ";
  text += exactText(moments.y());
  text += ", ";
  text += exactText(moments.z());
  text += ")";
  return text;
}

}  // namespace

std::optional<std::string> inertiaTensorProblem(const Mat3& inertia) {
  if (!inertia.allFinite()) return "the inertia tensor must be finite";
  const double largest = inertia.cwiseAbs().maxCoeff();
  const char* names[3][3] = {{"Ixx", "Ixy", "Ixz"}, {"Ixy", "Iyy", "Iyz"}, {"Ixz", "Iyz", "Izz"}};
  for (int row = 0; row < 3; ++row) {
    for (int col = row + 1; col < 3; ++col) {
      if (std::abs(inertia(row, col) - inertia(col, row)) > kInertiaTolerance * largest)
        return std::string("the inertia tensor must be symmetric: ") + names[row][col] + " is " +
               exactText(inertia(row, col)) + " above the diagonal and " +
               exactText(inertia(col, row)) + " below it";
    }
  }
  const PrincipalAxes axes = principalAxes(0.5 * (inertia + inertia.transpose()));
  const Vec3& moments = axes.moments;
  const double trace = moments.sum();
  // Below the tolerance a moment is zero to the eigensolver's rounding.
  if (!(moments.minCoeff() > kInertiaTolerance * std::abs(trace)))
    return "the inertia tensor must be positive definite: its principal moments are " +
           momentsText(moments) + " kg·m²";
  for (int i = 0; i < 3; ++i) {
    const double others = trace - moments[i];
    if (moments[i] > others + kInertiaTolerance * trace)
      return "no rigid body has these principal moments " + momentsText(moments) +
             " kg·m²: each must be at most the sum of the other two";
  }
  return std::nullopt;
}

}  // namespace rbsim
