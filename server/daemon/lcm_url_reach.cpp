#include "daemon/lcm_url_reach.h"

#include <charconv>
#include <cstdlib>
#include <string_view>

namespace rbsim {

std::optional<int> multicastTtl(const std::string& url) {
  std::string_view text = url;
  if (text.empty()) {
    const char* fromEnvironment = std::getenv("LCM_DEFAULT_URL");
    text = fromEnvironment != nullptr ? fromEnvironment : "";
    if (text.empty()) return 0;  // LCM's built-in default: udpm with ttl=0
  }
  constexpr std::string_view kScheme = "udpm://";
  if (text.substr(0, kScheme.size()) != kScheme) return std::nullopt;
  const std::size_t query = text.find('?');
  if (query == std::string_view::npos) return 0;
  std::string_view options = text.substr(query + 1);
  while (!options.empty()) {
    const std::size_t end = options.find('&');
    const std::string_view option = options.substr(0, end);
    if (option.substr(0, 4) == "ttl=") {
      const std::string_view value = option.substr(4);
      int ttl = 0;
      const auto [stop, error] = std::from_chars(value.data(), value.data() + value.size(), ttl);
      if (error != std::errc{} || stop != value.data() + value.size() || ttl < 0) return std::nullopt;
      return ttl;
    }
    if (end == std::string_view::npos) break;
    options.remove_prefix(end + 1);
  }
  return 0;
}

std::string reachWarning(const std::string& url) {
  const std::optional<int> ttl = multicastTtl(url);
  if (ttl && *ttl == 0) return "";
  const std::string shown = url.empty() ? "$LCM_DEFAULT_URL" : "'" + url + "'";
  if (!ttl)
    return "cannot tell how far LCM URL " + shown +
           " reaches; if its traffic leaves this host, anyone on that network can command this server"
           " (LCM has no authentication; see \"Deploying safely\" in docs/server.md)";
  return "LCM URL " + shown + " has ttl=" + std::to_string(*ttl) +
         ": its multicast leaves this host, and anyone on that network can read the state and command"
         " this server (LCM has no authentication or encryption); use it only on an isolated network"
         " (see \"Deploying safely\" in docs/server.md)";
}

}  // namespace rbsim
