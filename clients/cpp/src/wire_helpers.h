#pragma once
// What Client and Robot both need to talk LCM the same way (private to the
// library).

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

namespace rbsim::client::detail {

// LCM's default per-subscription queue holds 30 messages and drops the rest
// silently (docs/lcm.md, "Subscriptions"); a burst of STEPs at state rate 0
// publishes far more before the caller gets to handle them.
inline constexpr int kQueueCapacity = 10000;

inline int64_t wallMicroseconds() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// LCM subscribes to a POSIX extended regex anchored at both ends
// (docs/lcm.md, "Subscriptions"): a prefix such as "A.B_" must match itself only.
inline std::string regexEscaped(const std::string& channel) {
  std::string out;
  for (const char c : channel) {
    if (std::string_view("\\^$.|?*+()[]{}").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

}  // namespace rbsim::client::detail
