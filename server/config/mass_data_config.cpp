#include "config/mass_data_config.h"

#include "rbsim/physics/body_definition.h"

namespace rbsim {

namespace {

// An inertia of 1e12 kg at 1e6 m: the config's own bounds on mass and length.
constexpr double kMaxInertia = 1e24;  // kg·m²
constexpr double kMaxLength = 1e6;    // m

Expected<Mat3> parseInertia(const YamlReader& reader, const YamlNode& node) {
  const NumberRule rule = NumberRule::any(kMaxInertia);
  if (!node.node.IsSequence() || node.node.size() != 3) {
    return reader.error(
        node,
        "expected [Ixx, Iyy, Izz] or [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]] "
        "(kg·m²), got " +
            describeNode(node.node));
  }
  if (!node.node[0].IsSequence()) {
    // The diagonal form: principal moments about the config frame's axes.
    Expected<Vec3> diagonal = reader.vec3(node, rule);
    if (!diagonal) return diagonal.error();
    return Mat3(diagonal->asDiagonal());
  }
  Mat3 inertia;
  for (std::size_t row = 0; row < 3; ++row) {
    Expected<Vec3> values = reader.vec3(node.element(node.node[row], row), rule);
    if (!values) return values.error();
    inertia.row(static_cast<Eigen::Index>(row)) = values->transpose();
  }
  return inertia;
}

}  // namespace

std::optional<Error> parseGivenMassProperties(const YamlReader& reader, const YamlMap& body,
                                              BodyDef& def) {
  const YamlMap::Entry* inertia = body.find("inertia");
  const YamlMap::Entry* centerOfMass = body.find("center_of_mass");
  if (inertia == nullptr && centerOfMass == nullptr) return std::nullopt;
  const YamlMap::Entry& first = inertia != nullptr ? *inertia : *centerOfMass;
  if (def.isStatic) {
    return reader.error(
        first.keyMark, first.value.path,
        "a static body has no mass properties; remove " + first.key + " (or static: true)");
  }
  if (inertia == nullptr) {
    return reader.error(
        centerOfMass->keyMark, centerOfMass->value.path,
        "center_of_mass needs inertia and mass with it (the rule of URDF's <inertial>); "
        "without them the shape gives the mass properties");
  }
  if (!def.mass) {
    return reader.error(inertia->keyMark, inertia->value.path,
                        "inertia needs the body's mass with it (mass: kg, not density)");
  }
  Expected<Mat3> tensor = parseInertia(reader, inertia->value);
  if (!tensor) return tensor.error();
  if (const auto problem = inertiaTensorProblem(*tensor))
    return reader.error(inertia->value, *problem);
  def.inertia = *tensor;
  if (centerOfMass != nullptr) {
    Expected<Vec3> center = reader.vec3(centerOfMass->value, NumberRule::any(kMaxLength));
    if (!center) return center.error();
    def.centerOfMass = *center;
  }
  return std::nullopt;
}

}  // namespace rbsim
