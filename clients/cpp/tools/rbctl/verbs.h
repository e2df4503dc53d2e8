#pragma once
// rbctl's verbs: each one sends its request (or waits for what it prints) and
// turns the outcome into an exit code.

#include <string>
#include <vector>

#include "arguments.h"
#include "rbsim/client/client.h"

namespace rbsim::rbctl {

// Exit codes, the same for every verb.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRejected = 1;      // the server answered no
inline constexpr int kExitUsage = 2;         // bad arguments
inline constexpr int kExitNoAnswer = 3;      // nothing within --timeout
inline constexpr int kExitNoConnection = 4;  // LCM could not be opened

struct Context {
  client::Client& client;
  client::Client::Timeout timeout;
  // The client's URL, prefix and id, for the verbs that open a connection
  // of their own (robot: a client::Robot).
  const client::ClientOptions& options;
};

struct Verb {
  const char* name;
  const char* summary;  // one line for `rbctl --help`
  const char* usage;    // `rbctl VERB --help`
  int (*run)(Context& context, Arguments& arguments);
};

const std::vector<Verb>& verbs();

}  // namespace rbsim::rbctl
