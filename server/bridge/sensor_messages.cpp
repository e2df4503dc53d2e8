#include "bridge/sensor_messages.h"

namespace rbsim {

namespace {

void copyVector(double (&out)[3], const Vec3& v) {
  for (int i = 0; i < 3; ++i) out[i] = v[i];
}

void copyQuaternion(double (&out)[4], const Quaternion& q) {
  out[0] = q.w;
  out[1] = q.x;
  out[2] = q.y;
  out[3] = q.z;
}

template <class Message>
void fillHeader(Message& message, const SensorReading& reading, int64_t utime) {
  message.utime = utime;
  message.step = reading.step;
  message.sim_time = reading.simTime;
  message.name = reading.sensor->name;
}

}  // namespace

std::string sensorChannel(const std::string& channelPrefix, const std::string& sensorName) {
  return channelPrefix + "SENSOR_" + sensorName;
}

rbsim::imu_t sensorMessage(const SensorReading& reading, const ImuReading& imu, int64_t utime) {
  rbsim::imu_t message;
  fillHeader(message, reading, utime);
  message.body = reading.sensor->body;
  copyVector(message.linear_acceleration, imu.linearAcceleration);
  copyVector(message.angular_velocity, imu.angularVelocity);
  copyQuaternion(message.orientation, imu.orientation);
  return message;
}

rbsim::contact_sensor_t sensorMessage(const SensorReading& reading, const ContactReading& contact, int64_t utime) {
  rbsim::contact_sensor_t message;
  fillHeader(message, reading, utime);
  message.body = reading.sensor->body;
  copyVector(message.force, contact.force);
  copyVector(message.torque, contact.torque);
  message.num_contacts = contact.contacts;
  return message;
}

rbsim::force_torque_t sensorMessage(const SensorReading& reading, const ForceTorqueReading& wrench, int64_t utime) {
  rbsim::force_torque_t message;
  fillHeader(message, reading, utime);
  message.joint = reading.sensor->joint;
  message.body = reading.sensor->body;
  copyVector(message.force, wrench.force);
  copyVector(message.torque, wrench.torque);
  return message;
}

rbsim::range_scan_t sensorMessage(const SensorReading& reading, const RangeReading& scan, int64_t utime) {
  rbsim::range_scan_t message;
  fillHeader(message, reading, utime);
  const ScanPattern& pattern = reading.sensor->pattern;
  message.body = reading.sensor->body;
  copyVector(message.position, scan.position);
  copyQuaternion(message.orientation, scan.orientation);
  message.horizontal_samples = pattern.horizontalSamples;
  message.horizontal_min = pattern.horizontalMin;
  message.horizontal_increment = pattern.horizontalIncrement();
  message.beams = pattern.beams;
  message.vertical_min = pattern.verticalMin;
  message.vertical_increment = pattern.verticalIncrement();
  message.min_range = pattern.minRange;
  message.max_range = pattern.maxRange;
  message.num_ranges = static_cast<int32_t>(scan.ranges.size());
  message.ranges = scan.ranges;
  message.num_hit_bodies = static_cast<int32_t>(scan.hitBodies.size());
  message.hit_bodies = scan.hitBodies;
  return message;
}

}  // namespace rbsim
