#pragma once
// A whole session as a checkpoint payload: the world (World::encodeSnapshot),
// the wrenches pending and acting with all their parameters (an acting
// wrench whose point was given in the world holds the body point it was
// fixed to when it first acted), the joint commands scheduled for later
// steps, the pause state and STEPs still to take, and the world revision.
// A session restored from it continues bit-identically.
//
// Payload (little-endian): "RBSS", version, world revision, paused, steps
// requested, the world snapshot, the pending and the active wrenches, then
// the pending joint commands.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rbsim/physics/types.h"
#include "session/session.h"

namespace rbsim {

struct SessionState {
  World world;
  WrenchScheduler wrenches;
  std::vector<JointCommandRequest> jointCommands;  // accepted, not yet due
  int64_t worldRevision = 1;
  bool paused = false;
  int64_t stepsRequested = 0;
};

Expected<std::vector<uint8_t>> encodeSessionCheckpoint(const Session& session);
// `settings`: the config's world settings (they must match the saved ones).
Expected<SessionState> decodeSessionCheckpoint(std::span<const uint8_t> payload, const WorldSettings& settings);

// Whole files: the container of checkpoint_file.h around the payload.
Expected<bool> saveSessionCheckpoint(const Session& session, const std::string& path);
// `noFollow`: refuse a symbolic link (for names that come from clients).
Expected<SessionState> loadSessionCheckpoint(const std::string& path, const WorldSettings& settings,
                                             bool noFollow = false);

}  // namespace rbsim
