#pragma once
// The beams of a range sensor or lidar, cast with the world's batch ray
// cast (World::castRays, shared among the world's threads). The beams'
// directions in the sensor frame are computed once; each scan turns them
// into the world and reuses its buffers, so a scan allocates nothing after
// the first.
//
// Readings follow ROS REP 117 ("Informational distance measurements"), as
// LaserScan users expect: +inf where the beam hits nothing within the
// maximum range, -inf where the hit is closer than the minimum range.

#include <cstdint>
#include <optional>
#include <vector>

#include "rbsim/physics/ids.h"
#include "rbsim/physics/ray_cast.h"
#include "rbsim/physics/world.h"
#include "sensors/sensor_definition.h"
#include "sensors/sensor_frame.h"
#include "sensors/sensor_reading.h"

namespace rbsim {

class RangeScanner {
 public:
  explicit RangeScanner(const ScanPattern& pattern);

  // Casts every beam from the sensor's frame; the sensor's own body is
  // never hit. Gaussian noise of `rangeNoise` m (seeded as gaussian_noise.h
  // says, component = beam index) is added to each hit's distance before
  // the range limits are applied.
  void scan(const World& world, BodyId ownBody, const SensorFrame& frame, double rangeNoise, uint64_t seed,
            int64_t step, RangeReading& out);

  const std::vector<Vec3>& directions() const { return m_directions; }  // sensor frame, unit

 private:
  ScanPattern m_pattern;
  std::vector<Vec3> m_directions;
  std::vector<Ray> m_rays;
  std::vector<std::optional<RayHit>> m_hits;
};

}  // namespace rbsim
