#include "config/robot_config.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <set>
#include <string_view>

#include "config/collision_filter_config.h"
#include "config/joint_config.h"
#include "config/orientation_config.h"
#include "meshio/contained_path.h"
#include "robot/urdf_robot.h"

namespace rbsim {

namespace {

constexpr std::array<std::string_view, 18> kRobotKeys = {
    "name",           "urdf",          "position",           "orientation",   "rpy",
    "fixed_base",     "merge_fixed_links", "joint_positions", "joint_drives",  "package_paths",
    "self_collision", "disable_collisions", "link_collision", "hull_tolerance", "hull_max_vertices",
    "gravity_compensation", "state_rate", "state_dynamics"};
constexpr double kMaxLength = 1e6;           // m, as the bodies' positions
constexpr double kMaxJointPosition = 1e6;    // rad or m
constexpr std::size_t kMaxNameLength = 128;  // characters, as body names
constexpr double kMaxHullTolerance = 1.0;      // m: a simplified hull this far off is no longer the mesh
constexpr uint64_t kMaxHullVertices = 1000000;  // as many as a mesh may have

std::filesystem::path resolved(const std::filesystem::path& base, const std::string& file) {
  std::filesystem::path path(file);
  if (path.is_relative() && !base.empty()) path = base / path;
  return path.lexically_normal();
}

// joint_drives: {JOINT: {target, stiffness, damping, ...}}: a position drive
// on each named joint of the robot, as a world file's joint takes one, so
// that a robot holds its pose from the first step (a URDF has no drives).
// A drive without a target holds the joint where the robot was placed.
std::optional<Error> applyJointDrives(const YamlReader& reader, const YamlNode& node, RobotModel& robot) {
  Expected<YamlMap> drives = reader.map(node);
  if (!drives) return drives.error();
  for (const YamlMap::Entry& entry : drives->entries()) {
    const auto joint = std::find_if(robot.joints.begin(), robot.joints.end(), [&](const NamedJointDef& j) {
      const std::string& name = j.def.name;
      const std::size_t slash = name.find('/');
      return slash != std::string::npos && name.compare(slash + 1, std::string::npos, entry.key) == 0;
    });
    if (joint == robot.joints.end())
      return reader.error(entry.keyMark, entry.value.path, "the robot has no joint named \"" + entry.key + "\"");
    JointDef& def = joint->def;
    if (def.type != JointType::Revolute && def.type != JointType::Prismatic)
      return reader.error(entry.keyMark, entry.value.path,
                          "joint \"" + entry.key + "\" has no axis for a drive (a drive acts on a revolute or "
                          "prismatic joint's coordinate)");
    if (def.mimic.enabled)
      return reader.error(entry.keyMark, entry.value.path,
                          "joint \"" + entry.key + "\" follows joint '" + def.mimic.leader +
                              "' (mimic) and takes no drive of its own: drive its leader, which moves both");
    Expected<JointDrive> drive = parseJointDrive(reader, entry.value);
    if (!drive) return drive.error();
    Expected<YamlMap> fields = reader.map(entry.value);
    if (fields && fields->find("target") == nullptr) drive->target = def.position;
    def.drive = *drive;
    // Said in the load report, with what the URDF gave the joint.
    const bool prismatic = def.type == JointType::Prismatic;
    std::ostringstream line;
    line.precision(6);
    line << "joint '" << def.name << "': position drive (joint_drives), target " << drive->target
         << (prismatic ? " m" : " rad");
    if (drive->frequency > 0.0)
      line << ", frequency " << drive->frequency << " Hz, damping ratio " << drive->dampingRatio;
    else
      line << ", stiffness " << drive->stiffness << ", damping " << drive->damping;
    if (std::isfinite(drive->maxEffort)) line << ", max effort " << drive->maxEffort << (prismatic ? " N" : " N·m");
    robot.report.push_back(line.str());
  }
  return std::nullopt;
}

}  // namespace

std::optional<Error> parseRobots(const YamlReader& reader, const YamlNode& node,
                                 const std::filesystem::path& baseDirectory, RobotFilePaths paths,
                                 const BodyNameTaken& taken, WorldDef& world, std::vector<std::string>& report,
                                 const std::string& meshRoute, const std::filesystem::path& meshRouteDirectory,
                                 BodyVisuals& visuals, RobotPublishingMap& publishing) {
  const bool confined = paths == RobotFilePaths::InsideBaseDirectory;
  Expected<std::vector<YamlNode>> items = reader.list(node);
  if (!items) return items.error();
  std::set<std::string, std::less<>> names;
  for (const YamlNode& item : *items) {
    Expected<YamlMap> map = reader.map(item);
    if (!map) return map.error();
    if (auto error = reader.checkKeys(*map, kRobotKeys, "a robot")) return *error;

    RobotPlacement placement;
    Expected<YamlNode> nameNode = reader.required(*map, "name");
    if (!nameNode) return nameNode.error();
    Expected<std::string> name = reader.string(*nameNode);
    if (!name) return name.error();
    if (name->empty() || name->size() > kMaxNameLength || name->find('/') != std::string::npos)
      return reader.error(*nameNode, "a robot's name is 1 to 128 characters without '/' (it prefixes its bodies' names)");
    if (!names.insert(*name).second) return reader.error(*nameNode, "duplicate robot name \"" + *name + "\"");
    placement.name = *name;

    Expected<YamlNode> urdfNode = reader.required(*map, "urdf");
    if (!urdfNode) return urdfNode.error();
    Expected<std::string> urdf = reader.string(*urdfNode);
    if (!urdf) return urdf.error();
    if (urdf->empty()) return reader.error(*urdfNode, "expected the path of a URDF file");

    Expected<Vec3> position = reader.vec3(*map, "position", NumberRule::any(kMaxLength), Vec3::Zero());
    if (!position) return position.error();
    placement.position = *position;
    Expected<Quaternion> orientation = parseOrientation(reader, *map);
    if (!orientation) return orientation.error();
    placement.orientation = *orientation;
    Expected<bool> fixedBase = reader.boolean(*map, "fixed_base", false);
    if (!fixedBase) return fixedBase.error();
    placement.fixedBase = *fixedBase;
    Expected<bool> merge = reader.boolean(*map, "merge_fixed_links", false);
    if (!merge) return merge.error();
    placement.mergeFixedLinks = *merge;
    // How far a collision mesh's hull may be simplified (urdf_robot.h).
    Expected<double> hullTolerance =
        reader.number(*map, "hull_tolerance", NumberRule::nonNegative(kMaxHullTolerance), placement.hullTolerance);
    if (!hullTolerance) return hullTolerance.error();
    placement.hullTolerance = *hullTolerance;
    if (const YamlMap::Entry* budget = map->find("hull_max_vertices")) {
      Expected<uint64_t> vertices = reader.wholeNumber(budget->value, kMaxHullVertices, "hull_max_vertices");
      if (!vertices) return vertices.error();
      if (*vertices < 4) return reader.error(budget->value, "hull_max_vertices must be at least 4 (a tetrahedron)");
      placement.hullMaxVertices = static_cast<std::size_t>(*vertices);
    }

    const YamlMap::Entry* positions = map->find("joint_positions");
    if (positions != nullptr) {
      Expected<YamlMap> joints = reader.map(positions->value);
      if (!joints) return joints.error();
      for (const YamlMap::Entry& joint : joints->entries()) {
        Expected<double> q = reader.number(joint.value, NumberRule::any(kMaxJointPosition));
        if (!q) return q.error();
        placement.jointPositions.emplace(joint.key, *q);
      }
    }
    RobotFiles files;
    files.sourceName = *urdf;
    files.meshRoute = meshRoute;
    files.meshRouteDirectory = meshRouteDirectory.string();
    std::string urdfPath = resolved(baseDirectory, *urdf).string();
    if (confined) {
      Expected<std::string> inside = resolveContainedFile(*urdf, baseDirectory.string());
      if (!inside) return reader.error(*urdfNode, inside.error().message);
      urdfPath = *inside;
      files.confinedTo = baseDirectory.string();
      files.directory = std::filesystem::path(*urdf).parent_path().string();
    }
    if (const YamlMap::Entry* packagePaths = map->find("package_paths")) {
      Expected<std::vector<YamlNode>> list = reader.list(packagePaths->value);
      if (!list) return list.error();
      for (const YamlNode& entry : *list) {
        Expected<std::string> directory = reader.string(entry);
        if (!directory) return directory.error();
        if (directory->empty()) return reader.error(entry, "expected a directory");
        if (!confined) {
          files.packagePaths.push_back(resolved(baseDirectory, *directory).string());
          continue;
        }
        // Each file found through it is checked again (contained_path.h);
        // the directory itself must not point out.
        const std::filesystem::path given(*directory);
        const bool climbs = std::any_of(given.begin(), given.end(), [](const auto& part) { return part == ".."; });
        if (given.is_absolute() || climbs)
          return reader.error(entry, "a spawned robot's package path must be relative to the spawn directory, "
                                     "with no '..'");
        files.packagePaths.push_back(given.lexically_normal().string());
      }
    }

    Expected<RobotModel> robot = loadRobot(urdfPath, placement, files);
    if (!robot) {
      // A joint position the robot cannot take is the world file's mistake.
      constexpr std::string_view kPositions = "joint_positions: ";
      const std::string& message = robot.error().message;
      if (positions != nullptr && message.rfind(kPositions, 0) == 0)
        return reader.error(positions->value, message.substr(kPositions.size()));
      return reader.error(*urdfNode, message);
    }
    if (const YamlMap::Entry* drives = map->find("joint_drives"))
      if (auto error = applyJointDrives(reader, drives->value, *robot)) return *error;
    Expected<bool> compensated = reader.boolean(*map, "gravity_compensation", false);
    if (!compensated) return compensated.error();
    if (*compensated) {
      // Every actuated joint's drive, now and when a command turns it on
      // (a command's drive keeps the joint's setting).
      for (NamedJointDef& joint : robot->joints)
        if (!joint.def.mimic.enabled &&
            (joint.def.type == JointType::Revolute || joint.def.type == JointType::Prismatic))
          joint.def.drive.gravityCompensation = true;
      robot->report.push_back("gravity compensation on every joint's drive (gravity_compensation)");
    }
    RobotPublishing published;
    if (const YamlMap::Entry* rate = map->find("state_rate")) {
      // Hz; any rate at or above 1/dt means every step.
      Expected<double> hertz = reader.number(rate->value, NumberRule::positive(1e9));
      if (!hertz) return hertz.error();
      published.stateRate = *hertz;
    }
    Expected<bool> dynamics = reader.boolean(*map, "state_dynamics", false);
    if (!dynamics) return dynamics.error();
    published.dynamics = *dynamics;
    publishing[*name] = published;
    if (auto error = applyRobotCollisions(reader, *map, *name, *robot, world.excludedPairs)) return *error;
    for (const BodyDef& body : robot->bodies)
      if (taken(body.name))
        return reader.error(*nameNode, "robot \"" + *name + "\" makes a body named \"" + body.name +
                                           "\", which the world already has");
    for (BodyDef& body : robot->bodies) world.bodies.push_back(std::move(body));
    for (NamedJointDef& joint : robot->joints) world.joints.push_back(std::move(joint));
    for (auto& [body, looks] : robot->visuals) visuals[body] = std::move(looks);
    report.insert(report.end(), robot->report.begin(), robot->report.end());
  }
  return std::nullopt;
}

}  // namespace rbsim
