#pragma once
// The acks a client has received, by (kind, seq), for waitForAck: kept as they
// arrive, so that waiting after the ack came in still finds it, and the
// oldest by arrival dropped past a bound, so that a client streaming requests
// without waiting does not grow forever. (By arrival, not by key: a client
// that sends seven joint commands and a STEP a cycle must not lose each new
// STEP ack because kind 2 sorts before kind 3.)

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <rbsim/ack_t.hpp>
#include <utility>

namespace rbsim::client {

class AckStore {
 public:
  using Key = std::pair<int8_t, int64_t>;  // (ack_t.kind, ack_t.seq)

  explicit AckStore(std::size_t capacity = 4096) : m_capacity(capacity) {}

  void add(const rbsim::ack_t& ack) {
    const Key key{ack.kind, ack.seq};
    if (m_acks.insert_or_assign(key, ack).second) m_order.push_back(key);
    while (m_acks.size() > m_capacity) {
      m_acks.erase(m_order.front());
      m_order.pop_front();
    }
  }
  const rbsim::ack_t* find(const Key& key) const {
    const auto found = m_acks.find(key);
    return found == m_acks.end() ? nullptr : &found->second;
  }

 private:
  std::size_t m_capacity;
  std::map<Key, rbsim::ack_t> m_acks;
  std::deque<Key> m_order;  // m_acks' keys, oldest first
};

}  // namespace rbsim::client
