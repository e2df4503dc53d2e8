#pragma once
// The `joints:` list of a world file: joints between the bodies it names
// (rbsim/physics/joint_definition.h), checked here so that every mistake is
// reported at its file, line, column and key.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "config/yaml_reader.h"
#include "rbsim/physics/joint_definition.h"

namespace rbsim {

// Which bodies a joint may name: for a name, whether that body moves (false:
// static), or nullopt when there is no body of that name.
using JointBodyLookup = std::function<std::optional<bool>(const std::string& name)>;
// The names of the bodies a joint may name, for "did you mean" when one
// names none of them (may be empty: no suggestions).
using JointBodyNames = std::function<std::vector<std::string>()>;

// Reads the list `node` into `joints`; `bodies` says which bodies there are
// (a world file's, or a spawn's with the world's). Errors: an unknown key or
// type, a body that is not there, a joint naming one body twice or joining
// nothing that moves, a zero axis, lower > upper, a negative effort cap, a
// key that the joint's type does not take, a duplicate joint name, a motor
// and a drive on one joint, a drive with both stiffness and frequency, and
// negative gains, damping or friction.
std::optional<Error> parseJoints(const YamlReader& reader, const YamlNode& node, const JointBodyLookup& bodies,
                                 std::vector<NamedJointDef>& joints, const JointBodyNames& bodyNames = {});

// A joint's `drive:` map as a joint in `joints:` takes it: {target,
// stiffness, damping} or {target, frequency, damping_ratio}, and
// max_effort; a target not given is 0.
Expected<JointDrive> parseJointDrive(const YamlReader& reader, const YamlNode& node);

}  // namespace rbsim
