#pragma once
// World-wide simulation settings.

#include <string>
#include <string_view>
#include <optional>
#include <vector>

#include "physics/body/body_def.h"
#include "physics/math/types.h"

namespace rbsim {

enum class IntegratorKind {
  ExplicitEuler,      // the seed's: every state term advanced with the derivative at the step start
  SemiImplicitEuler,  // momenta first, then position and orientation with the new velocities
  Rk4,                // classical 4th-order Runge–Kutta, forces re-evaluated at every stage
};

std::string_view integratorName(IntegratorKind kind);                   // "explicit_euler", ...
std::optional<IntegratorKind> integratorFromName(std::string_view name);  // inverse of integratorName

struct WorldSettings {
  double dt = 0.001;                       // s, fixed step
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);    // m/s²
  IntegratorKind integrator = IntegratorKind::SemiImplicitEuler;
  double linearDamping = 0.0;              // 1/s, default for bodies that set none
  double angularDamping = 0.0;             // 1/s, default for bodies that set none
};

// A whole world as loaded from a config file, before it is built.
struct WorldDef {
  WorldSettings settings;
  std::vector<BodyDef> bodies;
};

}  // namespace rbsim
