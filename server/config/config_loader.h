#pragma once
// Loading YAML config files (schema: config/default.yaml): the world and the
// server's own sections, from one read and one parse of the file.
//
// Errors are Error values, never exceptions, and read like compiler
// messages: "world.yaml:7:15: bodies[2].shape.radius: expected a positive
// number, got "-1"" (1-based line and column, then the key path).
// Loading stops at the first error.

#include <string>
#include <vector>

#include "config/joint_config.h"
#include "config/server_settings.h"
#include "rbsim/physics/body_definition.h"
#include "rbsim/physics/types.h"
#include "rbsim/physics/world_settings.h"
#include "robot/robot_publishing.h"
#include "robot/visual.h"
#include "sensors/sensor_definition.h"

namespace rbsim {

// Everything a config file says.
struct Config {
  WorldDef world;
  // The `lcm:`, `server:` and `limits:` sections (defaults where absent),
  // before rbserver applies its command line.
  ServerSettings server;
  // What the `robots:` were made into and what of their URDFs was not
  // used, one line each (robot/urdf_robot.h), for rbserver --describe and
  // its start-up log.
  std::vector<std::string> robotReport;
  // How the robots' bodies look (robot/visual.h), by body name: drawing
  // only, published in world_t beside the bodies.
  BodyVisuals visuals;
  // How each robot's state is published (state_rate, state_dynamics).
  RobotPublishingMap robotPublishing;
  // The `sensors:` (config/sensor_config.h), in the file's order.
  std::vector<SensorDef> sensors;
};

// Reads and parses the file at `path`, the world and the server's sections
// in one pass; relative paths in it (meshes, checkpoint_dir,
// spawn_mesh_directory) are relative to the directory of `path`, and
// messages name `path` as given.
Expected<Config> loadConfig(const std::string& path);

// The same from YAML text (`sourceName` and `baseDirectory` as for
// parseWorldConfig; the server's relative directories are taken relative to
// the directory of `sourceName`).
Expected<Config> parseConfig(const std::string& yamlText, const std::string& sourceName,
                             const std::string& baseDirectory);

// Only the world of the file at `path`, for tools and tests that need no
// server: the server's sections may be there but are not read. Mesh files
// are resolved relative to the directory of `path`, and messages name
// `path` as given.
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

// What one SPAWN adds (command_t.spawn_yaml): bodies, and joints among them,
// the world's bodies and the world.
struct SpawnDef {
  std::vector<BodyDef> bodies;  // the spawn's bodies, then its robots' links
  std::vector<NamedJointDef> joints;  // its robots' joints, then the spawn's own
  std::vector<ExcludedPair> excludedPairs;  // pairs of its robots' bodies that never collide
  std::vector<std::string> robotReport;  // what the robots were made into (robot/urdf_robot.h)
  BodyVisuals visuals;  // how its robots' bodies look, by body name (robot/visual.h)
  RobotPublishingMap robotPublishing;  // how its robots' states are published
};

// Parses a spawn: either one body (a mapping in the schema of a `bodies:`
// entry) or a mapping with `bodies:`, `robots:` and `joints:` lists, as a
// world file has them (any may be absent). `existing` names the world's
// bodies: a new body may not take one of their names, and a joint may join
// them. The sender is not trusted with the server's file system: a mesh
// file, a robot's URDF and every file the URDF names must be a relative
// path to a regular file under `meshDirectory`, with no '..' and no
// symbolic link leading out (meshio/contained_path.h has the rules), and
// ROS_PACKAGE_PATH is not consulted. Messages name files as the sender did,
// never by the host's path.
// `existingNames` lists the world's bodies for "did you mean" when a joint
// names no body (may be empty).
Expected<SpawnDef> parseSpawnDef(const std::string& yamlText, const std::string& sourceName,
                                 const std::string& meshDirectory, const JointBodyLookup& existing,
                                 const JointBodyNames& existingNames = {});

}  // namespace rbsim
