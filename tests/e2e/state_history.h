#pragma once
// Every complete state a client receives, by (world revision, step), so that
// a test can look at the state of any step after the fact. A state
// republished while paused replaces the earlier copy of its step (they are
// equal but for utime).

#include <cstdint>
#include <map>
#include <rbsim/body_state_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <string>
#include <utility>

#include "rbsim/client/client.h"

namespace rbsim::e2e {

class StateHistory {
 public:
  void attach(client::Client& client);

  bool has(int64_t step) const { return m_states.count({m_revision, step}) > 0; }
  // The state of `step` in the newest world revision; throws when there is none.
  const rbsim::world_state_t& at(int64_t step) const;
  // One body of it; throws when absent.
  const rbsim::body_state_t& body(int64_t step, const std::string& name) const;
  int64_t revision() const { return m_revision; }
  // The highest step received in the newest revision (−1 before any).
  int64_t lastStep() const;

 private:
  std::map<std::pair<int64_t, int64_t>, rbsim::world_state_t> m_states;  // (revision, step)
  int64_t m_revision = -1;
};

}  // namespace rbsim::e2e
