#include "bridge/client_rate_limiter.h"

#include <algorithm>

namespace rbsim {

double ClientRateLimiter::tokensAt(const Bucket& bucket, int64_t now) const {
  const double elapsed = static_cast<double>(std::max<int64_t>(0, now - bucket.updated)) * 1e-9;
  return std::min(m_burst, bucket.tokens + elapsed * m_rate);
}

void ClientRateLimiter::makeRoom(int64_t now) {
  std::erase_if(m_buckets, [&](const auto& entry) { return tokensAt(entry.second, now) >= m_burst; });
  if (m_buckets.size() < kMaxClients) return;
  const auto oldest = std::min_element(m_buckets.begin(), m_buckets.end(), [](const auto& a, const auto& b) {
    return a.second.updated < b.second.updated;
  });
  m_buckets.erase(oldest);
}

bool ClientRateLimiter::allow(const std::string& client, int64_t now) {
  if (unlimited()) return true;
  auto found = m_buckets.find(client);
  if (found == m_buckets.end()) {
    if (m_buckets.size() >= kMaxClients) makeRoom(now);
    found = m_buckets.emplace(client, Bucket{m_burst, now}).first;
  }
  Bucket& bucket = found->second;
  bucket.tokens = tokensAt(bucket, now);
  bucket.updated = std::max(bucket.updated, now);
  if (bucket.tokens < 1.0) return false;
  bucket.tokens -= 1.0;
  return true;
}

}  // namespace rbsim
