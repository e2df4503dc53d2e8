#include "daemon/log.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>

namespace rbsim {

namespace {
std::atomic<int> g_minimumLevel{static_cast<int>(LogLevel::Info)};

const char* levelName(LogLevel level) {
  switch (level) {
    case LogLevel::Debug:
      return "DEBUG";
    case LogLevel::Info:
      return "INFO";
    case LogLevel::Warning:
      return "WARNING";
    case LogLevel::Error:
      return "ERROR";
  }
  return "?";
}
}  // namespace

void setLogLevel(LogLevel level) { g_minimumLevel = static_cast<int>(level); }

bool parseLogLevel(std::string_view text, LogLevel& level) {
  for (LogLevel candidate : {LogLevel::Debug, LogLevel::Info, LogLevel::Warning, LogLevel::Error}) {
    std::string name = levelName(candidate);
    for (char& c : name) c = static_cast<char>(c - 'A' + 'a');
    if (text == name) {
      level = candidate;
      return true;
    }
  }
  return false;
}

void logMessage(LogLevel level, const std::string& message) {
  if (static_cast<int>(level) < g_minimumLevel.load()) return;
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &utc);
  std::fprintf(stderr, "%s.%03dZ rbserver[%d] %s %s\n", stamp, static_cast<int>(millis),
               static_cast<int>(getpid()), levelName(level), message.c_str());
}

}  // namespace rbsim
