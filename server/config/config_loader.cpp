#include "config/config_loader.h"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <utility>

#include "config/collision_filter_config.h"
#include "config/contact_config.h"
#include "config/joint_config.h"
#include "config/orientation_config.h"
#include "config/robot_config.h"
#include "meshio/contained_path.h"
#include "meshio/height_grid.h"
#include "config/mass_data_config.h"
#include "config/sensor_config.h"
#include "config/server_sections.h"
#include "config/yaml_document_count.h"
#include "config/yaml_reader.h"
#include "meshio/mesh_io.h"
#include "rbsim/physics/shapes.h"

namespace rbsim {

namespace {

// Bounds that no sensible world comes near: they catch typos ("1e60") and
// values for which the double arithmetic of the engine stops meaning much.
constexpr double kMaxLength = 1e6;               // m: sizes, coordinates, plane offsets
constexpr double kMaxDt = 1.0;                   // s
constexpr double kMaxAcceleration = 1e4;         // m/s², gravity components (~1000 g)
constexpr double kMaxLinearSpeed = 1e5;          // m/s, per component
constexpr double kMaxAngularSpeed = 1e5;         // rad/s, per component
constexpr double kMaxMass = 1e12;                // kg
constexpr double kMaxDensity = 1e6;              // kg/m³ (osmium is 2.26e4)
constexpr double kMaxDamping = 1e6;              // 1/s
constexpr double kMinNorm = 1e-9;            // below this a quaternion or normal has no direction
constexpr std::size_t kMaxNameLength = 128;  // characters, body names

constexpr std::array<std::string_view, 9> kTopLevelKeys = {
    "world", "bodies", "robots", "joints", "contact",
    // Read with the server's settings (parseConfig, sensor_config.cpp).
    "sensors",
    // The server's settings (server_sections.cpp).
    "lcm", "server", "limits"};
constexpr std::array<std::string_view, 3> kSpawnKeys = {"bodies", "robots", "joints"};
constexpr std::array<std::string_view, 5> kWorldKeys = {"dt", "gravity", "integrator", "damping", "threads"};
constexpr std::array<std::string_view, 2> kDampingKeys = {"linear", "angular"};
constexpr std::array<std::string_view, 18> kBodyKeys = {
    "name",     "shape",       "mass", "density",         "center_of_mass",   "inertia",
    "position", "orientation", "rpy",  "linear_velocity", "angular_velocity", "static",
    "damping",  "material",    "ccd",  "collides",        kCollisionGroupKey, kCollisionMaskKey};

constexpr std::array<std::string_view, 2> kSphereKeys = {"type", "radius"};
constexpr std::array<std::string_view, 2> kBoxKeys = {"type", "half_extents"};
constexpr std::array<std::string_view, 3> kCylinderKeys = {"type", "radius", "half_length"};
constexpr std::array<std::string_view, 2> kMeshKeys = {"type", "file"};
constexpr std::array<std::string_view, 6> kHeightfieldKeys = {"type", "file", "heights", "cell_size",
                                                              "height_scale", "height_offset"};
constexpr std::array<std::string_view, 3> kPlaneKeys = {"type", "normal", "offset"};
constexpr std::array<std::string_view, 2> kCompoundKeys = {"type", "shapes"};
constexpr std::array<std::string_view, 5> kCompoundPartKeys = {"shape", "position", "orientation",
                                                               "rpy", "density"};
constexpr std::string_view kShapeTypes =
    "sphere, box, cylinder, capsule, mesh, plane, compound, trimesh, heightfield";

constexpr std::array<IntegratorKind, 3> kIntegrators = {
    IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4};

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

class ConfigParser {
 public:
  // How far mesh paths may reach: anywhere (a trusted config file), or only
  // files under the base directory (a body spawned over the network).
  enum class MeshPaths { Anywhere, InsideBaseDirectory };

  ConfigParser(std::string sourceName, const std::string& baseDirectory,
               MeshPaths meshPaths = MeshPaths::Anywhere)
      : m_reader(std::move(sourceName)), m_baseDirectory(baseDirectory), m_meshPaths(meshPaths) {}

  // `robotReport` (null: not wanted) gets the robots' load reports.
  // `visuals` (null: not wanted) gets how the robots' bodies look.
  // `publishing` (null: not wanted) gets how the robots' states are published.
  Expected<WorldDef> parseWorld(const YamlNode& root, std::vector<std::string>* robotReport = nullptr,
                                BodyVisuals* visuals = nullptr, RobotPublishingMap* publishing = nullptr) const;
  // The world, then the server's sections, of one document.
  Expected<Config> parseConfig(const YamlNode& root) const;
  Expected<BodyDef> parseBody(const YamlNode& node) const;
  Expected<SpawnDef> parseSpawn(const YamlNode& root, const JointBodyLookup& existing,
                                const JointBodyNames& existingNames = {}) const;

