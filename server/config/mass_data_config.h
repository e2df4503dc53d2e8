#pragma once
// A body's mass properties given as data: `center_of_mass` and `inertia`
// (with `mass`), as URDF <inertial>, SDF <inertial> and MJCF <inertial> give
// them from CAD.

#include <optional>

#include "config/yaml_reader.h"
#include "rbsim/physics/body_definition.h"
#include "rbsim/physics/types.h"

namespace rbsim {

// Reads `inertia` ([[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]] or
// [Ixx, Iyy, Izz], kg·m², about the centre of mass in the axes of the body's
// config frame) and `center_of_mass` ([x, y, z], m, config frame) of the
// body mapping `body` into `def`, whose mass and static flag are already
// read. The rules: `inertia` requires `mass`, `center_of_mass` requires
// `inertia`, neither on a static body; the tensor must be one a rigid body
// can have (inertiaTensorProblem). Errors point at the offending key.
std::optional<Error> parseGivenMassProperties(const YamlReader& reader, const YamlMap& body,
                                              BodyDef& def);

}  // namespace rbsim
