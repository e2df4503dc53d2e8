// rbctl: talk to rbserver from the shell.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "arguments.h"
#include "rbsim/client/client.h"
#include "rbsim/client/lcm_url.h"
#include "verbs.h"

using namespace rbsim;
using namespace rbsim::rbctl;

namespace {

struct GlobalOptions {
  std::string url;
  std::string prefix = client::kDefaultChannelPrefix;
  std::string clientId;  // empty: the library's default
  double timeout = 2.0;  // s
  bool help = false;
};

void printUsage(std::FILE* out) {
  std::fprintf(
      out,
      "usage: rbctl [--url URL] [--prefix P] [--timeout S] [--client-id ID] VERB [ARGS...]\n\n"
      "Talks to rbserver over LCM. Global options may come before or after the verb.\n"
      "  --url URL      LCM URL (default: $LCM_DEFAULT_URL, else %s)\n"
      "  --prefix P     channel prefix (default %s)\n"
      "  --timeout S    seconds to wait for the server's answer (default 2)\n"
      "  --client-id ID the sender id (default: $RBSIM_CLIENT_ID, else cpp-<host>-<pid>);\n"
      "                 reuse one to clear or replace the persistent wrenches of an\n"
      "                 earlier rbctl run\n\n"
      "verbs:\n",
      client::kDefaultUrl, client::kDefaultChannelPrefix);
  for (const Verb& verb : verbs()) std::fprintf(out, "  %-8s %s\n", verb.name, verb.summary);
  std::fprintf(out,
               "\n`rbctl VERB --help` describes a verb. Exit status: 0 done, 1 rejected by the\n"
               "server, 2 bad arguments, 3 no answer within the timeout, 4 LCM unavailable.\n");
}

// Takes the global options out of `arguments`, wherever they are.
GlobalOptions extractGlobalOptions(std::vector<std::string>& arguments) {
  GlobalOptions options;
  std::vector<std::string> rest;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    const std::string& argument = arguments[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= arguments.size()) throw UsageError(argument + ": missing value");
      return arguments[++i];
    };
    if (argument == "--url") {
      options.url = value();
    } else if (argument == "--prefix") {
      options.prefix = value();
    } else if (argument == "--client-id") {
      options.clientId = value();
    } else if (argument == "--timeout") {
      options.timeout = parseNumber(value(), "--timeout");
      if (options.timeout < 0.0 || options.timeout > 86400.0)
        throw UsageError("--timeout: expected seconds between 0 and 86400");
    } else if (argument == "--help" || argument == "-h") {
      options.help = true;
    } else {
      rest.push_back(argument);
    }
  }
  arguments = std::move(rest);
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> arguments(argv + 1, argv + argc);
  GlobalOptions options;
  const Verb* verb = nullptr;
  try {
    options = extractGlobalOptions(arguments);
    if (arguments.empty()) {
      printUsage(options.help ? stdout : stderr);
      return options.help ? kExitOk : kExitUsage;
    }
    for (const Verb& candidate : verbs())
      if (arguments.front() == candidate.name) verb = &candidate;
    if (verb == nullptr)
      throw UsageError("unknown verb '" + arguments.front() + "' (see rbctl --help)");
  } catch (const UsageError& error) {
    std::fprintf(stderr, "rbctl: %s\n", error.what());
    return kExitUsage;
  }
  if (options.help) {
    std::fputs(verb->usage, stdout);
    return kExitOk;
  }

  client::ClientOptions clientOptions;
  clientOptions.url = options.url;
  clientOptions.channelPrefix = options.prefix;
  clientOptions.clientId = options.clientId;
  client::Client client(clientOptions);
  if (!client.good()) {
    std::fprintf(stderr, "rbctl: %s\n", client::explainLcmOpenFailure(client.url()).c_str());
    return kExitNoConnection;
  }
  Context context{client, client::Client::Timeout(std::llround(options.timeout * 1000.0)),
                  clientOptions};
  Arguments verbArguments(std::vector<std::string>(arguments.begin() + 1, arguments.end()));
  try {
    const int status = verb->run(context, verbArguments);
    if (const std::string conflict = client.instanceConflict(); !conflict.empty())
      std::fprintf(stderr, "rbctl: warning: %s\n", conflict.c_str());
    return status;
  } catch (const UsageError& error) {
    std::fprintf(stderr, "rbctl %s: %s (see rbctl %s --help)\n", verb->name, error.what(),
                 verb->name);
    return kExitUsage;
  }
}
