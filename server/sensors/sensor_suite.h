#pragma once
// A world's sensors at run time: which are due after a step (each at its
// rate on the simulated clock), what they read, with their noise.
//
// Sensors observe: nothing here changes the world, so a world steps to the
// same bits with or without sensors. A sensor reads after step n when n is
// a multiple of its period in steps, round(1 / (rate dt)) (at least 1): a
// 1 kHz sensor on a 1 kHz world reads after every step, a 10 Hz one after
// every 100th. Bodies and joints are found by name at each reading, so a
// sensor follows a RESET or a checkpoint restored, and is silent while its
// body (or joint) is not in the world.

#include <cstdint>
#include <memory>
#include <vector>

#include "rbsim/physics/world.h"
#include "sensors/imu_model.h"
#include "sensors/range_scanner.h"
#include "sensors/sensor_definition.h"
#include "sensors/sensor_reading.h"

namespace rbsim {

class SensorSuite {
 public:
  SensorSuite() = default;
  // `dt` (s) is the world's step, which the rates are turned into periods of.
  SensorSuite(std::vector<SensorDef> sensors, double dt);

  bool empty() const { return m_sensors.empty(); }
  std::size_t size() const { return m_sensors.size(); }
  const SensorDef& definition(std::size_t index) const { return m_sensors[index]->def; }
  int64_t periodSteps(std::size_t index) const { return m_sensors[index]->periodSteps; }

  // Call right before World::step: the IMUs keep their bodies' velocities.
  void beforeStep(const World& world);
  // After World::step: the readings due after it, in declaration order,
  // into `readings` (cleared first).
  void readAfterStep(const World& world, std::vector<SensorReading>& readings);

 private:
  struct Active {
    SensorDef def;
    int64_t periodSteps = 1;
    BodyVelocities before;
    bool haveBefore = false;
    std::unique_ptr<RangeScanner> scanner;  // range and lidar
  };

  bool read(const World& world, Active& sensor, SensorReading& reading);

  std::vector<std::unique_ptr<Active>> m_sensors;
};

// round(1 / (rate dt)), at least 1: how many steps apart a sensor reads.
int64_t sensorPeriodSteps(double rate, double dt);

}  // namespace rbsim
