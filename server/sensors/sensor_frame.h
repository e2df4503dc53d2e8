#pragma once
// Where a sensor is in the world now: its body's pose composed with the
// sensor's pose in the body's config frame (the frame the world file's
// `position` and `orientation` place).

#include "rbsim/physics/body_view.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/quaternion.h"
#include "sensors/sensor_definition.h"

namespace rbsim {

struct SensorFrame {
  Vec3 position = Vec3::Zero();     // m, world
  Quaternion orientation;           // sensor -> world
  Mat3 rotation = Mat3::Identity();  // the same as a matrix

  Vec3 toSensor(const Vec3& worldVector) const { return rotation.transpose() * worldVector; }
};

SensorFrame sensorFrame(const BodyView& body, const SensorDef& sensor);

}  // namespace rbsim
