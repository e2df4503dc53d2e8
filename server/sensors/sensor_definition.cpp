#include "sensors/sensor_definition.h"

namespace rbsim {

std::string_view sensorTypeName(SensorType type) {
  switch (type) {
    case SensorType::Imu: return "imu";
    case SensorType::Contact: return "contact";
    case SensorType::ForceTorque: return "force_torque";
    case SensorType::Range: return "range";
    case SensorType::Lidar: return "lidar";
  }
  return "unknown";
}

}  // namespace rbsim
