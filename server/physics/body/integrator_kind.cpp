#include "rbsim/physics/integrator_kind.h"

namespace rbsim {

std::string_view integratorName(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::ExplicitEuler:
      return "explicit_euler";
    case IntegratorKind::SemiImplicitEuler:
      return "semi_implicit_euler";
    case IntegratorKind::Rk4:
      return "rk4";
  }
  return "unknown";
}

std::optional<IntegratorKind> integratorFromName(std::string_view name) {
  for (IntegratorKind kind :
       {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4})
    if (integratorName(kind) == name) return kind;
  return std::nullopt;
}

}  // namespace rbsim
