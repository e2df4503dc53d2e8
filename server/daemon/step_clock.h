#pragma once
// Real-time pacing of the stepping loop with absolute deadlines on the
// monotonic clock (never sleep(dt): sleeping accumulates every wake-up
// delay into drift, absolute deadlines do not).
//
// Step k (counted since the last anchor) is due at anchor + k·dt/rtf. When
// the loop falls behind, the catch-up policy decides:
//  - Burst: take the late steps back to back, at most `maxBurst` in a row
//    beyond the schedule; further behind than that, re-anchor (the missed
//    wall time is given up, counted in `slips`). Long-run rate stays exact
//    after short hiccups.
//  - Reanchor: every late step re-anchors the schedule at its start: never a
//    burst, the simulation slips by whatever was lost (Gazebo's behaviour).
// A real-time factor of 0 means as fast as possible: every step is due now.

#include <cstdint>

#include "config/server_settings.h"

namespace rbsim {

using Nanoseconds = int64_t;

Nanoseconds monotonicNow();  // CLOCK_MONOTONIC, ns

class StepClock {
 public:
  StepClock(double dt, double realTimeFactor, CatchUpPolicy policy, int maxBurst);

  // Restarts the schedule so that the next step is due at `now`.
  void anchor(Nanoseconds now);
  void setRealTimeFactor(double realTimeFactor, Nanoseconds now);
  double realTimeFactor() const { return m_realTimeFactor; }

  // When the next step is due (== now for an unpaced clock).
  Nanoseconds nextDeadline(Nanoseconds now) const;

  // Call when a step starts at `now`: returns how late it started against
  // its deadline (ns, >= 0) and applies the catch-up policy.
  Nanoseconds beginStep(Nanoseconds now);
  // Call when the step (and its publishing) is done: counts an overrun if it
  // finished after the following step was due.
  void endStep(Nanoseconds now);

  int64_t overruns() const { return m_overruns; }
  int64_t slips() const { return m_slips; }  // re-anchors forced by falling too far behind

 private:
  Nanoseconds deadlineOf(int64_t stepsSinceAnchor) const;

  double m_dt;
  double m_realTimeFactor;
  CatchUpPolicy m_policy;
  int m_maxBurst;
  Nanoseconds m_anchor = 0;
  int64_t m_stepsSinceAnchor = 0;  // steps begun since the anchor
  int64_t m_overruns = 0;
  int64_t m_slips = 0;
};

}  // namespace rbsim
