#pragma once
// Sensor readings (sensors/sensor_reading.h) as wire messages, and the
// channel each sensor publishes on: <prefix>SENSOR_<name>, one channel per
// sensor, so that a client subscribes to the sensors it wants and a scan of
// a lidar does not reach an IMU's reader (docs/lcm.md).

#include <cstdint>
#include <string>

#include <rbsim/contact_sensor_t.hpp>
#include <rbsim/force_torque_t.hpp>
#include <rbsim/imu_t.hpp>
#include <rbsim/range_scan_t.hpp>

#include "sensors/sensor_reading.h"

namespace rbsim {

std::string sensorChannel(const std::string& channelPrefix, const std::string& sensorName);

rbsim::imu_t sensorMessage(const SensorReading& reading, const ImuReading& imu, int64_t utime);
rbsim::contact_sensor_t sensorMessage(const SensorReading& reading, const ContactReading& contact, int64_t utime);
rbsim::force_torque_t sensorMessage(const SensorReading& reading, const ForceTorqueReading& wrench, int64_t utime);
rbsim::range_scan_t sensorMessage(const SensorReading& reading, const RangeReading& scan, int64_t utime);

}  // namespace rbsim
