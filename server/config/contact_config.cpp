#include "config/contact_config.h"

#include <array>
#include <string_view>

namespace rbsim {

namespace {

constexpr std::array<std::string_view, 3> kMaterialKeys = {"restitution", "friction",
                                                           "static_friction"};
constexpr std::array<std::string_view, 25> kContactKeys = {
    "enabled",           "model",
    "backtracking",      "iterations",
    "position_iterations", "stiffness",
    "damping",           "friction_damping",
    "penalty_law",       "restitution",
    "friction",          "static_friction",
    "restitution_threshold", "margin",
    "slop",              "baumgarte",
    "warm_starting",     "epsilon",
    "sleeping",          "sleep_velocity",
    "sleep_time",        "solver",
    "substeps",          "contact_hertz",
    "contact_damping_ratio"};

constexpr double kMaxCoefficient = 100.0;  // friction coefficients beyond this are typos

std::optional<Error> readNumber(const YamlReader& reader, const YamlMap& map,
                                std::string_view key, NumberRule rule, double& value) {
  const auto read = reader.number(map, key, rule, value);
  if (!read) return read.error();
  value = *read;
  return std::nullopt;
}

std::optional<Error> readCount(const YamlReader& reader, const YamlMap& map,
                               std::string_view key, int maximum, int& value) {
  double number = value;
  if (auto error = readNumber(reader, map, key, NumberRule::nonNegative(maximum), number))
    return error;
  if (number != static_cast<double>(static_cast<int>(number)))
    return reader.error(map.find(key)->value, "expected a whole number");
  value = static_cast<int>(number);
  return std::nullopt;
}

}  // namespace

Expected<MaterialSpec> parseMaterial(const YamlReader& reader, const YamlNode& node) {
  const auto map = reader.map(node);
  if (!map) return map.error();
  if (auto error = reader.checkKeys(*map, kMaterialKeys, "a material")) return *error;
  MaterialSpec spec;
  const auto read = [&](std::string_view key, double maximum,
                        std::optional<double>& out) -> std::optional<Error> {
    const YamlMap::Entry* entry = map->find(key);
    if (entry == nullptr) return std::nullopt;
    const auto value = reader.number(entry->value, NumberRule::nonNegative(maximum));
    if (!value) return value.error();
    out = *value;
    return std::nullopt;
  };
  if (auto e = read("restitution", 1.0, spec.restitution)) return *e;
  if (auto e = read("friction", kMaxCoefficient, spec.friction)) return *e;
  if (auto e = read("static_friction", kMaxCoefficient, spec.staticFriction)) return *e;
  if (spec.staticFriction && spec.friction && *spec.staticFriction < *spec.friction)
    return reader.error(map->find("static_friction")->value,
                        "static_friction must not be below friction");
  return spec;
}

std::optional<Error> parseContactConfig(const YamlReader& reader, const YamlNode& node,
                                        ContactConfig& config) {
  const auto map = reader.map(node);
  if (!map) return map.error();
  if (auto error = reader.checkKeys(*map, kContactKeys, "the contact section")) return error;

  const auto enabled = reader.boolean(*map, "enabled", config.enabled);
  if (!enabled) return enabled.error();
  config.enabled = *enabled;
  if (const auto* model = map->find("model")) {
    const auto name = reader.string(model->value);
    if (!name) return name.error();
    const auto kind = contactModelFromName(*name);
    if (!kind) return reader.error(model->value, "expected impulse or penalty, got \"" + *name + "\"");
    config.model = *kind;
  }
  if (const auto* law = map->find("penalty_law")) {
    const auto name = reader.string(law->value);
    if (!name) return name.error();
    const auto kind = penaltyLawFromName(*name);
    if (!kind)
      return reader.error(law->value, "expected clamped or unclamped, got \"" + *name + "\"");
    config.penaltyLaw = *kind;
  }
  if (const auto* solver = map->find("solver")) {
    const auto name = reader.string(solver->value);
    if (!name) return name.error();
    if (*name == "sequential_impulses") {
      config.solver.kind = ContactSolverKind::SequentialImpulses;
    } else if (*name == "soft_step") {
      config.solver.kind = ContactSolverKind::SoftStep;
    } else {
      return reader.error(solver->value, "expected sequential_impulses or soft_step, got \"" + *name + "\"");
    }
  }
  const auto backtracking = reader.boolean(*map, "backtracking", config.backtracking);
  if (!backtracking) return backtracking.error();
  config.backtracking = *backtracking;
  const auto warm = reader.boolean(*map, "warm_starting", config.solver.warmStarting);
  if (!warm) return warm.error();
  config.solver.warmStarting = *warm;
  const auto sleeping = reader.boolean(*map, "sleeping", config.sleeping);
  if (!sleeping) return sleeping.error();
  config.sleeping = *sleeping;

  if (auto e = readCount(reader, *map, "iterations", 1000, config.solver.velocityIterations)) return e;
  if (auto e = readCount(reader, *map, "position_iterations", 1000, config.solver.positionIterations))
    return e;
  if (auto e = readCount(reader, *map, "substeps", 64, config.solver.substeps)) return e;
  if (config.solver.substeps < 1)
    return reader.error(map->find("substeps")->value, "expected at least 1 sub-step");
  struct Field {
    std::string_view key;
    NumberRule rule;
    double* value;
  };
  const std::array<Field, 12> fields = {{
      {"stiffness", NumberRule::positive(1e12), &config.penaltyStiffness},
      {"damping", NumberRule::nonNegative(1e12), &config.penaltyDamping},
      {"friction_damping", NumberRule::nonNegative(1e12), &config.penaltyFrictionDamping},
      {"restitution_threshold", NumberRule::nonNegative(1e3), &config.solver.restitutionThreshold},
      {"margin", NumberRule::nonNegative(1.0), &config.detection.margin},
      {"slop", NumberRule::nonNegative(1.0), &config.solver.linearSlop},
      {"baumgarte", NumberRule::nonNegative(1.0), &config.solver.baumgarte},
      {"epsilon", NumberRule::nonNegative(1e3), &config.classificationEpsilon},
      {"sleep_velocity", NumberRule::nonNegative(1e3), &config.sleepLinearVelocity},
      {"sleep_time", NumberRule::nonNegative(1e6), &config.sleepTime},
      {"contact_hertz", NumberRule::positive(1e6), &config.solver.contactHertz},
      {"contact_damping_ratio", NumberRule::nonNegative(1e3), &config.solver.contactDampingRatio},
  }};
  for (const Field& field : fields)
    if (auto error = readNumber(reader, *map, field.key, field.rule, *field.value)) return error;

  // restitution / friction / static_friction give the default material.
  Material material = config.defaultMaterial;
  if (auto e = readNumber(reader, *map, "restitution", NumberRule::nonNegative(1.0),
                          material.restitution))
    return e;
  if (auto e = readNumber(reader, *map, "friction", NumberRule::nonNegative(kMaxCoefficient),
                          material.friction))
    return e;
  double staticFriction = map->find("static_friction") != nullptr ? material.staticCoefficient()
                                                                  : material.friction;
  if (auto e = readNumber(reader, *map, "static_friction", NumberRule::nonNegative(kMaxCoefficient),
                          staticFriction))
    return e;
  if (staticFriction < material.friction)
    return reader.error(map->find("static_friction")->value,
                        "static_friction must not be below friction");
  material.staticFriction = staticFriction;
  config.defaultMaterial = material;
  return std::nullopt;
}

}  // namespace rbsim
