#pragma once
// What Client and Robot both need to talk LCM the same way (private to the
// library).

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include <lcm/lcm-cpp.hpp>

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

using Timeout = std::chrono::milliseconds;

// handleMessages() stops draining after this many messages so that a fast
// publisher cannot keep it from returning.
inline constexpr int kMaxBatch = 100000;
// spinUntil() checks its predicate at least this often even when no message
// comes, for predicates that watch something other than LCM (a child
// process, a signal flag, a lost connection).
inline constexpr Timeout kMaxWaitSlice{50};

// Client::handle and Robot::handle: waits up to `timeout` for a message,
// then dispatches it and every one already waiting; how many, 0 for none,
// -1 on an LCM error.
inline int handleMessages(lcm::LCM& lcm, Timeout timeout) {
  const auto millis = std::clamp<Timeout::rep>(timeout.count(), 0, INT_MAX);
  errno = 0;
  int status = lcm.handleTimeout(static_cast<int>(millis));
  // A signal that interrupted the wait is no LCM error: report "nothing yet"
  // so that spinUntil() goes on (and sees a flag the handler may have set).
  if (status < 0 && errno == EINTR) return 0;
  if (status <= 0) return status < 0 ? -1 : 0;
  int handled = 1;
  while (handled < kMaxBatch && (status = lcm.handleTimeout(0)) > 0) ++handled;
  return status < 0 ? -1 : handled;
}

// Client::spinUntil and Robot::spinUntil: `handle` until `done` or `timeout`.
inline bool spinUntil(const std::function<int(Timeout)>& handle, const std::function<bool()>& good,
                      const std::function<bool()>& done, Timeout timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline || !good()) return false;
    const auto slice = std::min(std::chrono::ceil<Timeout>(deadline - now), kMaxWaitSlice);
    if (handle(slice) < 0) return done();
  }
  return true;
}

}  // namespace rbsim::client::detail
