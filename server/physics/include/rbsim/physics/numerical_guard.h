#pragma once
// The numerical guard's limits and what it reports. After every step the
// world checks each awake dynamic body once: a state that holds a NaN or an
// infinity, or moves faster than the world's StateLimits, is never
// integrated again. Such a body is frozen: put back at its pose from before
// the bad step (the last pose that passed the check), with zero momenta, and
// excluded from integration and from collision detection, so the rest of
// the world steps on exactly as if the body were not there (as long as
// nothing touched it in the bad step). A frozen body stays frozen: only
// RESET (a fresh copy of the initial world) or removing it brings the slot
// back. The check itself is internal (world/state_guard.h).

#include <cstdint>
#include <string>
#include <vector>

#include "rbsim/physics/freeze_reason.h"
#include "rbsim/physics/ids.h"

namespace rbsim {

// The bounds a healthy body stays within (config: the `limits:` section).
// Generous on purpose: they catch runaway states, not fast bodies. At the
// default dt of 1 ms, 1e4 m/s is 10 m a step and 1e4 rad/s 1.6 turns a step,
// beyond anything the integrators or the contact solver resolve.
struct StateLimits {
  double maxLinearSpeed = 1e4;   // m/s, of the centre of mass
  double maxAngularSpeed = 1e4;  // rad/s
};

// What the check found for one body.
struct StateVerdict {
  FreezeReason reason = FreezeReason::None;
  double measured = 0.0;  // the offending speed (m/s or rad/s); 0 for non-finite states
  double limit = 0.0;     // the limit it broke
};

// A body frozen during a step, for the caller to report.
struct FreezeEvent {
  BodyId id;
  std::string name;
  int64_t step = 0;  // the step that went bad (numbered as on the wire)
  StateVerdict verdict;
  std::vector<std::string> droppedJoints;  // the joints it had, removed with the freeze
};

// One line for a log: which body, at which step, why, and what happens to it.
std::string describeFreeze(const FreezeEvent& event);

}  // namespace rbsim
