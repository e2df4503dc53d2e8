#pragma once
// The server's sections of a config file, `lcm:`, `server:` and `limits:`
// (config/default.yaml documents every key), read from the same parsed
// document as the world, by the config loader: the file is read and parsed
// once (loadConfig in config_loader.h).

#include <filesystem>
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

// `server.viewer_mesh_directory` of the root mapping `root`: the directory
// the viewer's bridge serves the world's visual meshes from (`rbview
// --meshes DIR`), relative to `baseDirectory` (the world file's directory);
// nullopt when absent (then it is the world file's directory). Read before
// the world's robots, whose mesh URLs are relative to it
// (config/robot_config.h); readServerSections accepts the key.
Expected<std::optional<std::filesystem::path>> readViewerMeshDirectory(const YamlReader& reader,
                                                                       const YamlMap& root,
                                                                       const std::filesystem::path& baseDirectory);

}  // namespace rbsim
