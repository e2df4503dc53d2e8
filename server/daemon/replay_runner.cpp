#include "daemon/replay_runner.h"

#include <chrono>
#include <cstdio>
#include <memory>

#include <lcm/lcm-cpp.hpp>

#include "bridge/command_handler.h"
#include "daemon/log.h"
#include "replay/event_recorder.h"
#include "replay/replay.h"
#include "session/session.h"

namespace rbsim {

int runReplay(const Options& options, const ServerSettings& settings, World initialWorld,
              const std::string& spawnMeshDirectory, std::optional<SessionState> resumed,
              BodyVisuals visuals, std::vector<SensorDef> sensors) {
  // The log says which messages were accepted: admission rules that depend
  // on the moment (read-only mode, rate limits) must not second-guess it.
  ServerSettings replaySettings = settings;
  replaySettings.readOnly = false;
  replaySettings.clientRate = 0.0;
  Session session(std::move(initialWorld), settings.startPaused);
  session.setVisuals(std::move(visuals));
  if (resumed)
    session.resumeFrom(std::move(resumed->world), std::move(resumed->wrenches), resumed->worldRevision,
                       resumed->paused, resumed->stepsRequested, std::move(resumed->jointCommands));
  CommandHandler handler(session, replaySettings, spawnMeshDirectory);

  EventRecorder file;
  std::unique_ptr<lcm::LCM> lcm;
  Replay::Output output;
  if (options.replayOutputPath) {
    if (auto opened = file.open(*options.replayOutputPath); !opened) {
      std::fprintf(stderr, "rbserver: --replay-output: %s\n", opened.error().message.c_str());
      return 2;
    }
    output = [&](const std::string& channel, const std::vector<uint8_t>& data, int64_t timestamp) {
      file.write(channel, data.data(), data.size(), timestamp);
    };
  } else if (!options.verify) {
    lcm = std::make_unique<lcm::LCM>(settings.lcmUrl);
    if (!lcm->good()) {
      std::fprintf(stderr, "rbserver: cannot open LCM with URL '%s'\n", settings.lcmUrl.c_str());
      return 2;
    }
    output = [&](const std::string& channel, const std::vector<uint8_t>& data, int64_t) {
      lcm->publish(channel, data.data(), static_cast<unsigned int>(data.size()));
    };
  }

  Replay replay(session, handler, settings.channelPrefix, options.verify, output, std::move(sensors));
  const auto start = std::chrono::steady_clock::now();
  const auto report = replay.run(*options.replayPath);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  file.close();
  if (!report) {
    std::fprintf(stderr, "rbserver: replay: %s\n", report.error().message.c_str());
    return 3;
  }
  if (file.writeErrors() > 0) {
    std::fprintf(stderr, "rbserver: --replay-output: %lld events could not be written\n",
                 static_cast<long long>(file.writeErrors()));
    return 2;
  }
  logInfo("replayed " + std::to_string(report->eventsRead) + " log events: " +
          std::to_string(report->stepsSimulated) + " steps and " +
          std::to_string(report->messagesApplied) + " messages in " + std::to_string(seconds) +
          " s (" + std::to_string(seconds > 0.0 ? static_cast<double>(report->stepsSimulated) / seconds : 0.0) +
          " steps/s)");
  if (report->difference) {
    std::printf("replay differs from the log: %s\n", report->difference->c_str());
    return 1;
  }
  if (options.verify)
    std::printf("replay identical to the log: %lld state pages and %lld joint pages compared, %lld sensor "
                "readings, up to step %lld\n",
                static_cast<long long>(report->pagesCompared), static_cast<long long>(report->jointPagesCompared),
                static_cast<long long>(report->sensorReadingsCompared), static_cast<long long>(report->lastStep));
  return 0;
}

}  // namespace rbsim
