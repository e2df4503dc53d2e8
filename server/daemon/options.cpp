#include "daemon/options.h"

#include "rbsim/physics/world_settings.h"

#include <cmath>
#include <cstdlib>

namespace rbsim {

namespace {

Expected<double> parseNumber(const std::string& option, const std::string& text, bool allowZero) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value) || value < 0.0 ||
      (!allowZero && value == 0.0))
    return Error{option + ": expected a " + (allowZero ? "non-negative" : "positive") +
                 " number, got '" + text + "'"};
  return value;
}

}  // namespace

std::string usage() {
  return R"(usage: rbserver --config FILE [options]

Real-time rigid-body simulation server on LCM. Loads the world in FILE,
steps it at its fixed dt paced to the wall clock, publishes RBSIM_STATE,
RBSIM_STATUS, RBSIM_WORLD, RBSIM_CONTACTS and RBSIM_ACK, and takes RBSIM_WRENCH and
RBSIM_COMMAND from clients. SIGINT/SIGTERM stop it cleanly.

options (each overrides the config file's key):
  --config FILE            world and server settings (YAML), required
  --mass-properties        print every body's mass properties as JSON and exit
  --describe               print what the robots (robots:) were made into, and every URDF
                           element not used, by file and line, and exit
  --real-time-factor X     simulated s per wall s; 0 = as fast as possible (server.real_time_factor)
  --duration S             stop after S s of simulated time (server.duration)
  --lcm-url URL            LCM provider URL (lcm.url)
  --channel-prefix P       channel name prefix, default RBSIM_ (lcm.channel_prefix)
  --state-rate HZ          RBSIM_STATE rate in Hz of simulated time; 0 = every step (lcm.state_rate)
  --threads N              threads that share each step, 0 = one per core (world.threads);
                           every count gives the same results, bit for bit
  --record FILE            write every published and received message to an LCM log (server.record)
  --paused                 start paused (server.start_paused)
  --read-only              reject every wrench and command (with an ack saying so); state,
                           status and world are still published (server.read_only)
  --checkpoint-dir DIR     where SAVE_CHECKPOINT, RESET with a path and periodic checkpoints
                           put and find their files; clients can only name plain files in
                           it (server.checkpoint_dir; none: checkpoints disabled)
  --checkpoint-every S     write the whole session to DIR/periodic.rbck every S s of
                           simulated time, atomically (server.checkpoint_every; 0 = never)
  --resume FILE            start from the checkpoint FILE instead of the config's world
                           (the config's dt, gravity, integrator and contact model must match)
  --log-level LEVEL        debug, info, warning or error (default info)
  --instance-check S       listen S s (default 0.25) on the channel prefix before publishing;
                           another server heard there makes rbserver refuse to start, since two
                           servers on one prefix interleave their states (0: no check)
  --allow-other-instances  warn about another server on the prefix and run anyway

replay (instead of serving; as fast as possible, no pacing):
  --replay LOG             re-simulate the session recorded in LOG (an rbserver --record
                           file or an lcm-logger log of the bus), applying the wrenches
                           and commands the server accepted at the steps it handled them;
                           the states go to --replay-output, or are published on LCM
                           when neither --replay-output nor --verify is given
  --resume FILE            (with --replay) the checkpoint the recorded server resumed from
  --replay-output FILE     write the replayed states and world descriptions to an LCM log
  --verify                 compare every replayed state with the log's, bit for bit; exit 1
                           naming the first step and body that differ (and by how much),
                           0 when identical; 3 when the log cannot be read or followed
                           (2: the output cannot be opened)
  --help                   this text
)";
}

Expected<Options> parseOptions(const std::vector<std::string>& arguments) {
  Options options;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    const std::string& arg = arguments[i];
    const auto value = [&]() -> Expected<std::string> {
      if (i + 1 >= arguments.size()) return Error{arg + ": missing value"};
      return arguments[++i];
    };
    if (arg == "--help" || arg == "-h") {
      options.help = true;
    } else if (arg == "--mass-properties") {
      options.massProperties = true;
    } else if (arg == "--describe") {
      options.describe = true;
    } else if (arg == "--paused") {
      options.startPaused = true;
    } else if (arg == "--read-only") {
      options.readOnly = true;
    } else if (arg == "--allow-other-instances") {
      options.allowOtherInstances = true;
    } else if (arg == "--verify") {
      options.verify = true;
    } else if (arg == "--config" || arg == "--lcm-url" || arg == "--channel-prefix" ||
               arg == "--record" || arg == "--log-level" || arg == "--real-time-factor" ||
               arg == "--duration" || arg == "--state-rate" || arg == "--replay" ||
               arg == "--replay-output" || arg == "--checkpoint-dir" || arg == "--checkpoint-every" ||
               arg == "--resume" || arg == "--instance-check" || arg == "--threads") {
      const auto text = value();
      if (!text) return text.error();
      if (arg == "--config") options.configPath = *text;
      if (arg == "--lcm-url") options.lcmUrl = *text;
      if (arg == "--channel-prefix") options.channelPrefix = *text;
      if (arg == "--record") options.recordPath = *text;
      if (arg == "--log-level") options.logLevel = *text;
      if (arg == "--replay") options.replayPath = *text;
      if (arg == "--checkpoint-dir") options.checkpointDirectory = *text;
      if (arg == "--resume") options.resumePath = *text;
      if (arg == "--checkpoint-every") {
        const auto number = parseNumber(arg, *text, true);
        if (!number) return number.error();
        options.checkpointEvery = *number;
      }
      if (arg == "--replay-output") options.replayOutputPath = *text;
      if (arg == "--instance-check") {
        const auto number = parseNumber(arg, *text, true);
        if (!number) return number.error();
        if (*number > 60.0) return Error{"--instance-check: at most 60 s, got " + *text};
        options.instanceCheck = *number;
      }
      if (arg == "--real-time-factor" || arg == "--state-rate") {
        const auto number = parseNumber(arg, *text, true);
        if (!number) return number.error();
        (arg == "--real-time-factor" ? options.realTimeFactor : options.stateRate) = *number;
      }
      if (arg == "--threads") {
        const auto number = parseNumber(arg, *text, true);
        if (!number) return number.error();
        if (*number != static_cast<double>(static_cast<int>(*number)) || *number > kMaxThreads)
          return Error{"--threads: a whole number from 0 (one per core) to " + std::to_string(kMaxThreads) +
                       ", got " + *text};
        options.threads = static_cast<int>(*number);
      }
      if (arg == "--duration") {
        const auto number = parseNumber(arg, *text, false);
        if (!number) return number.error();
        options.duration = *number;
      }
    } else {
      return Error{"unknown argument '" + arg + "' (see --help)"};
    }
  }
  if (!options.help && options.configPath.empty()) return Error{"--config FILE is required (see --help)"};
  if (!options.replayPath && (options.verify || options.replayOutputPath))
    return Error{"--verify and --replay-output need --replay LOG"};
  return options;
}

}  // namespace rbsim
