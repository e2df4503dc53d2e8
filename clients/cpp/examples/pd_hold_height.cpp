// pd_hold_height: holds one body at a target height with a PD controller
// that pushes it through its centre of mass, computed from the states the
// server publishes.
//
//   pd_hold_height [--url URL] [--prefix P] [--client-id ID] [--body NAME] [--height M]
//                  [--frequency HZ] [--damping-ratio Z] [--duration S] [--tolerance M]
//   pd_hold_height --help
//
// The control law works on accelerations, so the gains do not depend on the
// mass: a = ω² (h − z) − 2ζω v_z, with ω = 2π·frequency, and the force adds
// gravity compensation, F = m (a e_z − g), with m and g from the world
// description. It is sent as a persistent world-frame wrench that each new
// state replaces (the server's per-client replacement rule), so the force is
// held between states like a zero-order hold; at exit the wrench is cleared.
//
// Exit status: 0 when the height is within --tolerance of the target at the
// end of --duration s of simulated time, 1 when not, 2 on bad arguments, 3
// when the server does not answer, 130 after SIGINT/SIGTERM.
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>

#include "rbsim/client/client.h"
#include "rbsim/client/lcm_url.h"
#include "rbsim/client/lookup.h"

using namespace std::chrono_literals;
using rbsim::client::Client;

