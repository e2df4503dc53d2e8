// rbserver: the real-time rigid-body simulation server.
#include <sys/prctl.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "config/config_loader.h"
#include "config/server_settings.h"
#include "daemon/lcm_url_reach.h"
#include "daemon/log.h"
#include "daemon/mass_properties_report.h"
#include "daemon/options.h"
#include "daemon/replay_runner.h"
#include "daemon/server.h"
#include "daemon/signal_events.h"
#include "persist/session_checkpoint.h"
#include "rbsim/physics/rotation_drift.h"

using namespace rbsim;

namespace {

// Channel names become exact-match subscriptions (LCM treats them as
// regular expressions): keep the prefix to characters that mean themselves.
bool isPlainChannelPrefix(const std::string& prefix) {
  if (prefix.size() > 40) return false;
  for (const char c : prefix)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const auto options = parseOptions(std::vector<std::string>(argv + 1, argv + argc));
  if (!options) {
    std::fprintf(stderr, "rbserver: %s\n", options.error().message.c_str());
    return 2;
  }
  if (options->help) {
    std::fputs(usage().c_str(), stdout);
    return 0;
  }
  if (options->logLevel) {
    LogLevel level;
    if (!parseLogLevel(*options->logLevel, level)) {
      std::fprintf(stderr, "rbserver: --log-level: expected debug, info, warning or error, got '%s'\n",
                   options->logLevel->c_str());
      return 2;
    }
    setLogLevel(level);
  }

  // One read of the file gives the world and the server's sections.
  auto config = loadConfig(options->configPath);
  if (!config) {
    std::fprintf(stderr, "rbserver: %s\n", config.error().message.c_str());
    return 1;
  }
  auto world = World::fromDef(config->world);
  if (!world) {
    std::fprintf(stderr, "rbserver: %s: %s\n", options->configPath.c_str(),
                 world.error().message.c_str());
    return 1;
  }
  if (options->massProperties) {
    std::fputs(massPropertiesJson(*world).c_str(), stdout);
    return 0;
  }
  if (options->describe) {
    for (const std::string& line : config->robotReport) std::printf("%s\n", line.c_str());
    std::printf("%d bodies, %d joints\n", world->bodyCount(), world->jointCount());
    return 0;
  }
  // The robots' load reports: what each URDF became, and what of it is not used.
  for (const std::string& line : config->robotReport) logInfo("robots: " + line);

  // The command line overrides the file.
  ServerSettings& settings = config->server;
  if (options->realTimeFactor) settings.realTimeFactor = *options->realTimeFactor;
  if (options->duration) settings.duration = *options->duration;
  if (options->lcmUrl) settings.lcmUrl = *options->lcmUrl;
  if (options->channelPrefix) settings.channelPrefix = *options->channelPrefix;
  if (options->recordPath) settings.recordPath = *options->recordPath;
  if (options->stateRate) settings.stateRate = *options->stateRate;
  if (options->startPaused) settings.startPaused = true;
  if (options->readOnly) settings.readOnly = true;
  if (options->allowOtherInstances) settings.allowOtherInstances = true;
  if (options->instanceCheck) settings.instanceCheckSeconds = *options->instanceCheck;
  if (options->checkpointDirectory) settings.checkpointDirectory = *options->checkpointDirectory;
  if (options->checkpointEvery) settings.checkpointEvery = *options->checkpointEvery;
  // The guard's limits live with the server's other limits in the config
  // file; the world (and RESET's copy of it, made from this one) obeys them.
  world->setStateLimits(settings.stateLimits);
  if (options->threads) (void)world->setThreads(*options->threads);  // in range: parseOptions checked
  // Bodies that explicit Euler would spin out of their motion: over the run
  // when it has a duration, else over the next 10 s (a horizon any run
  // reaches soon; the drift only grows after it).
  constexpr double kDriftHorizon = 10.0;  // s of simulated time
  const double driftHorizon = settings.duration.value_or(kDriftHorizon);
  for (const RotationDriftWarning& drift : rotationDriftWarnings(*world, driftHorizon))
    logWarning(drift.message);
  if (!isPlainChannelPrefix(settings.channelPrefix)) {
    std::fprintf(stderr, "rbserver: channel prefix '%s': use at most 40 letters, digits and '_'\n",
                 settings.channelPrefix.c_str());
    return 2;
  }

  const std::string configDirectory =
      std::filesystem::path(options->configPath).parent_path().string();
  // A replay must take the same SPAWN decisions as the recorded server.
  const std::string spawnMeshDirectory =
      settings.spawnMeshDirectory.empty() ? configDirectory : settings.spawnMeshDirectory;
  std::optional<SessionState> resumed;
  if (options->resumePath) {
    auto state = loadSessionCheckpoint(*options->resumePath, world->settings());
    if (!state) {
      std::fprintf(stderr, "rbserver: --resume: %s\n", state.error().message.c_str());
      return 1;
    }
    resumed = std::move(state).value();
  }
  if (options->replayPath)
    return runReplay(*options, settings, std::move(world).value(), spawnMeshDirectory,
                     std::move(resumed), config->visuals, config->sensors);

  // Wake-ups for the step deadlines as close to the deadline as the kernel
  // can: the default 50 µs timer slack would be most of our jitter budget.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);

  SignalEvents signals;
  if (!signals.ok()) {
    std::fprintf(stderr, "rbserver: cannot set up signal handling\n");
    return 1;
  }
  if (const std::string warning = reachWarning(settings.lcmUrl); !warning.empty()) logWarning(warning);
  Server server(settings, std::move(world).value(), spawnMeshDirectory, config->visuals, config->robotPublishing,
                config->sensors);
  const auto opened = server.open();
  if (!opened) {
    std::fprintf(stderr, "rbserver: %s\n", opened.error().message.c_str());
    return 1;
  }
  if (resumed) {
    logInfo("resuming from " + *options->resumePath + " at step " + std::to_string(resumed->world.stepCount()));
    server.resumeFrom(std::move(*resumed));
  }
  return server.run(signals);
}
