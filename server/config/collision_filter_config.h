#pragma once
// Collision filtering in world files and spawns (rbsim/physics/
// collision_filter.h): a body's group and mask, and a robot's
// self-collision, excluded link pairs and per-link filters.
//
//   bodies:
//     - name: tray
//       collision_group: 2          # the categories it belongs to (bits; default 1)
//       collision_mask: 0xFFFFFFFD  # the categories it collides with (default: all)
//   robots:
//     - name: arm
//       self_collision: true        # its links collide with each other (default false)
//       disable_collisions: [[link1, link3], [link4, link6]]   # not these pairs (SRDF)
//       link_collision: {gripper: {group: 4, mask: 1}}          # a link's group and mask
//
// A group or mask is a whole number from 0 to 4294967295 (0x... in
// hexadecimal), one bit per category. Errors name the file, line, column
// and key path; an unknown link is named with the nearest link the robot has.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config/yaml_reader.h"
#include "rbsim/physics/collision_filter.h"
#include "rbsim/physics/world_settings.h"
#include "robot/urdf_robot.h"

namespace rbsim {

// The keys of a body's filter, for the body's list of keys.
inline constexpr std::string_view kCollisionGroupKey = "collision_group";
inline constexpr std::string_view kCollisionMaskKey = "collision_mask";

// A group or a mask: 32 bits.
Expected<uint32_t> parseCollisionBits(const YamlReader& reader, const YamlNode& node);

// Reads `groupKey` and `maskKey` of `map` into `filter`, which keeps its
// values for absent keys.
std::optional<Error> parseCollisionFilter(const YamlReader& reader, const YamlMap& map, std::string_view groupKey,
                                          std::string_view maskKey, CollisionFilter& filter);

// A robot's `self_collision`, `disable_collisions` and `link_collision`
// keys applied to its model: per-link filters set on the links' bodies,
// and the pairs of its bodies that must not collide appended to `excluded`
// (every pair of its colliding bodies when self-collision is off, else
// the disable_collisions pairs; the pairs its joints join are left out by
// the world itself). The robot's load report says what was done.
std::optional<Error> applyRobotCollisions(const YamlReader& reader, const YamlMap& robot, const std::string& robotName,
                                          RobotModel& model, std::vector<ExcludedPair>& excluded);

}  // namespace rbsim
