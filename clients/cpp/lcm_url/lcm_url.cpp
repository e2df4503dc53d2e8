#include "rbsim/client/lcm_url.h"

#include <arpa/inet.h>

#include <array>
#include <cctype>
#include <cstdlib>

namespace rbsim::client {

namespace {

constexpr const char* kRouteHint =
    "is there a route for multicast? e.g. `ip route add 224.0.0.0/4 dev lo`";

bool allDigits(const std::string& text) {
  if (text.empty() || text.size() > 9) return false;
  for (const char c : text)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

}  // namespace

std::optional<std::string> lcmUrlProblem(const std::string& url) {
  const auto separator = url.find("://");
  if (separator == std::string::npos)
    return "not an LCM URL (expected PROVIDER://..., e.g. udpm://239.255.76.67:7667?ttl=0)";
  const std::string provider = url.substr(0, separator);
  const std::array<const char*, 5> known = {"udpm", "memq", "file", "tcpq", "mpudpm"};
  bool isKnown = false;
  for (const char* name : known) isKnown = isKnown || provider == name;
  if (!isKnown)
    return "unknown LCM provider '" + provider + "' (udpm, memq, file, tcpq or mpudpm)";
  if (provider != "udpm") return std::nullopt;

  const std::string rest = url.substr(separator + 3);
  const auto question = rest.find('?');
  const std::string address = rest.substr(0, question);
  const std::string options = question == std::string::npos ? "" : rest.substr(question + 1);
  const auto colon = address.rfind(':');
  const std::string host = colon == std::string::npos ? address : address.substr(0, colon);
  const std::string port = colon == std::string::npos ? "7667" : address.substr(colon + 1);
  in_addr group{};
  if (inet_pton(AF_INET, host.c_str(), &group) != 1)
    return "udpm address '" + host + "' is not an IPv4 address";
  if (!IN_MULTICAST(ntohl(group.s_addr)))
    return "udpm address " + host + " is not a multicast group (224.0.0.0 to 239.255.255.255)";
  if (!allDigits(port) || std::atoi(port.c_str()) < 1 || std::atoi(port.c_str()) > 65535)
    return "udpm port '" + port + "' is not a number from 1 to 65535";
  std::size_t start = 0;
  while (start <= options.size() && !options.empty()) {
    const auto end = options.find('&', start);
    const std::string option = options.substr(start, end == std::string::npos ? end : end - start);
    const auto equals = option.find('=');
    const std::string key = option.substr(0, equals);
    const std::string value = equals == std::string::npos ? "" : option.substr(equals + 1);
    if (key == "ttl" && (!allDigits(value) || std::atoi(value.c_str()) > 255))
      return "ttl '" + value + "' is not a number from 0 to 255";
    if (key == "recv_buf_size" && !allDigits(value))
      return "recv_buf_size '" + value + "' is not a number of bytes";
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return std::nullopt;
}

std::string explainLcmOpenFailure(const std::string& url) {
  if (const auto problem = lcmUrlProblem(url))
    return "cannot open LCM with URL '" + url + "': " + *problem;
  if (url.rfind("udpm://", 0) == 0)
    return "cannot open LCM with URL '" + url + "' (" + kRouteHint + ")";
  return "cannot open LCM with URL '" + url + "'";
}

}  // namespace rbsim::client
