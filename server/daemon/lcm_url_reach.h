#pragma once
// How far an LCM URL's traffic reaches, so that rbserver can say so at start:
// LCM has no authentication, so a server whose multicast leaves the host can
// be commanded by anyone on the network it reaches (docs/server.md,
// "Deploying safely").

#include <optional>
#include <string>

namespace rbsim {

// The multicast time-to-live of a `udpm://` URL: its `ttl` option, or LCM's
// default 0 when absent. Nullopt for other providers (memq://, file://, ...),
// which never leave the process or host, and for an unreadable ttl value.
// An empty URL means $LCM_DEFAULT_URL (or LCM's default), as for lcm_create.
std::optional<int> multicastTtl(const std::string& url);

// A warning for the log when the URL's traffic leaves this host; empty when
// it does not.
std::string reachWarning(const std::string& url);

}  // namespace rbsim