namespace {

volatile std::sig_atomic_t g_stop = 0;  // set by SIGINT/SIGTERM, read by the control loop

void onStopSignal(int) {
  g_stop = 1;
}

struct Options {
  rbsim::client::ClientOptions client;
  std::string body = "bouncy_ball";  // a dynamic body of config/default.yaml
  double height = 1.0;        // m, world z of the centre of mass
  double frequency = 1.0;     // Hz, natural frequency of the closed loop
  double dampingRatio = 1.0;  // 1: critically damped, no overshoot
  double duration = 3.0;      // s of simulated time
  double tolerance = 0.005;   // m
};

constexpr const char* kUsage =
    "usage: pd_hold_height [--url URL] [--prefix P] [--client-id ID] [--body NAME] [--height M]\n"
    "                      [--frequency HZ] [--damping-ratio Z] [--duration S] [--tolerance M]\n";

void printHelp() {
  const Options defaults;
  std::printf(
      "%s\n"
      "Holds a body at a height with a PD law on its acceleration plus gravity\n"
      "compensation, sent as a persistent world-frame force through its centre of mass.\n"
      "  --url URL            LCM URL (default: $LCM_DEFAULT_URL, else %s)\n"
      "  --prefix P           channel prefix (default %s)\n"
      "  --client-id ID       sender id (default: $RBSIM_CLIENT_ID, else cpp-<host>-<pid>)\n"
      "  --body NAME          the dynamic body to hold (default %s)\n"
      "  --height M           m, target world z of its centre of mass (default %g)\n"
      "  --frequency HZ       natural frequency of the closed loop (default %g)\n"
      "  --damping-ratio Z    1 = critically damped (default %g)\n"
      "  --duration S         s of simulated time to control for (default %g)\n"
      "  --tolerance M        m, final error for exit status 0 (default %g)\n\n"
      "Exit status: 0 within tolerance, 1 not (or a wrench rejected), 2 bad arguments or\n"
      "no such dynamic body, 3 no answer from the server, 130 interrupted.\n",
      kUsage, rbsim::client::kDefaultUrl, rbsim::client::kDefaultChannelPrefix,
      defaults.body.c_str(), defaults.height, defaults.frequency, defaults.dampingRatio,
      defaults.duration, defaults.tolerance);
}

[[noreturn]] void usageError(const std::string& message) {
  std::fprintf(stderr, "pd_hold_height: %s\n%s", message.c_str(), kUsage);
  std::exit(2);
}

Options parseOptions(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string option = argv[i];
    if (option == "--help" || option == "-h") {
      printHelp();
      std::exit(0);
    }
    if (i + 1 >= argc) usageError(option + ": missing value");
    const std::string value = argv[++i];
    const auto number = [&] {
      char* end = nullptr;
      const double parsed = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !std::isfinite(parsed))
        usageError(option + ": expected a number, got '" + value + "'");
      return parsed;
    };
    if (option == "--url") {
      options.client.url = value;
    } else if (option == "--prefix") {
      options.client.channelPrefix = value;
    } else if (option == "--client-id") {
      options.client.clientId = value;
    } else if (option == "--body") {
      options.body = value;
    } else if (option == "--height") {
      options.height = number();
    } else if (option == "--frequency") {
      options.frequency = number();
    } else if (option == "--damping-ratio") {
      options.dampingRatio = number();
    } else if (option == "--duration") {
      options.duration = number();
    } else if (option == "--tolerance") {
      options.tolerance = number();
    } else {
      usageError("unknown option '" + option + "'");
    }
  }
  if (options.frequency <= 0.0 || options.dampingRatio < 0.0 || options.duration <= 0.0)
    usageError("--frequency and --duration must be positive, --damping-ratio not negative");
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parseOptions(argc, argv);
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);

  Client client(options.client);
  if (!client.good()) {
    std::fprintf(stderr, "pd_hold_height: %s\n",
                 rbsim::client::explainLcmOpenFailure(client.url()).c_str());
    return 3;
  }

  // Mass and gravity come from the world description: ask for it once a
  // state shows the server is up (a request sent before it subscribed is lost).
  if (client.spinUntil([&] { return client.latestState().has_value(); }, 3s)) client.publishWorld();
  if (!client.spinUntil([&] { return client.world() && client.latestState(); }, 3s)) {
    std::fprintf(stderr, "pd_hold_height: no world description and state from the server\n");
    return 3;
  }
  const auto* description = rbsim::client::findBody(*client.world(), options.body);
  if (description == nullptr || description->is_static) {
    std::fprintf(stderr, "pd_hold_height: no dynamic body named '%s'\n", options.body.c_str());
    return 2;
  }
  const double mass = description->mass;
  const double* gravity = client.world()->gravity;
  const double omega = 2.0 * std::numbers::pi * options.frequency;
  const double kp = omega * omega;                       // 1/s²
  const double kd = 2.0 * options.dampingRatio * omega;  // 1/s

  int64_t lastStep = -1;
  double startTime = NAN;
  double height = NAN;
  int rejected = 0;
  client.onAck([&](const rbsim::ack_t& ack) {
    if (ack.client == client.clientId() && !ack.accepted && rejected++ == 0)
      std::fprintf(stderr, "pd_hold_height: wrench rejected: %s\n", ack.reason.c_str());
  });
  client.onState([&](const rbsim::world_state_t& state) {
    if (state.step == lastStep) return;  // republished while paused: nothing new to react to
    lastStep = state.step;
    const auto* body = rbsim::client::findBody(state, options.body);
    if (body == nullptr) return;
    if (std::isnan(startTime)) startTime = state.sim_time;
    height = body->position[2];
    const double acceleration = kp * (options.height - height) - kd * body->linear_velocity[2];
    rbsim::client::Wrench wrench;
    wrench.body = options.body;
    wrench.mode = rbsim::client::WrenchMode::Persistent;
    wrench.frame = rbsim::client::Frame::World;
    wrench.force = {-mass * gravity[0], -mass * gravity[1], mass * (acceleration - gravity[2])};
    // No point: through the centre of mass (placed there exactly by the
    // server), so the push does not spin the body.
    client.applyWrench(wrench);
  });

  const auto finished = [&] {
    return g_stop != 0 || (!std::isnan(startTime) &&
                           client.latestState()->sim_time - startTime >= options.duration);
  };
  // Simulated time may run slower than wall time; allow it 10× plus slack.
  const auto wallLimit = std::chrono::milliseconds(std::llround(options.duration * 10000.0)) + 5s;
  const bool done = client.spinUntil(finished, wallLimit);

  const auto clear = client.waitForAck(client.clearWrenches(options.body), 2s);
  if (!clear || !clear->accepted)
    std::fprintf(stderr, "pd_hold_height: could not clear the wrench\n");
  if (g_stop != 0) {
    std::fprintf(stderr, "pd_hold_height: interrupted; wrench cleared\n");
    return 130;
  }
  if (!done || std::isnan(height)) {
    std::fprintf(stderr, "pd_hold_height: the simulation did not run for %.3g s\n",
                 options.duration);
    return 3;
  }
  const double error = height - options.height;
  std::printf("final height %.9g m target %.9g m error %.3g m after %.3g s (%d rejected)\n", height,
              options.height, error, client.latestState()->sim_time - startTime, rejected);
  return std::abs(error) <= options.tolerance && rejected == 0 ? 0 : 1;
}
