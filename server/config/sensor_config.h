#pragma once
// The `sensors:` list of a world file (sensors/sensor_definition.h): each
// sensor checked against the world's bodies and joints, so that every
// mistake is reported at its file, line, column and key, with the sensor's
// name.

#include <optional>
#include <vector>

#include "config/yaml_reader.h"
#include "rbsim/physics/world_settings.h"
#include "sensors/sensor_definition.h"

namespace rbsim {

// Reads the list `node` into `sensors`. `world` is the file's world (its
// bodies, robots' links and joints, and its dt, which bounds the rates).
// Errors: an unknown key or type, a missing or duplicate name or one that
// cannot name a channel, an unknown body, robot link or joint, a rate that
// is not positive or above the world's step rate, a bad pose, negative
// noise, and scan patterns out of bounds.
std::optional<Error> parseSensors(const YamlReader& reader, const YamlNode& node, const WorldDef& world,
                                  std::vector<SensorDef>& sensors);

}  // namespace rbsim
