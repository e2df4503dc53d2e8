#include "replay/event_recorder.h"

#include <lcm/eventlog.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace rbsim {

EventRecorder::~EventRecorder() { close(); }

Expected<bool> EventRecorder::open(const std::string& path) {
  close();
  m_log = lcm_eventlog_create(path.c_str(), "w");
  if (m_log == nullptr)
    return Error{"cannot open record file '" + path + "' for writing: " + std::strerror(errno)};
  m_eventNumber = 0;
  return true;
}

void EventRecorder::write(const std::string& channel, const void* data, std::size_t size,
                          int64_t utime) {
  if (m_log == nullptr) return;
  lcm_eventlog_event_t event{};
  event.eventnum = m_eventNumber;
  event.timestamp = utime;
  event.channellen = static_cast<int32_t>(channel.size());
  event.datalen = static_cast<int32_t>(size);
  event.channel = const_cast<char*>(channel.c_str());  // the C API takes non-const but only reads
  event.data = const_cast<void*>(data);
  if (lcm_eventlog_write_event(m_log, &event) == 0) {
    ++m_eventNumber;
  } else {
    ++m_writeErrors;
  }
}

void EventRecorder::flush() {
  if (m_log != nullptr) std::fflush(m_log->f);
}

void EventRecorder::close() {
  if (m_log == nullptr) return;
  lcm_eventlog_destroy(m_log);  // flushes and closes the file
  m_log = nullptr;
}

}  // namespace rbsim
