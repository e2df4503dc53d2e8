#include "physics/world/world_settings.h"

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

std::string_view contactModelName(ContactModel model) {
  return model == ContactModel::Penalty ? "penalty" : "impulse";
}

std::optional<ContactModel> contactModelFromName(std::string_view name) {
  if (name == "impulse") return ContactModel::Impulse;
  if (name == "penalty") return ContactModel::Penalty;
  return std::nullopt;
}

std::string_view penaltyLawName(PenaltyLaw law) {
  return law == PenaltyLaw::Unclamped ? "unclamped" : "clamped";
}

std::optional<PenaltyLaw> penaltyLawFromName(std::string_view name) {
  if (name == "clamped") return PenaltyLaw::Clamped;
  if (name == "unclamped") return PenaltyLaw::Unclamped;
  return std::nullopt;
}

}  // namespace rbsim
