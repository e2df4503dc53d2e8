#include "sensors/sensor_suite.h"

#include <algorithm>
#include <cmath>

#include "sensors/contact_model.h"
#include "sensors/force_torque_model.h"
#include "sensors/gaussian_noise.h"

namespace rbsim {

namespace {

// Adds noise of `stddev` to the three components of `value`, numbered from
// `firstComponent`.
void addNoise(Vec3& value, double stddev, uint64_t seed, int64_t step, uint64_t firstComponent) {
  if (stddev <= 0.0) return;
  for (int i = 0; i < 3; ++i)
    value[i] += stddev * standardNormal(seed, step, firstComponent + static_cast<uint64_t>(i));
}

}  // namespace

int64_t sensorPeriodSteps(double rate, double dt) {
  return std::max<int64_t>(1, static_cast<int64_t>(std::llround(1.0 / (rate * dt))));
}

SensorSuite::SensorSuite(std::vector<SensorDef> sensors, double dt) {
  for (SensorDef& def : sensors) {
    auto active = std::make_unique<Active>();
    active->periodSteps = sensorPeriodSteps(def.rate, dt);
    if (def.type == SensorType::Range || def.type == SensorType::Lidar)
      active->scanner = std::make_unique<RangeScanner>(def.pattern);
    active->def = std::move(def);
    m_sensors.push_back(std::move(active));
  }
}

void SensorSuite::beforeStep(const World& world) {
  for (auto& sensor : m_sensors) {
    if (sensor->def.type != SensorType::Imu) continue;
    const BodyId id = world.findBody(sensor->def.body);
    sensor->haveBefore = !id.isNull();
    if (!sensor->haveBefore) continue;
    const BodyView body = world.body(id);
    sensor->before = {body.linearVelocity(), body.angularVelocity()};
  }
}

void SensorSuite::readAfterStep(const World& world, std::vector<SensorReading>& readings) {
  readings.clear();
  const int64_t step = world.stepCount();
  for (std::size_t i = 0; i < m_sensors.size(); ++i) {
    if (step % m_sensors[i]->periodSteps != 0) continue;
    SensorReading reading;
    reading.sensorIndex = i;
    if (read(world, *m_sensors[i], reading)) readings.push_back(std::move(reading));
  }
}

bool SensorSuite::read(const World& world, Active& sensor, SensorReading& reading) {
  const SensorDef& def = sensor.def;
  const BodyId id = world.findBody(def.body);
  if (id.isNull()) return false;
  const BodyView body = world.body(id);
  const SensorFrame frame = sensorFrame(body, def);
  const int64_t step = world.stepCount();
  const uint64_t seed = def.noise.seed;
  reading.sensor = &def;
  reading.step = step;
  reading.simTime = world.time();
  switch (def.type) {
    case SensorType::Imu: {
      if (!sensor.haveBefore) return false;
      ImuReading imu = readImu(body, frame, sensor.before, world.settings().gravity, world.settings().dt);
      addNoise(imu.linearAcceleration, def.noise.linearAcceleration, seed, step, 0);
      addNoise(imu.angularVelocity, def.noise.angularVelocity, seed, step, 3);
      reading.value = imu;
      return true;
    }
    case SensorType::Contact: {
      ContactReading contact = readContacts(world, body, frame);
      addNoise(contact.force, def.noise.force, seed, step, 0);
      addNoise(contact.torque, def.noise.torque, seed, step, 3);
      reading.value = contact;
      return true;
    }
    case SensorType::ForceTorque: {
      const JointId joint = world.findJoint(def.joint);
      if (joint.isNull()) return false;
      ForceTorqueReading wrench = readForceTorque(world.jointState(joint), frame);
      addNoise(wrench.force, def.noise.force, seed, step, 0);
      addNoise(wrench.torque, def.noise.torque, seed, step, 3);
      reading.value = wrench;
      return true;
    }
    case SensorType::Range:
    case SensorType::Lidar: {
      RangeReading scan;
      sensor.scanner->scan(world, id, frame, def.noise.range, seed, step, scan);
      reading.value = std::move(scan);
      return true;
    }
  }
  return false;
}

}  // namespace rbsim
