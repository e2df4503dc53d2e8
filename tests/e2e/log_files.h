#pragma once
// Writing LCM event logs from tests (to tamper with a recorded one), with
// LCM's own C API.

#include <string>
#include <vector>

#include "event_log.h"

namespace rbsim::e2e {

// Writes `events` as a new log at `path`; false on any error.
bool writeEventLog(const std::string& path, const std::vector<LoggedEvent>& events);

}  // namespace rbsim::e2e
