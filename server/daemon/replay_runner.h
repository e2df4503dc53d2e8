#pragma once
// `rbserver --replay LOG`: the session set up as the recorded server had it,
// the replay run into the requested output, a report on stdout. Returns the
// process exit code: 0 done (identical, with --verify), 1 a difference,
// 3 a log that cannot be read or followed, 2 an output that cannot be opened.

#include <optional>
#include <string>

#include "config/server_settings.h"
#include "daemon/options.h"
#include "persist/session_checkpoint.h"
#include "rbsim/physics/world.h"
#include "robot/visual.h"

#include <vector>

#include "sensors/sensor_definition.h"

namespace rbsim {

// `resumed`: the checkpoint the recorded server started from (--resume).
int runReplay(const Options& options, const ServerSettings& settings, World initialWorld,
              const std::string& spawnMeshDirectory, std::optional<SessionState> resumed,
              BodyVisuals visuals = {}, std::vector<SensorDef> sensors = {});

}  // namespace rbsim
