#pragma once
// Log lines on stderr: "2026-11-22T01:02:03.456Z rbserver[pid] LEVEL message".
// journald keeps stderr of a systemd service, so this is also the daemon's log.

#include <string>
#include <string_view>

namespace rbsim {

enum class LogLevel { Debug = 0, Info = 1, Warning = 2, Error = 3 };

void setLogLevel(LogLevel level);
bool parseLogLevel(std::string_view text, LogLevel& level);  // "debug", "info", "warning", "error"
void logMessage(LogLevel level, const std::string& message);

inline void logDebug(const std::string& message) { logMessage(LogLevel::Debug, message); }
inline void logInfo(const std::string& message) { logMessage(LogLevel::Info, message); }
inline void logWarning(const std::string& message) { logMessage(LogLevel::Warning, message); }
inline void logError(const std::string& message) { logMessage(LogLevel::Error, message); }

}  // namespace rbsim
