#include "daemon/instance_guard.h"

#include <unistd.h>

#include <cstdio>
#include <random>
#include <rbsim/status_t.hpp>

namespace rbsim {

std::string makeInstanceId() {
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) != 0 || host[0] == '\0') host[0] = '?';
  std::random_device entropy;
  const uint64_t random = (static_cast<uint64_t>(entropy()) << 32) ^ entropy();
  char suffix[17];
  std::snprintf(suffix, sizeof suffix, "%016llx", static_cast<unsigned long long>(random));
  return std::string(host) + "-" + std::to_string(getpid()) + "-" + suffix;
}

namespace {

void onOtherServersMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel,
                           std::optional<OtherInstance>* out) {
  if (*out) return;
  OtherInstance other{channel, ""};
  rbsim::status_t status;
  if (channel.size() >= 6 && channel.compare(channel.size() - 6, 6, "STATUS") == 0 &&
      status.decode(buffer->data, 0, static_cast<int>(buffer->data_size)) > 0)
    other.instanceId = status.instance_id;
  *out = other;
}

}  // namespace

std::optional<OtherInstance> listenForOtherInstance(lcm::LCM& lcm, const std::string& prefix,
                                                    Nanoseconds window) {
  std::optional<OtherInstance> heard;
  // The prefix holds only letters, digits and '_' (checked at start): no
  // regex characters to escape.
  lcm::Subscription* subscription =
      lcm.subscribeFunction(prefix + "(STATE|STATUS|WORLD|CONTACTS)", &onOtherServersMessage, &heard);
  const Nanoseconds end = monotonicNow() + window;
  for (Nanoseconds now = monotonicNow(); now < end && !heard; now = monotonicNow()) {
    const int milliseconds = static_cast<int>((end - now + 999999) / 1000000);
    if (lcm.handleTimeout(milliseconds) < 0) break;
  }
  lcm.unsubscribe(subscription);
  return heard;
}

bool InstanceWatch::heard(const std::string& instanceId, Nanoseconds now, Nanoseconds logEvery) {
  if (instanceId == m_ownId) return false;
  m_other = instanceId;
  m_otherHeardAt = now;
  if (m_loggedAt && now - *m_loggedAt < logEvery) return false;
  m_loggedAt = now;
  return true;
}

std::string InstanceWatch::recentOther(Nanoseconds now, Nanoseconds recent) const {
  if (m_other.empty() || now - m_otherHeardAt > recent) return "";
  return m_other;
}

}  // namespace rbsim
