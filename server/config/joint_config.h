#pragma once
// The `joints:` list of a world file: joints between the bodies it names
// (rbsim/physics/joint_definition.h), checked here so that every mistake is
// reported at its file, line, column and key.

#include <optional>
#include <vector>

#include "config/yaml_reader.h"
#include "rbsim/physics/body_definition.h"
#include "rbsim/physics/joint_definition.h"

namespace rbsim {

// Reads the list `node` into `joints`; `bodies` are the world's bodies (for
// the names and which are static). Errors: an unknown key or type, a body
// that is not there, a joint naming one body twice or joining nothing that
// moves, a zero axis, lower > upper, a negative effort cap, a key that the
// joint's type does not take, a duplicate joint name, a motor and a drive
// on one joint, a drive with both stiffness and frequency, and negative
// gains, damping or friction.
std::optional<Error> parseJoints(const YamlReader& reader, const YamlNode& node, const std::vector<BodyDef>& bodies,
                                 std::vector<NamedJointDef>& joints);

}  // namespace rbsim
