#pragma once
// Where a client connects and how it names itself when not told.

#include <string>

namespace rbsim::client {

// rbserver's default URL (multicast that never leaves the host) with a 2 MiB
// kernel receive buffer: a client that falls behind for a moment then keeps
// the states instead of losing them (the receiver's buffer is what counts:
// docs/lcm.md, "Kernel receive buffers").
inline constexpr const char* kDefaultUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152";
inline constexpr const char* kDefaultChannelPrefix = "RBSIM_";

// `url` if not empty, else $LCM_DEFAULT_URL if set and not empty, else kDefaultUrl.
std::string resolveLcmUrl(const std::string& url);

// "cpp-<hostname>-<pid>" for the first call in a process, then
// "cpp-<hostname>-<pid>-2", "-3", ...: every Client of a process gets its own
// id, so that acks, CLEAR and the persistent-wrench replacement rule (all per
// client id on the server) never mix two of them up.
std::string makeDefaultClientId();

// The client id a Client takes when ClientOptions::clientId is empty:
// $RBSIM_CLIENT_ID if set and not empty (a name that persists across runs,
// so that a later run may CLEAR or replace an earlier run's persistent
// wrenches), else makeDefaultClientId().
std::string resolveClientId(const std::string& clientId);

}  // namespace rbsim::client
