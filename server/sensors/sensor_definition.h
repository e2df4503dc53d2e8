#pragma once
// What a world file's `sensors:` entry declares (config/sensor_config.h
// reads it): a sensor's kind, where it sits, how often it reads and how
// noisy it is. Plain data, checked by the config reader; SensorSuite
// (sensors/sensor_suite.h) makes readings from it.

#include <cstdint>
#include <string>
#include <string_view>

#include "rbsim/physics/math_types.h"
#include "rbsim/physics/quaternion.h"

namespace rbsim {

enum class SensorType { Imu, Contact, ForceTorque, Range, Lidar };

// The world file's spelling of each type ("imu", "contact", ...).
std::string_view sensorTypeName(SensorType type);

// Standard deviations of the zero-mean Gaussian noise added to each
// component of a reading (0: none), and the seed that makes it replayable:
// the noise of a reading is a function of (seed, step, component) only
// (sensors/gaussian_noise.h).
struct SensorNoise {
  double linearAcceleration = 0.0;  // m/s², imu
  double angularVelocity = 0.0;     // rad/s, imu
  double force = 0.0;               // N, contact and force_torque
  double torque = 0.0;              // N·m, contact and force_torque
  double range = 0.0;               // m, range and lidar
  uint64_t seed = 0;
};

// The beams of a lidar: `beams` elevations from verticalMin to verticalMax
// times `horizontalSamples` azimuths from horizontalMin to horizontalMax,
// both ends included (as Gazebo's and ROS LaserScan's angle_min/angle_max).
// A range sensor is one beam along the sensor's x axis.
struct ScanPattern {
  int horizontalSamples = 1;
  double horizontalMin = 0.0;  // rad, about the sensor's z from its x axis
  double horizontalMax = 0.0;
  int beams = 1;
  double verticalMin = 0.0;  // rad, from the sensor's x-y plane towards +z
  double verticalMax = 0.0;
  double minRange = 0.0;  // m: closer readings are -inf
  double maxRange = 10.0;  // m: beyond it, no return (+inf)
  bool reportBodies = false;  // publish the name of the body each beam hit

  double horizontalIncrement() const {
    return horizontalSamples > 1 ? (horizontalMax - horizontalMin) / (horizontalSamples - 1) : 0.0;
  }
  double verticalIncrement() const { return beams > 1 ? (verticalMax - verticalMin) / (beams - 1) : 0.0; }
  int rayCount() const { return horizontalSamples * beams; }
};

struct SensorDef {
  std::string name;  // unique in the world; letters, digits and '_' (it names a channel)
  SensorType type = SensorType::Imu;
  // The body that carries the sensor (a robot's link is "robot/link"). For
  // force_torque, the joint's child body (body_b), filled in by the reader.
  std::string body;
  std::string joint;  // force_torque only: the joint measured
  // The sensor frame in the body's config frame (the frame its `position`
  // and `orientation` place, a robot link's own frame): m and (w, x, y, z).
  Vec3 position = Vec3::Zero();
  Quaternion orientation = Quaternion::identity();
  double rate = 100.0;  // Hz on the simulated clock
  SensorNoise noise;
  ScanPattern pattern;  // range and lidar
  std::string source;   // where it was declared, for messages ("world.yaml:30:5: sensors[1]")
};

}  // namespace rbsim
