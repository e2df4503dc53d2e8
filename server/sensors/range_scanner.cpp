#include "sensors/range_scanner.h"

#include <cmath>
#include <limits>

#include "sensors/gaussian_noise.h"

namespace rbsim {

RangeScanner::RangeScanner(const ScanPattern& pattern) : m_pattern(pattern) {
  m_directions.reserve(static_cast<std::size_t>(pattern.rayCount()));
  for (int b = 0; b < pattern.beams; ++b) {
    const double elevation = pattern.verticalMin + b * pattern.verticalIncrement();
    for (int s = 0; s < pattern.horizontalSamples; ++s) {
      const double azimuth = pattern.horizontalMin + s * pattern.horizontalIncrement();
      m_directions.emplace_back(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                std::sin(elevation));
    }
  }
  m_rays.resize(m_directions.size());
  m_hits.resize(m_directions.size());
}

void RangeScanner::scan(const World& world, BodyId ownBody, const SensorFrame& frame, double rangeNoise,
                        uint64_t seed, int64_t step, RangeReading& out) {
  const double length = m_pattern.maxRange;
  for (std::size_t i = 0; i < m_directions.size(); ++i)
    m_rays[i] = Ray{frame.position, frame.position + frame.rotation * m_directions[i] * length};
  RayFilter filter;
  filter.excluded = ownBody;
  world.castRays(m_rays, m_hits, filter);

  constexpr float kNoReturn = std::numeric_limits<float>::infinity();
  out.position = frame.position;
  out.orientation = frame.orientation;
  out.ranges.resize(m_hits.size());
  out.hitBodies.clear();
  if (m_pattern.reportBodies) out.hitBodies.resize(m_hits.size());
  for (std::size_t i = 0; i < m_hits.size(); ++i) {
    const std::optional<RayHit>& hit = m_hits[i];
    if (!hit) {
      out.ranges[i] = kNoReturn;
      continue;
    }
    double distance = hit->distance;
    if (rangeNoise > 0.0) distance += rangeNoise * standardNormal(seed, step, i);
    if (distance > m_pattern.maxRange) out.ranges[i] = kNoReturn;
    else if (distance < m_pattern.minRange) out.ranges[i] = -kNoReturn;
    else out.ranges[i] = static_cast<float>(distance);
    if (m_pattern.reportBodies && std::isfinite(out.ranges[i])) out.hitBodies[i] = world.body(hit->body).name();
  }
}

}  // namespace rbsim
