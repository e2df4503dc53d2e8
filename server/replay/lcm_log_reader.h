#pragma once
// Reads an LCM event log (lcm-logger's or rbserver --record's) one event at
// a time, for replays. The file is untrusted: every length is checked
// against the rest of the file before anything is allocated, and an error
// names the byte offset and the event number where the log went wrong.

#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "rbsim/physics/types.h"

namespace rbsim {

struct LogEvent {
  int64_t eventNumber = 0;
  int64_t timestamp = 0;  // µs since the epoch (receive or publish time)
  std::string channel;
  std::vector<uint8_t> data;
};

class LcmLogReader {
 public:
  // LCM's own limits: channel names up to 255 bytes (we allow LCM's 1000 in
  // old logs), messages up to 256 MiB.
  static constexpr int32_t kMaxChannelLength = 1000;
  static constexpr int32_t kMaxDataLength = 1 << 28;

  Expected<bool> open(const std::string& path);
  // The next event; nullopt at the clean end of the file; an error for a
  // truncated or corrupt event.
  Expected<std::optional<LogEvent>> next();
  const std::string& path() const { return m_path; }

 private:
  std::ifstream m_file;
  std::string m_path;
  int64_t m_fileSize = 0;
  int64_t m_offset = 0;
  int64_t m_eventsRead = 0;
};

}  // namespace rbsim