 private:
  // A `bodies:` list, appended to `bodies` (indexByName: name -> index in
  // `bodies`); with `existing`, a name the world already has is an error.
  std::optional<Error> parseBodies(const YamlNode& node, const JointBodyLookup* existing,
                                   std::vector<BodyDef>& bodies,
                                   std::map<std::string, std::size_t, std::less<>>& indexByName) const;
  Expected<WorldSettings> parseSettings(const YamlNode& node) const;
  Expected<IntegratorKind> parseIntegrator(const YamlNode& node) const;
  // Reads {linear, angular} into the two outputs, which keep their values
  // for absent keys.
  std::optional<Error> parseDamping(const YamlNode& node, std::optional<double>& linear,
                                    std::optional<double>& angular) const;
  Expected<std::string> parseName(const YamlNode& node) const;
  Expected<Shape> parseShape(const YamlNode& node, bool isStatic) const;
  // A mesh shape (closed: it bounds a solid) or a trimesh (any surface).
  enum class MeshUse { Solid, Surface };
  Expected<Shape> parseMesh(const YamlMap& shape, MeshUse use) const;
  // A terrain: a grid of heights (a file or inline rows) as a trimesh.
  Expected<Shape> parseHeightfield(const YamlMap& shape, const YamlNode& type) const;
  Expected<Shape> parsePlane(const YamlMap& shape, const YamlNode& type, bool isStatic) const;
  Expected<Shape> parseCompound(const YamlMap& shape, bool isStatic) const;
  Expected<CompoundPart> parseCompoundPart(const YamlNode& node, bool isStatic) const;

  // Where the mesh named `file` is read from, or why it may not be.
  Expected<std::string> meshPath(const std::string& file) const;

