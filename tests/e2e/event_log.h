#pragma once
// Reading an LCM event log (as written by rbserver --record or lcm-logger)
// with LCM's own C API, so the tests check the file the tools will read.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rbsim::e2e {

struct LoggedEvent {
  int64_t eventNumber = 0;
  int64_t timestamp = 0;  // µs since the epoch
  std::string channel;
  std::vector<uint8_t> data;
};

struct EventLog {
  std::vector<LoggedEvent> events;
  int64_t fileSize = 0;
  int64_t bytesParsed = 0;  // where the reader stopped: fileSize when the last event is whole
  bool opened = false;
};

EventLog readEventLog(const std::string& path);

// The message of an event, when it decodes as T using all of its bytes.
template <class T>
std::optional<T> decodeAs(const LoggedEvent& event) {
  T message;
  const int used = message.decode(event.data.data(), 0, static_cast<int>(event.data.size()));
  if (used < 0 || static_cast<std::size_t>(used) != event.data.size()) return std::nullopt;
  return message;
}

}  // namespace rbsim::e2e
