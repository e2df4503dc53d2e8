#pragma once
// The `robots:` list of a world file: robots from URDF descriptions
// (robot/urdf_robot.h), each placed in the world with its joints at their
// initial positions; their bodies and joints are added to the world's under
// the robot's name ("arm/base_link", "arm/shoulder_joint"):
//
//   robots:
//     - name: arm                  # the prefix of its bodies' and joints' names
//       urdf: robots/arm.urdf      # relative to the config file
//       position: [0, 0, 0]        # m: where the root link's frame goes
//       orientation: [1, 0, 0, 0]  # or rpy
//       fixed_base: true           # the root link static (welded to the world)
//       merge_fixed_links: false   # links held by fixed joints as one body
//       joint_positions: {shoulder_joint: 0.3}   # rad or m
//       joint_drives: {shoulder_joint: {stiffness: 200, damping: 20}}  # as a joint's drive:
//                                  # no target: hold where the joint is placed
//       package_paths: [robots]    # where package://NAME/... is looked up
//       self_collision: false      # its links collide with each other (default: no)
//       disable_collisions: [[link1, link3]]   # with self_collision: pairs that never collide
//       link_collision: {gripper: {group: 2, mask: 1}}   # a link's collision group and mask
//                                  # (config/collision_filter_config.h)
//       gravity_compensation: true # every joint's drive adds the gravity torques
//                                  # (JointDrive::gravityCompensation)
//       state_rate: 1000           # Hz: robot_state_t this often (default: with
//                                  # every world state); at most every step
//       state_dynamics: true       # robot_state_t carries M, h, g, link Jacobians
//
// Errors name the world file's line and key, and the URDF's line.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "config/yaml_reader.h"
#include "rbsim/physics/world_settings.h"
#include "robot/robot_publishing.h"
#include "robot/visual.h"

namespace rbsim {

// Whether a body of this name is already in the world.
using BodyNameTaken = std::function<bool(const std::string& name)>;

// Who names the files: the world file (trusted: paths go anywhere) or a
// SPAWN's sender (not trusted: the URDF, its package paths and every mesh
// it names must lie inside the spawn directory, meshio/contained_path.h).
enum class RobotFilePaths { Anywhere, InsideBaseDirectory };

// Reads the list `node`, appends each robot's bodies, joints and pairs of
// bodies excluded from collision to `world`, their visuals to `visuals` and
// its load report (robot/urdf_robot.h) to `report`. Relative paths are
// relative to `baseDirectory`. The viewer's bridge serves visual meshes
// from `meshRouteDirectory` under `meshRoute` (robot/visual.h): a visual
// mesh inside it is published with its URL there. `publishing` gets how
// each robot's state is published (state_rate, state_dynamics).
std::optional<Error> parseRobots(const YamlReader& reader, const YamlNode& node,
                                 const std::filesystem::path& baseDirectory, RobotFilePaths paths,
                                 const BodyNameTaken& taken, WorldDef& world, std::vector<std::string>& report,
                                 const std::string& meshRoute, const std::filesystem::path& meshRouteDirectory,
                                 BodyVisuals& visuals, RobotPublishingMap& publishing);

}  // namespace rbsim
