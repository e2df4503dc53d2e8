#pragma once
// The server's sections of a config file, `lcm:`, `server:` and `limits:`
// (config/default.yaml documents every key), read from the same parsed
// document as the world, by the config loader: the file is read and parsed
// once (loadConfig in config_loader.h).

#include <optional>

#include "config/server_settings.h"
#include "config/yaml_reader.h"
#include "rbsim/physics/types.h"

namespace rbsim {

// Reads the sections present in the root mapping `root` into `settings`
// (absent sections and keys keep the values `settings` has). Relative
// directories (checkpoint_dir, spawn_mesh_directory) are taken relative to
// the directory of `reader.sourceName()`, the config file. The first error,
// if any, names file, line, column and key path ("limits.max_force").
std::optional<Error> readServerSections(const YamlReader& reader, const YamlMap& root,
                                        ServerSettings& settings);

}  // namespace rbsim
