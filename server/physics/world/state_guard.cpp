#include "physics/world/state_guard.h"

#include <cstdio>

namespace rbsim {

std::string_view freezeReasonName(FreezeReason reason) {
  switch (reason) {
    case FreezeReason::None:
      return "none";
    case FreezeReason::NonFiniteState:
      return "non-finite state";
    case FreezeReason::LinearSpeed:
      return "linear speed";
    case FreezeReason::AngularSpeed:
      return "angular speed";
    case FreezeReason::Requested:
      return "requested";
  }
  return "unknown";
}

std::string describeFreeze(const FreezeEvent& event) {
  std::string why;
  char numbers[96];
  switch (event.verdict.reason) {
    case FreezeReason::NonFiniteState:
      why = "its state became non-finite (NaN or infinity)";
      break;
    case FreezeReason::LinearSpeed:
      std::snprintf(numbers, sizeof numbers, "%.6g m/s is above limits.max_linear_speed (%.6g m/s)",
                    event.verdict.measured, event.verdict.limit);
      why = "its linear speed " + std::string(numbers);
      break;
    case FreezeReason::AngularSpeed:
      std::snprintf(numbers, sizeof numbers,
                    "%.6g rad/s is above limits.max_angular_speed (%.6g rad/s)",
                    event.verdict.measured, event.verdict.limit);
      why = "its angular speed " + std::string(numbers);
      break;
    case FreezeReason::Requested:
      why = "it was asked to";
      break;
    case FreezeReason::None:
      why = "no reason";
      break;
  }
  std::string joints;
  for (std::size_t i = 0; i < event.droppedJoints.size(); ++i)
    joints += (i == 0 ? "'" : ", '") + event.droppedJoints[i] + "'";
  if (!joints.empty())
    joints = "; its joint" + std::string(event.droppedJoints.size() > 1 ? "s " : " ") + joints +
             (event.droppedJoints.size() > 1 ? " were" : " was") + " removed";
  return "body '" + event.name + "' frozen at step " + std::to_string(event.step) + ": " + why +
         "; it is held at its last good pose with zero velocity and no longer stepped or collided" +
         joints + " (RESET restores the world; REMOVE clears the body)";
}

}  // namespace rbsim
