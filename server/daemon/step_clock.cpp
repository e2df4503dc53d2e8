#include "daemon/step_clock.h"

#include <cmath>
#include <ctime>

namespace rbsim {

Nanoseconds monotonicNow() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<Nanoseconds>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

StepClock::StepClock(double dt, double realTimeFactor, CatchUpPolicy policy, int maxBurst)
    : m_dt(dt), m_realTimeFactor(realTimeFactor), m_policy(policy), m_maxBurst(maxBurst) {}

void StepClock::anchor(Nanoseconds now) {
  m_anchor = now;
  m_stepsSinceAnchor = 0;
}

void StepClock::setRealTimeFactor(double realTimeFactor, Nanoseconds now) {
  m_realTimeFactor = realTimeFactor;
  anchor(now);
}

Nanoseconds StepClock::deadlineOf(int64_t stepsSinceAnchor) const {
  if (m_realTimeFactor <= 0.0) return m_anchor;
  // Computed from the anchor every time (not accumulated) so the schedule
  // has no rounding drift however long it runs.
  const double period = m_dt / m_realTimeFactor * 1e9;
  return m_anchor + static_cast<Nanoseconds>(std::llround(static_cast<double>(stepsSinceAnchor) * period));
}

Nanoseconds StepClock::nextDeadline(Nanoseconds now) const {
  if (m_realTimeFactor <= 0.0) return now;
  return deadlineOf(m_stepsSinceAnchor);
}

Nanoseconds StepClock::beginStep(Nanoseconds now) {
  if (m_realTimeFactor <= 0.0) {
    ++m_stepsSinceAnchor;
    return 0;
  }
  const Nanoseconds due = deadlineOf(m_stepsSinceAnchor);
  const Nanoseconds lateness = now > due ? now - due : 0;
  if (lateness > 0) {
    const double period = m_dt / m_realTimeFactor * 1e9;
    const double stepsBehind = static_cast<double>(lateness) / period;
    const bool reanchor = m_policy == CatchUpPolicy::Reanchor
                              ? stepsBehind >= 1.0
                              : stepsBehind > static_cast<double>(m_maxBurst);
    if (reanchor) {
      if (m_policy == CatchUpPolicy::Burst) ++m_slips;
      anchor(now);
    }
  }
  ++m_stepsSinceAnchor;
  return lateness;
}

void StepClock::endStep(Nanoseconds now) {
  if (m_realTimeFactor <= 0.0) return;
  if (now > deadlineOf(m_stepsSinceAnchor)) ++m_overruns;
}

}  // namespace rbsim
