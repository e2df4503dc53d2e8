#include "rbsim/client/sensor_reader.h"

#include <cstring>

#include "wire_helpers.h"

namespace rbsim::client {

namespace {

// The message's type is in its first 8 bytes, the type's fingerprint
// (big-endian), as every LCM message begins.
int64_t fingerprintOf(const void* data, std::size_t size) {
  if (size < 8) return 0;
  const auto* bytes = static_cast<const uint8_t*>(data);
  uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value = (value << 8) | bytes[i];
  return static_cast<int64_t>(value);
}

template <class Message>
std::optional<SensorMessage> decodeAs(const void* data, std::size_t size) {
  Message message;
  const int length = static_cast<int>(size);
  if (message.decode(data, 0, length) != length) return std::nullopt;
  return SensorMessage{std::move(message)};
}

}  // namespace

std::string sensorChannel(const std::string& channelPrefix, const std::string& sensorName) {
  return channelPrefix + "SENSOR_" + sensorName;
}

std::optional<SensorMessage> decodeSensorMessage(const void* data, std::size_t size) {
  if (size > static_cast<std::size_t>(INT32_MAX)) return std::nullopt;
  const int64_t fingerprint = fingerprintOf(data, size);
  if (fingerprint == rbsim::imu_t::getHash()) return decodeAs<rbsim::imu_t>(data, size);
  if (fingerprint == rbsim::contact_sensor_t::getHash()) return decodeAs<rbsim::contact_sensor_t>(data, size);
  if (fingerprint == rbsim::force_torque_t::getHash()) return decodeAs<rbsim::force_torque_t>(data, size);
  if (fingerprint == rbsim::range_scan_t::getHash()) return decodeAs<rbsim::range_scan_t>(data, size);
  return std::nullopt;
}

const char* sensorMessageKind(const SensorMessage& message) {
  switch (message.index()) {
    case 0: return "imu";
    case 1: return "contact";
    case 2: return "force_torque";
    default: return "range_scan";
  }
}

SensorReader::SensorReader(Client& client, std::string sensorName)
    : m_client(client), m_name(std::move(sensorName)), m_channel(sensorChannel(client.channelPrefix(), m_name)) {
  if (!client.good()) return;
  m_subscription = client.lcm().subscribe(detail::regexEscaped(m_channel), &SensorReader::onMessage, this);
  // A reading every step at 1 kHz: keep a burst between two handle() calls.
  m_subscription->setQueueCapacity(10000);
}

SensorReader::~SensorReader() {
  if (m_subscription != nullptr) m_client.lcm().unsubscribe(m_subscription);
}

void SensorReader::onMessage(const lcm::ReceiveBuffer* buffer, const std::string&) {
  std::optional<SensorMessage> message = decodeSensorMessage(buffer->data, buffer->data_size);
  if (!message) {
    ++m_undecodable;
    return;
  }
  m_latest = std::move(message);
  ++m_count;
  if (m_callback) m_callback(*m_latest);
}

}  // namespace rbsim::client
