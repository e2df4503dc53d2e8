#pragma once
// The `contact:` section of a world file and a body's `material:`.

#include <optional>

#include "config/yaml_reader.h"
#include "rbsim/physics/types.h"
#include "rbsim/physics/world_settings.h"

namespace rbsim {

// Reads the `contact:` mapping into `config` (absent keys keep their values).
std::optional<Error> parseContactConfig(const YamlReader& reader, const YamlNode& node,
                                        ContactConfig& config);

// Reads a body's {restitution, friction, static_friction}.
Expected<MaterialSpec> parseMaterial(const YamlReader& reader, const YamlNode& node);

}  // namespace rbsim
