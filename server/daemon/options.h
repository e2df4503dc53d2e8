#pragma once
// rbserver's command line.

#include <optional>
#include <string>
#include <vector>

#include "rbsim/physics/types.h"

namespace rbsim {

struct Options {
  std::string configPath;
  bool massProperties = false;
  bool describe = false;  // print what the robots were made into and exit
  bool help = false;
  std::optional<double> realTimeFactor;
  std::optional<double> duration;  // s of simulated time
  std::optional<std::string> lcmUrl;
  std::optional<std::string> channelPrefix;
  std::optional<std::string> recordPath;
  std::optional<double> stateRate;  // Hz
  std::optional<int> threads;       // the step's threads (world.threads); 0: one per core
  std::optional<std::string> logLevel;
  bool startPaused = false;
  bool readOnly = false;
  bool allowOtherInstances = false;
  std::optional<double> instanceCheck;  // s
  std::optional<std::string> checkpointDirectory;
  std::optional<double> checkpointEvery;  // s of simulated time
  std::optional<std::string> resumePath;  // a checkpoint file to start from
  // Replay of a recorded session instead of serving (see replay.h).
  std::optional<std::string> replayPath;
  std::optional<std::string> replayOutputPath;
  bool verify = false;
};

// Parses argv[1..]; errors say which argument is wrong and why.
Expected<Options> parseOptions(const std::vector<std::string>& arguments);

std::string usage();

}  // namespace rbsim
