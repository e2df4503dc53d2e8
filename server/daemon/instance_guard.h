#pragma once
// Two rbservers on one URL and channel prefix interleave their states, and
// every client then sees the worlds alternate. Each server names itself with
// an instance id (in status_t.instance_id); at start it listens to its
// channels before publishing anything, and while it runs it watches the
// statuses on its prefix for another instance's id.

#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>

#include "daemon/step_clock.h"

namespace rbsim {

// "<host>-<pid>-<16 hex digits from std::random_device>": unique per run.
std::string makeInstanceId();

// What another server gave away on our prefix.
struct OtherInstance {
  std::string channel;     // where it was heard, e.g. RBSIM_STATE
  std::string instanceId;  // from its status; empty if only other messages were heard
};

// Listens on prefix STATE, STATUS, WORLD and CONTACTS for `window` ns
// (nothing of ours is out yet); the first message heard, if any.
std::optional<OtherInstance> listenForOtherInstance(lcm::LCM& lcm, const std::string& prefix,
                                                    Nanoseconds window);

// Keeps the last other instance heard on the status channel (the server
// feeds it every status it receives, its own included).
class InstanceWatch {
 public:
  explicit InstanceWatch(std::string ownId) : m_ownId(std::move(ownId)) {}
  const std::string& ownId() const { return m_ownId; }
  // True when this status comes from another instance and should be logged
  // (the first time, then at most every `logEvery`).
  bool heard(const std::string& instanceId, Nanoseconds now, Nanoseconds logEvery);
  // The other instance heard within `recent` before `now`, else empty.
  std::string recentOther(Nanoseconds now, Nanoseconds recent) const;

 private:
  std::string m_ownId;
  std::string m_other;
  Nanoseconds m_otherHeardAt = 0;
  std::optional<Nanoseconds> m_loggedAt;
};

}  // namespace rbsim
