#include "log_files.h"

#include <lcm/eventlog.h>

namespace rbsim::e2e {

bool writeEventLog(const std::string& path, const std::vector<LoggedEvent>& events) {
  lcm_eventlog_t* file = lcm_eventlog_create(path.c_str(), "w");
  if (file == nullptr) return false;
  bool ok = true;
  for (const LoggedEvent& e : events) {
    lcm_eventlog_event_t event{};
    event.eventnum = e.eventNumber;
    event.timestamp = e.timestamp;
    event.channellen = static_cast<int32_t>(e.channel.size());
    event.datalen = static_cast<int32_t>(e.data.size());
    event.channel = const_cast<char*>(e.channel.c_str());  // the C API only reads it
    event.data = const_cast<uint8_t*>(e.data.data());
    ok = ok && lcm_eventlog_write_event(file, &event) == 0;
  }
  lcm_eventlog_destroy(file);
  return ok;
}

}  // namespace rbsim::e2e
