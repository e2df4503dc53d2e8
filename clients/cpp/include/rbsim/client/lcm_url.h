#pragma once
// Why LCM could not open a URL, as far as the URL itself tells: a malformed
// udpm:// URL is named as such, and only a well-formed one gets the hint
// about a multicast route (lcm_create fails on both the same way). The
// Python client applies the same rules (clients/python/rbsim/lcm_url.py).

#include <optional>
#include <string>

namespace rbsim::client {

// What is wrong with `url` by itself (udpm://GROUP:PORT?ttl=N&recv_buf_size=B,
// GROUP an IPv4 multicast address), or nullopt if it looks well formed.
std::optional<std::string> lcmUrlProblem(const std::string& url);

// One sentence for "LCM could not open `url`".
std::string explainLcmOpenFailure(const std::string& url);

}  // namespace rbsim::client
