#include "event_log.h"

#include <lcm/eventlog.h>

#include <cstdio>
#include <filesystem>

namespace rbsim::e2e {

EventLog readEventLog(const std::string& path) {
  EventLog log;
  lcm_eventlog_t* file = lcm_eventlog_create(path.c_str(), "r");
  if (file == nullptr) return log;
  log.opened = true;
  while (lcm_eventlog_event_t* event = lcm_eventlog_read_next_event(file)) {
    LoggedEvent copy;
    copy.eventNumber = event->eventnum;
    copy.timestamp = event->timestamp;
    copy.channel.assign(event->channel, static_cast<std::size_t>(event->channellen));
    const auto* bytes = static_cast<const uint8_t*>(event->data);
    copy.data.assign(bytes, bytes + event->datalen);
    log.events.push_back(std::move(copy));
    lcm_eventlog_free_event(event);
    log.bytesParsed = std::ftell(file->f);
  }
  lcm_eventlog_destroy(file);
  log.fileSize = static_cast<int64_t>(std::filesystem::file_size(path));
  return log;
}

}  // namespace rbsim::e2e
