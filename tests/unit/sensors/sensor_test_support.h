#pragma once
// Small worlds and one-line reads for the sensor tests.

#include <gtest/gtest.h>

#include <variant>
#include <vector>

#include "rbsim/physics/world.h"
#include "sensors/sensor_suite.h"

namespace rbsim::testing {

inline WorldSettings settingsWith(double dt, const Vec3& gravity,
                                  IntegratorKind integrator = IntegratorKind::SemiImplicitEuler) {
  WorldSettings settings;
  settings.dt = dt;
  settings.gravity = gravity;
  settings.integrator = integrator;
  return settings;
}

inline BodyId addBody(World& world, BodyDef def) {
  auto id = world.createBody(def);
  EXPECT_TRUE(id.ok()) << (id.ok() ? "" : id.error().message);
  return id.ok() ? *id : BodyId{};
}

inline BodyId addGround(World& world) {
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  return addBody(world, ground);
}

// Steps once with the suite watching and gives the readings due after it.
inline std::vector<SensorReading> stepAndRead(World& world, SensorSuite& suite) {
  suite.beforeStep(world);
  world.step();
  std::vector<SensorReading> readings;
  suite.readAfterStep(world, readings);
  return readings;
}

// The one reading of the kind T after a step (the suite holds one sensor).
template <class T>
T stepAndReadOne(World& world, SensorSuite& suite) {
  const std::vector<SensorReading> readings = stepAndRead(world, suite);
  EXPECT_EQ(readings.size(), 1u);
  if (readings.empty() || !std::holds_alternative<T>(readings[0].value)) {
    ADD_FAILURE() << "no reading of the expected kind";
    return T{};
  }
  return std::get<T>(readings[0].value);
}

inline SensorDef sensorOn(const std::string& body, SensorType type, double rate) {
  SensorDef def;
  def.name = std::string(1, 's');  // (GCC 12 warns, wrongly, about assigning a literal here)
  def.type = type;
  def.body = body;
  def.rate = rate;
  return def;
}

}  // namespace rbsim::testing
