#include "state_history.h"

#include <climits>
#include <iterator>
#include <stdexcept>

#include "rbsim/client/lookup.h"

namespace rbsim::e2e {

void StateHistory::attach(client::Client& client) {
  client.onState([this](const rbsim::world_state_t& state) {
    if (state.world_revision > m_revision) m_revision = state.world_revision;
    m_states[{state.world_revision, state.step}] = state;
  });
}

const rbsim::world_state_t& StateHistory::at(int64_t step) const {
  const auto found = m_states.find({m_revision, step});
  if (found == m_states.end())
    throw std::runtime_error("no state of step " + std::to_string(step) + " (world revision " +
                             std::to_string(m_revision) + ") was received");
  return found->second;
}

const rbsim::body_state_t& StateHistory::body(int64_t step, const std::string& name) const {
  const auto* found = client::findBody(at(step), name);
  if (found == nullptr)
    throw std::runtime_error("the state of step " + std::to_string(step) + " has no body '" + name +
                             "'");
  return *found;
}

int64_t StateHistory::lastStep() const {
  const auto last = m_states.lower_bound({m_revision + 1, INT64_MIN});
  if (last == m_states.begin()) return -1;
  const auto& [key, state] = *std::prev(last);
  return key.first == m_revision ? key.second : -1;
}

}  // namespace rbsim::e2e
