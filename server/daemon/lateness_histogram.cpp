#include "daemon/lateness_histogram.h"

#include <algorithm>
#include <cmath>

namespace rbsim {

void LatenessHistogram::add(Nanoseconds lateness) {
  const Nanoseconds clamped = std::max<Nanoseconds>(0, lateness);
  const auto bin = static_cast<std::size_t>(std::min<Nanoseconds>(clamped / 1000, kBins));
  ++m_counts[bin];
  ++m_count;
  m_maximum = std::max(m_maximum, clamped);
}

Nanoseconds LatenessHistogram::percentile(double q) const {
  if (m_count == 0) return 0;
  const auto rank = static_cast<int64_t>(std::ceil(q * static_cast<double>(m_count)));
  int64_t seen = 0;
  for (std::size_t bin = 0; bin < m_counts.size(); ++bin) {
    seen += m_counts[bin];
    if (seen >= std::max<int64_t>(rank, 1)) {
      // The bin's upper edge, but never above the largest sample seen.
      return bin == static_cast<std::size_t>(kBins)
                 ? m_maximum
                 : std::min(static_cast<Nanoseconds>(bin + 1) * 1000, m_maximum);
    }
  }
  return m_maximum;
}

}  // namespace rbsim
