#pragma once
// Per-client rate limit of wrenches and commands: a token bucket per client
// id. Each message takes a token; tokens come back at `rate` per second up
// to `burst`. A message that finds no token is rejected at once (with an
// ack): nothing is ever queued, so a flood costs the server one decode and
// one ack per message and never memory.
//
// Client ids are whatever the sender writes, so the table is bounded too:
// at most kMaxClients ids are tracked; beyond that, the ids whose buckets
// are full again are forgotten first, then the one seen longest ago.
// (This limits honest clients that misbehave; it is no defence against a
// sender who forges ids: LCM has no authentication, see docs/server.md.)

#include <cstdint>
#include <string>
#include <unordered_map>

namespace rbsim {

class ClientRateLimiter {
 public:
  static constexpr std::size_t kMaxClients = 4096;

  // rate: messages per second (0 = unlimited); burst: messages (>= 1).
  ClientRateLimiter(double rate, double burst) : m_rate(rate), m_burst(burst < 1.0 ? 1.0 : burst) {}

  // True if `client` may send a message at `now` (ns, monotonic); takes its token.
  bool allow(const std::string& client, int64_t now);

  bool unlimited() const { return m_rate <= 0.0; }
  std::size_t trackedClients() const { return m_buckets.size(); }

 private:
  struct Bucket {
    double tokens = 0.0;
    int64_t updated = 0;  // ns
  };
  double tokensAt(const Bucket& bucket, int64_t now) const;
  void makeRoom(int64_t now);

  double m_rate;
  double m_burst;
  // Looked up by id only; iterated only to evict, where the order decides
  // nothing about the simulation.
  std::unordered_map<std::string, Bucket> m_buckets;
};

}  // namespace rbsim
