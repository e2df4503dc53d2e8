#pragma once
// Reading one sensor of a world (the world file's `sensors:`), which
// rbserver publishes on <prefix>SENSOR_<name> with the lcmtype of its kind:
// imu_t, contact_sensor_t, force_torque_t or range_scan_t.
//
//   rbsim::client::Client client;
//   rbsim::client::SensorReader imu(client, "cart_imu");
//   imu.onReading([](const rbsim::client::SensorMessage& m) {
//     if (const auto* reading = std::get_if<rbsim::imu_t>(&m)) use(reading->linear_acceleration);
//   });
//   client.spinUntil([&] { return imu.count() >= 100; }, 2s);
//
// The reader decodes whichever of the four types arrives (told apart by
// their LCM fingerprints); messages run through the Client's handle(), on
// its thread, like every other callback.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <variant>

#include <lcm/lcm-cpp.hpp>
#include <rbsim/contact_sensor_t.hpp>
#include <rbsim/force_torque_t.hpp>
#include <rbsim/imu_t.hpp>
#include <rbsim/range_scan_t.hpp>

#include "rbsim/client/client.h"

namespace rbsim::client {

using SensorMessage = std::variant<rbsim::imu_t, rbsim::contact_sensor_t, rbsim::force_torque_t, rbsim::range_scan_t>;

// <prefix>SENSOR_<name>.
std::string sensorChannel(const std::string& channelPrefix, const std::string& sensorName);

// The message in `data`, whichever sensor type it is; nullopt for bytes that
// are none of them or do not decode whole.
std::optional<SensorMessage> decodeSensorMessage(const void* data, std::size_t size);

// The sensor kind's world-file name: "imu", "contact", "force_torque", "range_scan".
const char* sensorMessageKind(const SensorMessage& message);

class SensorReader {
 public:
  using Callback = std::function<void(const SensorMessage&)>;

  // Subscribes `client`'s connection to the sensor's channel.
  SensorReader(Client& client, std::string sensorName);
  ~SensorReader();
  SensorReader(const SensorReader&) = delete;
  SensorReader& operator=(const SensorReader&) = delete;

  const std::string& name() const { return m_name; }
  const std::string& channel() const { return m_channel; }
  // The newest reading, and how many have arrived.
  const std::optional<SensorMessage>& latest() const { return m_latest; }
  uint64_t count() const { return m_count; }
  // Messages on the channel that were none of the sensor types.
  uint64_t undecodable() const { return m_undecodable; }
  // Runs for every reading, inside the Client's handle().
  void onReading(Callback callback) { m_callback = std::move(callback); }

 private:
  void onMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel);

  Client& m_client;
  std::string m_name;
  std::string m_channel;
  lcm::Subscription* m_subscription = nullptr;
  std::optional<SensorMessage> m_latest;
  uint64_t m_count = 0;
  uint64_t m_undecodable = 0;
  Callback m_callback;
};

}  // namespace rbsim::client
