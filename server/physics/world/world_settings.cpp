#include "rbsim/physics/world_settings.h"

namespace rbsim {

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
