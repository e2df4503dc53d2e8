#include "rbsim/client/client_defaults.h"

#include <unistd.h>

#include <atomic>
#include <cstdlib>

namespace rbsim::client {

std::string resolveLcmUrl(const std::string& url) {
  if (!url.empty()) return url;
  const char* fromEnvironment = std::getenv("LCM_DEFAULT_URL");
  if (fromEnvironment != nullptr && *fromEnvironment != '\0') return fromEnvironment;
  return kDefaultUrl;
}

std::string makeDefaultClientId() {
  static std::atomic<int> made{0};
  const int index = ++made;
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) != 0 || host[0] == '\0') host[0] = '?';
  std::string id = "cpp-" + std::string(host) + "-" + std::to_string(getpid());
  if (index > 1) id += "-" + std::to_string(index);
  return id;
}

std::string resolveClientId(const std::string& clientId) {
  if (!clientId.empty()) return clientId;
  const char* fromEnvironment = std::getenv("RBSIM_CLIENT_ID");
  if (fromEnvironment != nullptr && *fromEnvironment != '\0') return fromEnvironment;
  return makeDefaultClientId();
}

}  // namespace rbsim::client
