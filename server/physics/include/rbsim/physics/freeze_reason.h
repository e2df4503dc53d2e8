#pragma once
// Why the numerical guard took a body out of the simulation (see
// numerical_guard.h). None: the body is simulated normally.

#include <cstdint>
#include <string_view>

namespace rbsim {

enum class FreezeReason : uint8_t {
  None,
  NonFiniteState,  // x, q, P or L held a NaN or an infinity after a step
  LinearSpeed,     // |v| above StateLimits::maxLinearSpeed
  AngularSpeed,    // |ω| above StateLimits::maxAngularSpeed
  Requested,       // frozen through World::freezeBody (tests, restored checkpoints)
};

// "non-finite state", "linear speed", ... for log lines.
std::string_view freezeReasonName(FreezeReason reason);

}  // namespace rbsim