  YamlReader m_reader;
  std::filesystem::path m_baseDirectory;
  MeshPaths m_meshPaths;
};

Expected<WorldDef> ConfigParser::parseWorld(const YamlNode& root, std::vector<std::string>* robotReport,
                                            BodyVisuals* visuals, RobotPublishingMap* publishing) const {
  Expected<YamlMap> top = m_reader.map(root);
  if (!top) return top.error();
  if (auto error = m_reader.checkKeys(*top, kTopLevelKeys, "the top level")) return *error;

  WorldDef world;
  if (const YamlMap::Entry* settings = top->find("world")) {
    Expected<WorldSettings> parsed = parseSettings(settings->value);
    if (!parsed) return parsed.error();
    world.settings = *parsed;
  }
  if (const YamlMap::Entry* contact = top->find("contact")) {
    if (auto error = parseContactConfig(m_reader, contact->value, world.settings.contact))
      return *error;
  }

  const YamlMap::Entry* bodies = top->find("bodies");
  const YamlMap::Entry* robots = top->find("robots");
  if (bodies == nullptr && robots == nullptr) {
    if (const YamlMap::Entry* joints = top->find("joints"))
      return m_reader.error(joints->value, "joints need bodies to join (there is no bodies: list)");
    return world;
  }
  std::map<std::string, std::size_t, std::less<>> indexByName;
  if (bodies != nullptr) {
    if (auto error = parseBodies(bodies->value, nullptr, world.bodies, indexByName)) return *error;
  }
  if (robots != nullptr) {
    std::vector<std::string> report;
    const BodyNameTaken taken = [&](const std::string& name) { return indexByName.count(name) > 0; };
    BodyVisuals looks;
    RobotPublishingMap published;
    // The world file names the directory the viewer serves (default: its own).
    Expected<std::optional<std::filesystem::path>> served =
        readViewerMeshDirectory(m_reader, *top, m_baseDirectory);
    if (!served) return served.error();
    if (auto error = parseRobots(m_reader, robots->value, m_baseDirectory, RobotFilePaths::Anywhere, taken, world,
                                 report, kWorldMeshRoute, served->value_or(m_baseDirectory), looks, published))
      return *error;
    if (visuals != nullptr) visuals->merge(looks);
    if (publishing != nullptr) publishing->merge(published);
    for (std::size_t i = 0; i < world.bodies.size(); ++i) indexByName.emplace(world.bodies[i].name, i);
    if (robotReport != nullptr) robotReport->insert(robotReport->end(), report.begin(), report.end());
  }
  if (const YamlMap::Entry* joints = top->find("joints")) {
    const JointBodyLookup lookup = [&](const std::string& name) -> std::optional<bool> {
      const auto found = indexByName.find(name);
      if (found == indexByName.end()) return std::nullopt;
      return !world.bodies[found->second].isStatic;
    };
    const JointBodyNames names = [&] {
      std::vector<std::string> all;
      for (const auto& entry : indexByName) all.push_back(entry.first);
      return all;
    };
    if (auto error = parseJoints(m_reader, joints->value, lookup, world.joints, names)) return *error;
  }
  return world;
}

std::optional<Error> ConfigParser::parseBodies(const YamlNode& node, const JointBodyLookup* existing,
                                               std::vector<BodyDef>& bodies,
                                               std::map<std::string, std::size_t, std::less<>>& indexByName) const {
  Expected<std::vector<YamlNode>> items = m_reader.list(node);
  if (!items) return items.error();
  for (std::size_t i = 0; i < items->size(); ++i) {
    const YamlNode& item = (*items)[i];
    Expected<BodyDef> body = parseBody(item);
    if (!body) return body.error();
    const YAML::Node& itemNode = item.node;
    if (existing != nullptr && (*existing)(body->name))
      return m_reader.error(itemNode["name"].Mark(), item.path + ".name",
                            "the world already has a body named \"" + body->name + "\"");
    const auto [previous, inserted] = indexByName.emplace(body->name, bodies.size());
    if (!inserted)
      return m_reader.error(itemNode["name"].Mark(), item.path + ".name",
                            "duplicate body name \"" + body->name + "\" (also the name of " + node.path + "[" +
                                std::to_string(previous->second) + "])");
    bodies.push_back(std::move(*body));
  }
  return std::nullopt;
}

Expected<SpawnDef> ConfigParser::parseSpawn(const YamlNode& root, const JointBodyLookup& existing,
                                            const JointBodyNames& existingNames) const {
  Expected<YamlMap> top = m_reader.map(root);
  if (!top) return top.error();
  SpawnDef spawn;
  if (top->find("bodies") == nullptr && top->find("robots") == nullptr && top->find("joints") == nullptr) {
    // One body, as a `bodies:` entry.
    Expected<BodyDef> body = parseBody(root);
    if (!body) return body.error();
    if (existing(body->name))
      return m_reader.error(root.node["name"].Mark(), "name", "the world already has a body named \"" + body->name + "\"");
    spawn.bodies.push_back(std::move(*body));
    return spawn;
  }
  if (auto error = m_reader.checkKeys(*top, kSpawnKeys, "a spawn of bodies, robots and joints")) return *error;
  std::map<std::string, std::size_t, std::less<>> indexByName;
  if (const YamlMap::Entry* bodies = top->find("bodies")) {
    if (auto error = parseBodies(bodies->value, &existing, spawn.bodies, indexByName)) return *error;
  }
  if (const YamlMap::Entry* robots = top->find("robots")) {
    // The sender names the URDF and its meshes: they must lie inside the
    // spawn directory, as a spawned body's mesh must.
    const RobotFilePaths paths = m_meshPaths == MeshPaths::InsideBaseDirectory ? RobotFilePaths::InsideBaseDirectory
                                                                               : RobotFilePaths::Anywhere;
    const BodyNameTaken taken = [&](const std::string& name) {
      return indexByName.count(name) > 0 || existing(name).has_value();
    };
    WorldDef made;
    std::vector<std::string> report;
    if (auto error = parseRobots(m_reader, robots->value, m_baseDirectory, paths, taken, made, report,
                                 kSpawnMeshRoute, m_baseDirectory, spawn.visuals, spawn.robotPublishing))
      return *error;
    for (BodyDef& body : made.bodies) {
      indexByName.emplace(body.name, spawn.bodies.size());
      spawn.bodies.push_back(std::move(body));
    }
    for (NamedJointDef& joint : made.joints) spawn.joints.push_back(std::move(joint));
    spawn.excludedPairs = std::move(made.excludedPairs);
    spawn.robotReport = std::move(report);
  }
  if (const YamlMap::Entry* joints = top->find("joints")) {
    const JointBodyLookup lookup = [&](const std::string& name) -> std::optional<bool> {
      const auto found = indexByName.find(name);
      if (found != indexByName.end()) return !spawn.bodies[found->second].isStatic;
      return existing(name);
    };
    const JointBodyNames names = [&] {
      std::vector<std::string> all = existingNames ? existingNames() : std::vector<std::string>{};
      for (const auto& entry : indexByName) all.push_back(entry.first);
      return all;
    };
    if (auto error = parseJoints(m_reader, joints->value, lookup, spawn.joints, names)) return *error;
  }
  return spawn;
}

Expected<Config> ConfigParser::parseConfig(const YamlNode& root) const {
  std::vector<std::string> robotReport;
  BodyVisuals visuals;
  RobotPublishingMap publishing;
  Expected<WorldDef> world = parseWorld(root, &robotReport, &visuals, &publishing);
  if (!world) return world.error();
  Config config{std::move(*world), ServerSettings{}, std::move(robotReport), std::move(visuals),
                std::move(publishing), {}};
  // parseWorld has checked that the root is a mapping.
  const Expected<YamlMap> top = m_reader.map(root);
  if (!top) return top.error();
  if (auto error = readServerSections(m_reader, *top, config.server)) return *error;
  if (const YamlMap::Entry* sensors = top->find("sensors")) {
    if (auto error = parseSensors(m_reader, sensors->value, config.world, config.sensors)) return *error;
  }
  return config;
}

Expected<WorldSettings> ConfigParser::parseSettings(const YamlNode& node) const {
  Expected<YamlMap> map = m_reader.map(node);
  if (!map) return map.error();
  if (auto error = m_reader.checkKeys(*map, kWorldKeys, "the world")) return *error;

  WorldSettings settings;
  Expected<double> dt = m_reader.number(*map, "dt", NumberRule::positive(kMaxDt), settings.dt);
  if (!dt) return dt.error();
  settings.dt = *dt;

  Expected<Vec3> gravity =
      m_reader.vec3(*map, "gravity", NumberRule::any(kMaxAcceleration), settings.gravity);
  if (!gravity) return gravity.error();
  settings.gravity = *gravity;

  if (const YamlMap::Entry* integrator = map->find("integrator")) {
    Expected<IntegratorKind> kind = parseIntegrator(integrator->value);
    if (!kind) return kind.error();
    settings.integrator = *kind;
  }

  if (const YamlMap::Entry* damping = map->find("damping")) {
    std::optional<double> linear = settings.linearDamping;
    std::optional<double> angular = settings.angularDamping;
    if (auto error = parseDamping(damping->value, linear, angular)) return *error;
    settings.linearDamping = *linear;
    settings.angularDamping = *angular;
  }

  // 0 (the default): as many threads as the process has cores.
  Expected<double> threads = m_reader.number(*map, "threads", NumberRule::nonNegative(kMaxThreads), 0.0);
  if (!threads) return threads.error();
  if (*threads != static_cast<double>(static_cast<int>(*threads)))
    return m_reader.error(map->find("threads")->value, "expected a whole number (0: one per core)");
  settings.threads = static_cast<int>(*threads);
  return settings;
}

Expected<IntegratorKind> ConfigParser::parseIntegrator(const YamlNode& node) const {
  Expected<std::string> name = m_reader.string(node);
  if (!name) return name.error();
  if (std::optional<IntegratorKind> kind = integratorFromName(*name)) return *kind;
  std::string names;
  for (IntegratorKind kind : kIntegrators) {
    if (!names.empty()) names += ", ";
    names += integratorName(kind);
  }
  return m_reader.error(node, "expected one of " + names + ", got " + describeNode(node.node));
}

std::optional<Error> ConfigParser::parseDamping(const YamlNode& node, std::optional<double>& linear,
                                                std::optional<double>& angular) const {
  Expected<YamlMap> map = m_reader.map(node);
  if (!map) return map.error();
  if (auto error = m_reader.checkKeys(*map, kDampingKeys, "damping")) return error;
  const NumberRule rule = NumberRule::nonNegative(kMaxDamping);
  if (const YamlMap::Entry* entry = map->find("linear")) {
    Expected<double> value = m_reader.number(entry->value, rule);
    if (!value) return value.error();
    linear = *value;
  }
  if (const YamlMap::Entry* entry = map->find("angular")) {
    Expected<double> value = m_reader.number(entry->value, rule);
    if (!value) return value.error();
    angular = *value;
  }
  return std::nullopt;
}

Expected<BodyDef> ConfigParser::parseBody(const YamlNode& node) const {
  Expected<YamlMap> map = m_reader.map(node);
  if (!map) return map.error();
  if (auto error = m_reader.checkKeys(*map, kBodyKeys, "a body")) return *error;

  BodyDef body;
  Expected<YamlNode> nameNode = m_reader.required(*map, "name");
  if (!nameNode) return nameNode.error();
  Expected<std::string> name = parseName(*nameNode);
  if (!name) return name.error();
  body.name = *name;

  // Before the shape: a plane needs to know.
  Expected<bool> isStatic = m_reader.boolean(*map, "static", false);
  if (!isStatic) return isStatic.error();
  body.isStatic = *isStatic;

  Expected<YamlNode> shapeNode = m_reader.required(*map, "shape");
  if (!shapeNode) return shapeNode.error();
  Expected<Shape> shape = parseShape(*shapeNode, body.isStatic);
  if (!shape) return shape.error();
  body.shape = std::move(*shape);

  const YamlMap::Entry* mass = map->find("mass");
  const YamlMap::Entry* density = map->find("density");
  if (mass != nullptr && density != nullptr) {
    const YamlMap::Entry& second = laterEntry(*mass, *density);
    return m_reader.error(second.keyMark, second.value.path, "give mass or density, not both");
  }
  if (mass != nullptr) {
    Expected<double> value = m_reader.number(mass->value, NumberRule::positive(kMaxMass));
    if (!value) return value.error();
    body.mass = *value;
  }
  if (density != nullptr) {
    Expected<double> value = m_reader.number(density->value, NumberRule::positive(kMaxDensity));
    if (!value) return value.error();
    body.density = *value;
  }
  if (auto error = parseGivenMassProperties(m_reader, *map, body)) return *error;

  Expected<Vec3> position =
      m_reader.vec3(*map, "position", NumberRule::any(kMaxLength), body.position);
  if (!position) return position.error();
  body.position = *position;

  Expected<Quaternion> orientation = parseOrientation(m_reader, *map);
  if (!orientation) return orientation.error();
  body.orientation = *orientation;

  Expected<Vec3> linearVelocity =
      m_reader.vec3(*map, "linear_velocity", NumberRule::any(kMaxLinearSpeed), body.linearVelocity);
  if (!linearVelocity) return linearVelocity.error();
  body.linearVelocity = *linearVelocity;

  Expected<Vec3> angularVelocity = m_reader.vec3(
      *map, "angular_velocity", NumberRule::any(kMaxAngularSpeed), body.angularVelocity);
  if (!angularVelocity) return angularVelocity.error();
  body.angularVelocity = *angularVelocity;

  // The engine never integrates a static body: a velocity would be ignored
  // without a word, which is worse than refusing it.
  if (body.isStatic) {
    for (std::string_view key : {"linear_velocity", "angular_velocity"}) {
      const YamlMap::Entry* entry = map->find(key);
      const Vec3& velocity = key == "linear_velocity" ? body.linearVelocity : body.angularVelocity;
      if (entry != nullptr && !velocity.isZero(0.0)) {
        return m_reader.error(entry->value, "a static body cannot move; expected [0, 0, 0] or no " +
                                                std::string(key));
      }
    }
  }

  if (const YamlMap::Entry* damping = map->find("damping")) {
    if (auto error = parseDamping(damping->value, body.linearDamping, body.angularDamping)) {
      return *error;
    }
  }
  if (const YamlMap::Entry* material = map->find("material")) {
    Expected<MaterialSpec> spec = parseMaterial(m_reader, material->value);
    if (!spec) return spec.error();
    body.material = *spec;
  }
  Expected<bool> ccd = m_reader.boolean(*map, "ccd", false);
  if (!ccd) return ccd.error();
  body.continuousCollision = *ccd;
  // false: a body that collides with nothing (a robot link without
  // collision geometry): its shape only draws it and gives its mass.
  Expected<bool> collides = m_reader.boolean(*map, "collides", true);
  if (!collides) return collides.error();
  body.collides = *collides;
  // Which bodies it collides with: Bullet's group and mask (config/collision_filter_config.h).
  if (auto error = parseCollisionFilter(m_reader, *map, kCollisionGroupKey, kCollisionMaskKey, body.collisionFilter))
    return *error;
  return body;
}

Expected<std::string> ConfigParser::parseName(const YamlNode& node) const {
  Expected<std::string> name = m_reader.string(node);
  if (!name) return name.error();
  if (name->empty()) return m_reader.error(node, "expected a non-empty name");
  if (name->size() > kMaxNameLength) {
    return m_reader.error(node, "expected a name of at most " + std::to_string(kMaxNameLength) +
                                    " characters, got " + std::to_string(name->size()));
  }
  for (const char c : *name) {
    if (std::iscntrl(static_cast<unsigned char>(c)) != 0) {
      return m_reader.error(node, "expected a name without control characters");
    }
  }
  // Joints (and world_t's joint descriptions) call the world itself "world".
  if (*name == "world")
    return m_reader.error(node, "\"world\" is reserved: joints name the world itself so; give the body another name");
  return name;
}

Expected<Shape> ConfigParser::parseShape(const YamlNode& node, bool isStatic) const {
  Expected<YamlMap> map = m_reader.map(node);
  if (!map) return map.error();
  Expected<YamlNode> typeNode = m_reader.required(*map, "type");
  if (!typeNode) return typeNode.error();
  Expected<std::string> type = m_reader.string(*typeNode);
  if (!type) return type.error();

  const NumberRule length = NumberRule::positive(kMaxLength);
  if (*type == "sphere") {
    if (auto error = m_reader.checkKeys(*map, kSphereKeys, "a sphere shape")) return *error;
    Expected<YamlNode> radius = m_reader.required(*map, "radius");
    if (!radius) return radius.error();
    Expected<double> value = m_reader.number(*radius, length);
    if (!value) return value.error();
    return Shape{SphereShape{*value}};
  }
  if (*type == "box") {
    if (auto error = m_reader.checkKeys(*map, kBoxKeys, "a box shape")) return *error;
    Expected<YamlNode> halfExtents = m_reader.required(*map, "half_extents");
    if (!halfExtents) return halfExtents.error();
    Expected<Vec3> value = m_reader.vec3(*halfExtents, length);
    if (!value) return value.error();
    return Shape{BoxShape{*value}};
  }
  if (*type == "cylinder" || *type == "capsule") {
    const std::string owner = "a " + *type + " shape";
    if (auto error = m_reader.checkKeys(*map, kCylinderKeys, owner)) return *error;
    Expected<YamlNode> radiusNode = m_reader.required(*map, "radius");
    if (!radiusNode) return radiusNode.error();
    Expected<double> radius = m_reader.number(*radiusNode, length);
    if (!radius) return radius.error();
    Expected<YamlNode> halfLengthNode = m_reader.required(*map, "half_length");
    if (!halfLengthNode) return halfLengthNode.error();
    Expected<double> halfLength = m_reader.number(*halfLengthNode, length);
    if (!halfLength) return halfLength.error();
    if (*type == "cylinder") return Shape{CylinderShape{*radius, *halfLength}};
    return Shape{CapsuleShape{*radius, *halfLength}};
  }
  if (*type == "mesh") {
    if (auto error = m_reader.checkKeys(*map, kMeshKeys, "a mesh shape")) return *error;
    return parseMesh(*map, MeshUse::Solid);
  }
  if (*type == "trimesh") {
    if (auto error = m_reader.checkKeys(*map, kMeshKeys, "a trimesh shape")) return *error;
    // Its triangles collide one by one, on a body that never moves: a
    // surface has no mass and cannot be integrated.
    if (!isStatic) {
      return m_reader.error(*typeNode,
                            "a trimesh is only allowed on a static body (add static: true)");
    }
    return parseMesh(*map, MeshUse::Surface);
  }
  if (*type == "heightfield") {
    if (auto error = m_reader.checkKeys(*map, kHeightfieldKeys, "a heightfield shape")) return *error;
    if (!isStatic) {
      return m_reader.error(*typeNode,
                            "a heightfield is only allowed on a static body (add static: true)");
    }
    return parseHeightfield(*map, *typeNode);
  }
  if (*type == "plane") {
    if (auto error = m_reader.checkKeys(*map, kPlaneKeys, "a plane shape")) return *error;
    return parsePlane(*map, *typeNode, isStatic);
  }
  if (*type == "compound") {
    if (auto error = m_reader.checkKeys(*map, kCompoundKeys, "a compound shape")) return *error;
    return parseCompound(*map, isStatic);
  }
  return m_reader.error(*typeNode, "expected one of " + std::string(kShapeTypes) + ", got " +
                                       describeNode(typeNode->node));
}

Expected<Shape> ConfigParser::parseMesh(const YamlMap& shape, MeshUse use) const {
  Expected<YamlNode> fileNode = m_reader.required(shape, "file");
  if (!fileNode) return fileNode.error();
  Expected<std::string> file = m_reader.string(*fileNode);
  if (!file) return file.error();
  if (file->empty()) return m_reader.error(*fileNode, "expected a mesh file path");

  const Expected<std::string> path = meshPath(*file);
  if (!path) return m_reader.error(*fileNode, path.error().message);
  const bool contained = m_meshPaths == MeshPaths::InsideBaseDirectory;
  // A spawned body's mesh is named as its sender named it (in messages and in
  // the world description): the host's directory layout is none of its business.
  const std::string resolved = contained ? *file : *path;

  Expected<TriangleMesh> mesh = loadMesh(*path);
  if (!mesh) {
    std::string message = mesh.error().message;
    if (contained) replaceAll(message, *path, *file);
    return m_reader.error(*fileNode, message);
  }
  Expected<bool> valid = use == MeshUse::Solid ? validateClosedMesh(*mesh, resolved)
                                               : validateSurfaceMesh(*mesh, resolved);
  if (!valid) return m_reader.error(*fileNode, valid.error().message);
  for (const Vec3& vertex : mesh->vertices) {
    if (!vertex.allFinite() || vertex.cwiseAbs().maxCoeff() > kMaxLength) {
      return m_reader.error(*fileNode, resolved + ": a vertex is not finite or lies beyond " +
                                           std::to_string(static_cast<long long>(kMaxLength)) +
                                           " m");
    }
  }
  auto shared = std::make_shared<const TriangleMesh>(std::move(*mesh));
  if (use == MeshUse::Surface) return Shape{TriangleMeshShape{resolved, std::move(shared)}};
  return Shape{MeshShape{resolved, std::move(shared)}};
}

Expected<Shape> ConfigParser::parseHeightfield(const YamlMap& shape, const YamlNode& type) const {
  const YamlMap::Entry* fileEntry = shape.find("file");
  const YamlMap::Entry* heightsEntry = shape.find("heights");
  if ((fileEntry != nullptr) == (heightsEntry != nullptr)) {
    return m_reader.error(type, "a heightfield takes exactly one of file (a .png or .npy height map) and "
                                "heights (rows of numbers)");
  }
  HeightGrid grid;
  std::string source = "inline heights";
  if (fileEntry != nullptr) {
    const YamlNode& fileNode = fileEntry->value;
    Expected<std::string> file = m_reader.string(fileNode);
    if (!file) return file.error();
    if (file->empty()) return m_reader.error(fileNode, "expected a height map file path (.png or .npy)");
    const Expected<std::string> path = meshPath(*file);
    if (!path) return m_reader.error(fileNode, path.error().message);
    const bool contained = m_meshPaths == MeshPaths::InsideBaseDirectory;
    source = contained ? *file : *path;
    Expected<HeightGrid> loaded = loadHeightGrid(*path);
    if (!loaded) {
      std::string message = loaded.error().message;
      if (contained) replaceAll(message, *path, *file);
      return m_reader.error(fileNode, message);
    }
    grid = std::move(*loaded);
  } else {
    // Rows of samples, row 0 at the terrain's −y edge (as a .npy file's).
    const YamlNode& heightsNode = heightsEntry->value;
    Expected<std::vector<YamlNode>> rows = m_reader.list(heightsNode);
    if (!rows) return rows.error();
    if (rows->size() < 2)
      return m_reader.error(heightsNode, "expected at least 2 rows of heights (one cell)");
    for (const YamlNode& rowNode : *rows) {
      Expected<std::vector<YamlNode>> samples = m_reader.list(rowNode);
      if (!samples) return samples.error();
      if (grid.rows == 0) grid.columns = static_cast<int>(samples->size());
      if (samples->size() < 2)
        return m_reader.error(rowNode, "expected at least 2 heights in a row (one cell)");
      if (static_cast<int>(samples->size()) != grid.columns) {
        return m_reader.error(rowNode, "expected " + std::to_string(grid.columns) +
                                           " heights, as in the first row; got " + std::to_string(samples->size()));
      }
      if (static_cast<long>(rows->size()) * grid.columns > kMaxHeightSamples)
        return m_reader.error(heightsNode, "more than " + std::to_string(kMaxHeightSamples) + " heights");
      for (const YamlNode& sample : *samples) {
        Expected<double> height = m_reader.number(sample, NumberRule::any(kMaxLength));
        if (!height) return height.error();
        grid.values.push_back(*height);
      }
      ++grid.rows;
    }
  }

  // The spacing of the samples: one number for square cells, or [x, y].
  Expected<YamlNode> cellNode = m_reader.required(shape, "cell_size");
  if (!cellNode) return cellNode.error();
  double cellX = 0.0, cellY = 0.0;
  if (cellNode->node.IsSequence()) {
    Expected<std::array<double, 2>> cell = m_reader.numbers<2>(*cellNode, NumberRule::positive(kMaxLength));
    if (!cell) return cell.error();
    cellX = (*cell)[0];
    cellY = (*cell)[1];
  } else {
    Expected<double> cell = m_reader.number(*cellNode, NumberRule::positive(kMaxLength));
    if (!cell) return cell.error();
    cellX = cellY = *cell;
  }
  Expected<double> scale = m_reader.number(shape, "height_scale", NumberRule::any(kMaxLength), 1.0);
  if (!scale) return scale.error();
  Expected<double> offset = m_reader.number(shape, "height_offset", NumberRule::any(kMaxLength), 0.0);
  if (!offset) return offset.error();
  if (cellX * (grid.columns - 1) > 2 * kMaxLength || cellY * (grid.rows - 1) > 2 * kMaxLength)
    return m_reader.error(*cellNode, "the terrain reaches beyond " + std::to_string(static_cast<long long>(kMaxLength)) + " m");
  TriangleMesh mesh = heightGridMesh(grid, cellX, cellY, *scale, *offset);
  for (const Vec3& vertex : mesh.vertices) {
    if (!vertex.allFinite() || std::abs(vertex.z()) > kMaxLength) {
      return m_reader.error(type, source + ": a height (scale × value + offset) is not finite or lies beyond " +
                                      std::to_string(static_cast<long long>(kMaxLength)) + " m");
    }
  }
  Expected<bool> valid = validateSurfaceMesh(mesh, source);
  if (!valid) return m_reader.error(type, valid.error().message);
  return Shape{TriangleMeshShape{source, std::make_shared<const TriangleMesh>(std::move(mesh))}};
}

Expected<std::string> ConfigParser::meshPath(const std::string& file) const {
  if (m_meshPaths == MeshPaths::InsideBaseDirectory)
    return resolveContainedFile(file, m_baseDirectory.string());
  // Relative to the config file, so that a world and its meshes move together.
  std::filesystem::path path(file);
  if (path.is_relative() && !m_baseDirectory.empty()) path = m_baseDirectory / path;
  return path.lexically_normal().string();
}

Expected<Shape> ConfigParser::parsePlane(const YamlMap& shape, const YamlNode& type,
                                         bool isStatic) const {
  // A half-space has infinite mass; nothing could move it or integrate it.
  if (!isStatic) {
    return m_reader.error(type, "a plane is only allowed on a static body (add static: true)");
  }
  PlaneShape plane;
  Expected<Vec3> normal = m_reader.vec3(shape, "normal", NumberRule::any(kMaxLength), plane.normal);
  if (!normal) return normal.error();
  if (normal->norm() < kMinNorm) {
    return m_reader.error(shape.find("normal")->value, "expected a non-zero normal vector");
  }
  plane.normal = normal->normalized();
  Expected<double> offset =
      m_reader.number(shape, "offset", NumberRule::any(kMaxLength), plane.offset);
  if (!offset) return offset.error();
  plane.offset = *offset;
  return Shape{plane};
}

Expected<Shape> ConfigParser::parseCompound(const YamlMap& shape, bool isStatic) const {
  Expected<YamlNode> shapesNode = m_reader.required(shape, "shapes");
  if (!shapesNode) return shapesNode.error();
  Expected<std::vector<YamlNode>> items = m_reader.list(*shapesNode);
  if (!items) return items.error();
  if (items->empty()) {
    return m_reader.error(*shapesNode, "expected at least one part shape in a compound");
  }
  CompoundShape compound;
  for (const YamlNode& item : *items) {
    Expected<CompoundPart> part = parseCompoundPart(item, isStatic);
    if (!part) return part.error();
    compound.parts.push_back(std::move(*part));
  }
  return Shape{std::move(compound)};
}

Expected<CompoundPart> ConfigParser::parseCompoundPart(const YamlNode& node, bool isStatic) const {
  Expected<YamlMap> map = m_reader.map(node);
  if (!map) return map.error();
  if (auto error = m_reader.checkKeys(*map, kCompoundPartKeys, "a compound part")) return *error;

  Expected<YamlNode> shapeNode = m_reader.required(*map, "shape");
  if (!shapeNode) return shapeNode.error();
  // Planes and compounds are refused by name before parsing, so that the
  // message says why rather than what a plane would need elsewhere.
  Expected<YamlMap> shapeMap = m_reader.map(*shapeNode);
  if (!shapeMap) return shapeMap.error();
  if (const YamlMap::Entry* type = shapeMap->find("type")) {
    Expected<std::string> name = m_reader.string(type->value);
    if (!name) return name.error();
    if (*name == "compound") {
      return m_reader.error(type->value,
                            "a compound cannot contain a compound; list its parts here instead");
    }
    if (*name == "trimesh") {
      return m_reader.error(type->value,
                            "a trimesh cannot be part of a compound (it is static only); make "
                            "it a static body of its own");
    }
    if (*name == "plane") {
      return m_reader.error(type->value,
                            "a plane cannot be part of a compound (a half-space has no finite "
                            "mass); make it a static body of its own");
    }
  }
  Expected<Shape> shape = parseShape(*shapeNode, isStatic);
  if (!shape) return shape.error();

  std::optional<CompoundPartShape> partShape = toPartShape(std::move(*shape));
  if (!partShape) return m_reader.error(*shapeNode, "this shape cannot be part of a compound");
  CompoundPart part;
  part.shape = std::move(*partShape);

  Expected<Vec3> position =
      m_reader.vec3(*map, "position", NumberRule::any(kMaxLength), part.position);
  if (!position) return position.error();
  part.position = *position;

  Expected<Quaternion> orientation = parseOrientation(m_reader, *map);
  if (!orientation) return orientation.error();
  part.orientation = *orientation;

  if (const YamlMap::Entry* density = map->find("density")) {
    Expected<double> value = m_reader.number(density->value, NumberRule::positive(kMaxDensity));
    if (!value) return value.error();
    part.density = *value;
  }
  return part;
}

// Runs `parse` on the single document of `yamlText`, turning every yaml-cpp
// exception (syntax errors, nesting too deep) into an Error.
template <class T, class Parse>
Expected<T> parseDocument(const std::string& yamlText, const std::string& sourceName,
                          const Parse& parse) {
  const YamlReader reader(sourceName);
  try {
    // Not YAML::LoadAll, which can loop forever (yaml_document_count.h).
    YAML::Mark secondStart;
    const int documents = countYamlDocuments(yamlText, 2, &secondStart);
    if (documents == 0) {
      return reader.error(YAML::Mark(), "", "expected a mapping, got an empty document");
    }
    if (documents > 1) {
      return reader.error(secondStart, "", "expected one YAML document, found a second one");
    }
    return parse(YamlNode::root(YAML::Load(yamlText)));
  } catch (const YAML::Exception& e) {
    return reader.error(e.mark, "", "YAML syntax error: " + e.msg);
  } catch (const std::exception& e) {
    return reader.error(YAML::Mark::null_mark(), "", e.what());
  }
}

}  // namespace

Expected<WorldDef> parseWorldConfig(const std::string& yamlText, const std::string& sourceName,
                                    const std::string& baseDirectory) {
  const ConfigParser parser(sourceName, baseDirectory);
  return parseDocument<WorldDef>(yamlText, sourceName,
                                 [&](const YamlNode& root) { return parser.parseWorld(root); });
}

Expected<BodyDef> parseBodyDef(const std::string& yamlText, const std::string& sourceName,
                               const std::string& baseDirectory) {
  const ConfigParser parser(sourceName, baseDirectory);
  return parseDocument<BodyDef>(yamlText, sourceName,
                                [&](const YamlNode& root) { return parser.parseBody(root); });
}

Expected<SpawnDef> parseSpawnDef(const std::string& yamlText, const std::string& sourceName,
                                 const std::string& meshDirectory, const JointBodyLookup& existing,
                                 const JointBodyNames& existingNames) {
  const ConfigParser parser(sourceName, meshDirectory, ConfigParser::MeshPaths::InsideBaseDirectory);
  return parseDocument<SpawnDef>(yamlText, sourceName,
                                 [&](const YamlNode& root) { return parser.parseSpawn(root, existing, existingNames); });
}

Expected<Config> parseConfig(const std::string& yamlText, const std::string& sourceName,
                             const std::string& baseDirectory) {
  const ConfigParser parser(sourceName, baseDirectory);
  return parseDocument<Config>(yamlText, sourceName,
                               [&](const YamlNode& root) { return parser.parseConfig(root); });
}

namespace {

// The whole text of the config file at `path`.
Expected<std::string> readConfigFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    const std::string why =
        ec ? ec.message()
           : (std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
    return Error{path + ": cannot read the config file: " + why};
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return Error{path + ": cannot read the config file: " + ec.message()};
  std::string text(size, '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (!in) return Error{path + ": cannot read the config file: " + std::strerror(errno)};
  return text;
}

}  // namespace

Expected<WorldDef> loadWorldConfig(const std::string& path) {
  const Expected<std::string> text = readConfigFile(path);
  if (!text) return text.error();
  return parseWorldConfig(*text, path, std::filesystem::path(path).parent_path().string());
}

Expected<Config> loadConfig(const std::string& path) {
  const Expected<std::string> text = readConfigFile(path);
  if (!text) return text.error();
  return parseConfig(*text, path, std::filesystem::path(path).parent_path().string());
}

}  // namespace rbsim
