#pragma once
// The real-time factor a server achieved while it was running: simulated
// time of the steps taken while not paused over the wall-clock time spent
// not paused. Paused time, STEP commands taken while paused and RESETs
// (which set the step count back) do not enter it, so the shutdown summary
// of a session that was paused for a while still says how well it kept pace.

#include <cstdint>
#include <optional>

#include "daemon/step_clock.h"

namespace rbsim {

class RunningRate {
 public:
  // Call whenever the pause state may have changed (and at the end), with
  // whether the server was running since the previous mark.
  void mark(Nanoseconds now, bool runningSincePreviousMark) {
    if (m_previous && runningSincePreviousMark) m_runningNanoseconds += now - *m_previous;
    m_previous = now;
  }
  // One step taken while running (not a STEP command's).
  void stepped() { ++m_steps; }

  double runningSeconds() const { return static_cast<double>(m_runningNanoseconds) * 1e-9; }
  int64_t steps() const { return m_steps; }
  // Simulated s per wall s while running; 0 before any running time.
  double factor(double dt) const {
    return m_runningNanoseconds > 0 ? static_cast<double>(m_steps) * dt / runningSeconds() : 0.0;
  }

 private:
  std::optional<Nanoseconds> m_previous;
  Nanoseconds m_runningNanoseconds = 0;
  int64_t m_steps = 0;
};

}  // namespace rbsim
