#pragma once
// Loading worlds from YAML config files (schema: config/default.yaml).
//
// Errors are Error values, never exceptions, and read like compiler
// messages: "world.yaml:7:15: bodies[2].shape.radius: expected a positive
// number, got "-1"" (1-based line and column, then the key path).
// Loading stops at the first error.

#include <string>

#include "physics/body/body_def.h"
#include "physics/common/expected.h"
#include "physics/world/world_settings.h"

namespace rbsim {

// Reads and parses the file at `path`; mesh files are resolved relative to
// the directory of `path`, and messages name `path` as given.
Expected<WorldDef> loadWorldConfig(const std::string& path);

// Parses a whole world from YAML text. `sourceName` is what messages call
// the text (usually its file name); relative mesh paths are resolved against
// `baseDirectory` (the current directory if empty).
Expected<WorldDef> parseWorldConfig(const std::string& yamlText, const std::string& sourceName,
                                    const std::string& baseDirectory);

// Parses one body, a mapping in the schema of one `bodies:` entry (used to
// spawn bodies sent over LCM). Key paths in messages start at the body's
// keys ("shape.radius").
Expected<BodyDef> parseBodyDef(const std::string& yamlText, const std::string& sourceName,
                               const std::string& baseDirectory);

// The same for a body spawned over the network (SPAWN's spawn_yaml), whose
// sender is not trusted with the server's file system: a mesh file must be a
// relative path to a regular file under `meshDirectory`, with no '..' and no
// symbolic link leading out (config/contained_path.h has the rules). Messages
// name the mesh as the sender did, never by the host's path.
Expected<BodyDef> parseSpawnedBodyDef(const std::string& yamlText, const std::string& sourceName,
                                      const std::string& meshDirectory);

}  // namespace rbsim
