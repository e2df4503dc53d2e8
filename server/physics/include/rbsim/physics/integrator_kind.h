#pragma once
// Which integrator advances the bodies, and its name in world files.

#include <optional>
#include <string_view>

namespace rbsim {

enum class IntegratorKind {
  ExplicitEuler,      // Baraff's: every state term advanced with the derivative at the step start
  SemiImplicitEuler,  // momenta first, then position and orientation with the new velocities
  Rk4,                // classical 4th-order Runge–Kutta, forces re-evaluated at every stage
};

std::string_view integratorName(IntegratorKind kind);                   // "explicit_euler", ...
std::optional<IntegratorKind> integratorFromName(std::string_view name);  // inverse of integratorName

}  // namespace rbsim
