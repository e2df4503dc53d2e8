#pragma once
// Distribution of step-start lateness against the real-time schedule, in
// 1 µs bins up to 100 ms (beyond that, one overflow bin), so percentiles of
// a long run cost a fixed 800 kB and nothing per step but an increment.

#include <cstdint>
#include <vector>

#include "daemon/step_clock.h"

namespace rbsim {

class LatenessHistogram {
 public:
  LatenessHistogram() : m_counts(kBins + 1, 0) {}

  void add(Nanoseconds lateness);
  int64_t count() const { return m_count; }
  // Smallest lateness (ns, the bin's upper edge capped at the maximum) at or below which a fraction q of
  // the samples lie; nearest rank. 0 when empty.
  Nanoseconds percentile(double q) const;
  Nanoseconds maximum() const { return m_maximum; }

 private:
  static constexpr int kBins = 100000;  // 1 µs each
  std::vector<int64_t> m_counts;
  int64_t m_count = 0;
  Nanoseconds m_maximum = 0;
};

}  // namespace rbsim
