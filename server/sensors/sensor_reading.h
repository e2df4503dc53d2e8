#pragma once
// What a sensor read after a step: one struct per kind, all in SI units,
// vectors in the sensor frame unless said otherwise. The bridge turns them
// into the wire types (imu_t, contact_sensor_t, force_torque_t,
// range_scan_t).

#include <cstdint>
#include <cstddef>
#include <string>
#include <variant>
#include <vector>

#include "rbsim/physics/math_types.h"
#include "rbsim/physics/quaternion.h"
#include "sensors/sensor_definition.h"

namespace rbsim {

struct ImuReading {
  Vec3 linearAcceleration = Vec3::Zero();  // m/s²: specific force, a − g
  Vec3 angularVelocity = Vec3::Zero();     // rad/s
  Quaternion orientation;                  // sensor -> world
};

struct ContactReading {
  Vec3 force = Vec3::Zero();   // N, on the body over the last step
  Vec3 torque = Vec3::Zero();  // N·m, about the sensor's origin
  int contacts = 0;            // contact points touching the body
};

struct ForceTorqueReading {
  Vec3 force = Vec3::Zero();   // N, the joint's on its child body over the last step
  Vec3 torque = Vec3::Zero();  // N·m, about the sensor's origin
};

struct RangeReading {
  Vec3 position = Vec3::Zero();  // m, world: the beams' origin
  Quaternion orientation;        // sensor -> world
  // m, beam-major (ranges[b * horizontalSamples + s]); +inf: no return
  // within the maximum range, -inf: closer than the minimum.
  std::vector<float> ranges;
  std::vector<std::string> hitBodies;  // as ranges when asked for ("" for no hit), else empty
};

struct SensorReading {
  const SensorDef* sensor = nullptr;  // owned by the SensorSuite that made it
  std::size_t sensorIndex = 0;        // its place in that suite (declaration order)
  int64_t step = 0;
  double simTime = 0.0;  // s
  std::variant<ImuReading, ContactReading, ForceTorqueReading, RangeReading> value;
};

}  // namespace rbsim
