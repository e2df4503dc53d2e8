#pragma once
// An orientation as a world file writes it: `orientation: [w, x, y, z]` (a
// quaternion, normalised here) or `rpy: [roll, pitch, yaw]` (rad, fixed
// axes x, y, z), not both; the identity when neither is there. Bodies,
// compound parts and robots take it.

#include "config/yaml_reader.h"
#include "rbsim/physics/types.h"

namespace rbsim {

Expected<Quaternion> parseOrientation(const YamlReader& reader, const YamlMap& map);

// Of two entries of one map, the one written later (to point at in "not
// both" messages: the reader has just passed the first).
const YamlMap::Entry& laterEntry(const YamlMap::Entry& a, const YamlMap::Entry& b);

}  // namespace rbsim
