// A whole config file as rbserver reads it (parseConfig): the world,
// contact section included, and the server's own sections, in one pass. A
// world that loads is built (World::fromDef: mass properties, hulls) and
// stepped a few times, as rbserver would, its sensors reading after each step.

#include <cstddef>
#include <cstdint>
#include <string>

#include "config/config_loader.h"
#include "sensors/sensor_suite.h"
#include "fuzz_paths.h"
#include "rbsim/physics/world.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rbsim;
  const std::string text(reinterpret_cast<const char*>(data), size);
  // Relative mesh paths resolve as for config/*.yaml (config/meshes/...).
  const auto config = parseConfig(text, "world.yaml", rbsim::fuzz::kConfigDir);
  if (!config) return 0;
  auto world = World::fromDef(config->world);
  if (!world) return 0;
  // Its sensors read after every step, whatever their rates say.
  std::vector<SensorDef> sensors = config->sensors;
  for (SensorDef& sensor : sensors) sensor.rate = 1.0 / world->settings().dt;
  SensorSuite suite(std::move(sensors), world->settings().dt);
  std::vector<SensorReading> readings;
  for (int i = 0; i < 3; ++i) {
    suite.beforeStep(*world);
    world->step();
    suite.readAfterStep(*world, readings);
  }
  return 0;
}
