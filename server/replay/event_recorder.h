#pragma once
// `--record FILE`: every message the server publishes and every message it
// receives, written to a standard LCM event log (readable by lcm-logplayer,
// lcm-spy's log player and our Python log reader), so a session can be
// analysed without UDP loss.

#include <cstdint>
#include <string>

#include "rbsim/physics/types.h"

struct _lcm_eventlog_t;

namespace rbsim {

class EventRecorder {
 public:
  EventRecorder() = default;
  ~EventRecorder();
  EventRecorder(const EventRecorder&) = delete;
  EventRecorder& operator=(const EventRecorder&) = delete;

  Expected<bool> open(const std::string& path);
  bool isOpen() const { return m_log != nullptr; }
  // `utime`: µs since the epoch (the receive time for received messages).
  void write(const std::string& channel, const void* data, std::size_t size, int64_t utime);
  void flush();
  void close();
  int64_t eventsWritten() const { return m_eventNumber; }
  int64_t writeErrors() const { return m_writeErrors; }

 private:
  _lcm_eventlog_t* m_log = nullptr;
  int64_t m_eventNumber = 0;
  int64_t m_writeErrors = 0;
};

}  // namespace rbsim
