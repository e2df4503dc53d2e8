#include "robot/urdf_robot.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>
#include <iomanip>
#include <sstream>

#include "meshio/contained_path.h"
#include "meshio/mesh_io.h"
#include "robot/urdf_document.h"

namespace rbsim {

namespace {

// Bounds no robot comes near (as the config's): sizes and offsets in m.
constexpr double kMaxLength = 1e6;

struct Pose {
  Vec3 position = Vec3::Zero();
  Quaternion orientation = Quaternion::identity();
};

// (outer ∘ inner): a frame given in `inner` terms, placed by `outer`.
Pose compose(const Pose& outer, const Pose& inner) {
  return {outer.position + outer.orientation.rotate(inner.position), outer.orientation * inner.orientation};
}

Pose inverse(const Pose& pose) {
  const Quaternion back = pose.orientation.conjugate();
  return {-back.rotate(pose.position), back};
}

Vec3 vectorOf(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

Pose poseOf(const urdf::Pose& pose) {
  const urdf::Rotation& r = pose.rotation;
  return {vectorOf(pose.position), Quaternion{r.w, r.x, r.y, r.z}.normalized()};
}

std::string number(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

std::string vectorText(const Vec3& v) { return "(" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + ")"; }

// urdfdom reports its errors through console_bridge; while it parses, they
// are kept here (and not printed), to go into the error rbsim returns.
class CapturedLog : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN && first.empty()) first = text;
  }
  std::string first;
};

// console_bridge's handler is process-wide: one parse at a time.
std::mutex g_parseMutex;

// The line of the joint or link urdfdom's message names ("Joint [j] is of
// type REVOLUTE but ...", "... link [a] ..."), when tinyxml2's pass saw it:
// urdfdom's own messages carry no line.
std::string lineOfNamed(const std::string& message, const UrdfDocument& document) {
  for (std::size_t open = message.find('['); open != std::string::npos; open = message.find('[', open + 1)) {
    const std::size_t close = message.find(']', open);
    if (close == std::string::npos) break;
    const std::string name = message.substr(open + 1, close - open - 1);
    const auto joint = document.jointLine.find(name);
    if (joint != document.jointLine.end()) return std::to_string(joint->second);
    const auto link = document.linkLine.find(name);
    if (link != document.linkLine.end()) return std::to_string(link->second);
  }
  return "";
}

Expected<urdf::ModelInterfaceSharedPtr> parseModel(const std::string& xml, const std::string& sourceName,
                                                   const UrdfDocument& document) {
  const std::lock_guard<std::mutex> lock(g_parseMutex);
  CapturedLog log;
  console_bridge::useOutputHandler(&log);
  urdf::ModelInterfaceSharedPtr model;
  std::string thrown;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    thrown = e.what();
  }
  console_bridge::restorePreviousOutputHandler();
  if (model) return model;
  const std::string why = !thrown.empty() ? thrown : !log.first.empty() ? log.first : "urdfdom could not read it";
  const std::string line = lineOfNamed(why, document);
  return Error{sourceName + (line.empty() ? "" : ":" + line) + ": not a valid URDF: " + why};
}

const char* jointTypeText(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    case urdf::Joint::FIXED: return "fixed";
    default: return "unknown";
  }
}

bool moves(int type) {
  return type == urdf::Joint::REVOLUTE || type == urdf::Joint::CONTINUOUS || type == urdf::Joint::PRISMATIC;
}

bool hasMass(const urdf::Link& link) { return link.inertial && link.inertial->mass > 0.0; }

class RobotBuilder {
 public:
  RobotBuilder(const RobotPlacement& placement, const RobotFiles& files, UrdfDocument document,
               urdf::ModelInterfaceSharedPtr model)
      : m_placement(placement), m_files(files), m_document(std::move(document)), m_model(std::move(model)) {}

  Expected<RobotModel> build();

 private:
  // "arm.urdf:12: link 'forearm'", for messages.
  std::string linkAt(const std::string& link) const { return at(m_document.linkLine, link) + "link '" + link + "'"; }
  std::string jointAt(const std::string& joint) const {
    return at(m_document.jointLine, joint) + "joint '" + joint + "'";
  }
  std::string at(const std::map<std::string, int, std::less<>>& lines, const std::string& name) const {
    const auto found = lines.find(name);
    return m_files.sourceName + ":" + (found != lines.end() ? std::to_string(found->second) + ": " : std::string(" "));
  }
  std::string prefixed(const std::string& name) const { return m_placement.name + "/" + name; }

  std::optional<Error> checkJoints() const;
  void placeLinks(const urdf::Link& link, const Pose& pose);
  std::optional<Error> assignBodies();
  Expected<BodyDef> makeBody(const std::string& top);
  Expected<CompoundPartShape> makeShape(const urdf::Geometry& geometry, const std::string& link);
  Expected<CompoundPartShape> makeMesh(const urdf::Mesh& mesh, const std::string& link);
  Expected<std::string> meshFile(const std::string& uri, const std::string& link) const;
  Expected<std::string> confinedPackageFile(const std::string& uri, const std::string& package,
                                            const std::string& inside, const std::string& link) const;
  std::optional<Error> makeJoint(const urdf::Joint& joint);
  // Where a joint starts: its joint_positions entry, a follower's
  // multiplier · leader's + offset, or 0.
  double initialPosition(const urdf::Joint& joint) const;
  std::optional<Visual> makeVisual(const urdf::Visual& visual, const std::string& link, const Pose& inBody);
  std::string meshUrl(const std::string& path) const;

  const RobotPlacement& m_placement;
  const RobotFiles& m_files;
  UrdfDocument m_document;
  urdf::ModelInterfaceSharedPtr m_model;
  std::map<std::string, Pose, std::less<>> m_linkPose;        // world, at the initial joint positions
  std::map<std::string, std::string, std::less<>> m_bodyOf;  // link -> the link whose body it is part of
  std::string m_root;
  bool m_rootStatic = false;
  RobotModel m_out;
};

std::optional<Error> RobotBuilder::checkJoints() const {
  for (const auto& [name, joint] : m_model->joints_) {
    if (joint->type == urdf::Joint::PLANAR)
      return Error{jointAt(name) + ": planar joints are not supported (build the plane from two prismatic joints "
                                   "and a revolute one)"};
    if (joint->type == urdf::Joint::UNKNOWN) return Error{jointAt(name) + ": has no known type"};
    if (joint->mimic) {
      const urdf::JointMimic& mimic = *joint->mimic;
      const auto leader = m_model->joints_.find(mimic.joint_name);
      if (leader == m_model->joints_.end())
        return Error{jointAt(name) + ": <mimic joint='" + mimic.joint_name + "'>: the robot has no such joint"};
      if (!moves(joint->type) || !moves(leader->second->type))
        return Error{jointAt(name) + ": <mimic>: a revolute, continuous or prismatic joint follows another such joint ('" +
                     mimic.joint_name + "' is " + jointTypeText(leader->second->type) + ", this one " +
                     jointTypeText(joint->type) + ")"};
      if (!std::isfinite(mimic.multiplier) || !std::isfinite(mimic.offset))
        return Error{jointAt(name) + ": <mimic>: multiplier and offset must be finite"};
      // A chain of followers must end at a joint that leads.
      std::set<std::string> seen{name};
      for (auto at = leader->second; at->mimic; at = m_model->joints_.at(at->mimic->joint_name)) {
        if (!seen.insert(at->name).second || !m_model->joints_.count(at->mimic->joint_name))
          return Error{jointAt(name) + ": <mimic>: its leaders follow each other in a loop"};
      }
    }
    if (moves(joint->type)) {
      const Vec3 axis = vectorOf(joint->axis);
      if (!axis.allFinite() || axis.norm() < 1e-9) return Error{jointAt(name) + ": its <axis> is zero"};
    }
    if (joint->dynamics && (!(joint->dynamics->damping >= 0.0) || !(joint->dynamics->friction >= 0.0) ||
                            !std::isfinite(joint->dynamics->damping) || !std::isfinite(joint->dynamics->friction)))
      return Error{jointAt(name) + ": <dynamics> damping and friction must be finite and >= 0"};
    if (joint->limits && joint->type != urdf::Joint::CONTINUOUS &&
        (!std::isfinite(joint->limits->lower) || !std::isfinite(joint->limits->upper) ||
         joint->limits->lower > joint->limits->upper))
      return Error{jointAt(name) + ": <limit> needs finite lower <= upper, got lower " +
                   number(joint->limits->lower) + ", upper " + number(joint->limits->upper)};
  }
  for (const auto& [name, position] : m_placement.jointPositions) {
    const auto found = m_model->joints_.find(name);
    if (found == m_model->joints_.end())
      return Error{"joint_positions: the robot has no joint '" + name + "' (" + m_files.sourceName + ")"};
    const urdf::Joint& joint = *found->second;
    if (!moves(joint.type))
      return Error{"joint_positions: joint '" + name + "' is " + jointTypeText(joint.type) +
                   ": only revolute, continuous and prismatic joints take a position"};
    if (!std::isfinite(position)) return Error{"joint_positions: joint '" + name + "': not a finite number"};
    if (joint.mimic)
      return Error{"joint_positions: joint '" + name + "' follows joint '" + joint.mimic->joint_name +
                   "' (<mimic>): give its leader's position, which places both"};
    if (joint.type != urdf::Joint::CONTINUOUS && joint.limits &&
        (position < joint.limits->lower || position > joint.limits->upper))
      return Error{"joint_positions: joint '" + name + "' at " + number(position) + " is outside its limits [" +
                   number(joint.limits->lower) + ", " + number(joint.limits->upper) + "]"};
  }
  return std::nullopt;
}

// The link frames in the world: the root's where the placement puts it,
// each child's through its joint's origin and the joint's motion by its
// initial position (a turn about the axis, or a slide along it).
void RobotBuilder::placeLinks(const urdf::Link& link, const Pose& pose) {
  m_linkPose[link.name] = pose;
  for (const urdf::JointSharedPtr& joint : link.child_joints) {
    Pose motion;
    const double q = initialPosition(*joint);
    const Vec3 axis = moves(joint->type) ? Vec3(vectorOf(joint->axis).normalized()) : Vec3::UnitZ();
    if (joint->type == urdf::Joint::PRISMATIC) motion.position = q * axis;
    if (joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::CONTINUOUS)
      motion.orientation = Quaternion::fromAxisAngle(axis, q);
    const urdf::LinkConstSharedPtr child = m_model->getLink(joint->child_link_name);
    if (child) placeLinks(*child, compose(compose(pose, poseOf(joint->parent_to_joint_origin_transform)), motion));
  }
}

// Which body each link is part of: its own, or (held by a fixed joint, and
// massless or merging) its parent's.
std::optional<Error> RobotBuilder::assignBodies() {
  const urdf::Link& root = *m_model->getRoot();
  m_root = root.name;
  if (root.inertial && !(root.inertial->mass >= 0.0 && std::isfinite(root.inertial->mass)))
    return Error{linkAt(root.name) + ": its mass must be finite and >= 0"};
  m_rootStatic = m_placement.fixedBase || !hasMass(root);
  if (m_rootStatic)
    m_out.report.push_back("link '" + root.name + "' (the root) is static: " +
                           (m_placement.fixedBase ? std::string("fixed_base")
                                                  : "it has no mass (PyBullet's convention for a static base)"));
  // Parents before children: the document's order need not be the tree's.
  std::function<std::optional<Error>(const urdf::Link&)> visit = [&](const urdf::Link& link) -> std::optional<Error> {
    for (const urdf::JointSharedPtr& joint : link.child_joints) {
      const urdf::LinkConstSharedPtr child = m_model->getLink(joint->child_link_name);
      if (!child) continue;
      if (child->inertial && !(child->inertial->mass >= 0.0 && std::isfinite(child->inertial->mass)))
        return Error{linkAt(child->name) + ": its mass must be finite and >= 0"};
      const bool fixed = joint->type == urdf::Joint::FIXED;
      if (fixed && (!hasMass(*child) || m_placement.mergeFixedLinks)) {
        m_bodyOf[child->name] = m_bodyOf[link.name];
        m_out.report.push_back("link '" + child->name + "' merged into '" + m_bodyOf[link.name] + "' (fixed joint '" +
                               joint->name + "'" + (hasMass(*child) ? ", masses combined)" : ", it has no mass)"));
      } else if (!hasMass(*child)) {
        return Error{linkAt(child->name) + ": has no mass (no <inertial>, or mass 0) but moves on " +
                     jointTypeText(joint->type) + " joint '" + joint->name +
                     "': give it an <inertial>, or hold it with a fixed joint (it is then merged into its parent)"};
      } else {
        m_bodyOf[child->name] = child->name;
      }
      if (auto error = visit(*child)) return error;
    }
    return std::nullopt;
  };
  m_bodyOf[root.name] = root.name;
  return visit(root);
}

Expected<std::string> RobotBuilder::meshFile(const std::string& uri, const std::string& link) const {
  namespace fs = std::filesystem;
  const auto isFile = [](const fs::path& p) {
    std::error_code ignored;
    return fs::is_regular_file(p, ignored);
  };
  constexpr std::string_view kPackage = "package://", kFile = "file://";
  if (uri.rfind(kPackage, 0) == 0) {
    const std::string rest = uri.substr(kPackage.size());
    const std::size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0)
      return Error{linkAt(link) + ": mesh '" + uri + "' names no package (package://NAME/path)"};
    const std::string package = rest.substr(0, slash), inside = rest.substr(slash + 1);
    std::vector<std::string> directories = m_files.packagePaths;
    if (m_files.confinedTo) return confinedPackageFile(uri, package, inside, link);
    if (const char* rosPath = std::getenv("ROS_PACKAGE_PATH")) {
      std::stringstream list(rosPath);
      for (std::string directory; std::getline(list, directory, ':');)
        if (!directory.empty()) directories.push_back(directory);
    }
    for (const std::string& directory : directories) {
      const fs::path base(directory);
      if (isFile(base / package / inside)) return (base / package / inside).lexically_normal().string();
      if (base.filename() == package && isFile(base / inside)) return (base / inside).lexically_normal().string();
    }
    std::string searched;
    for (const std::string& directory : directories) searched += (searched.empty() ? "" : ", ") + directory;
    return Error{linkAt(link) + ": mesh '" + uri + "': package '" + package + "' not found in " +
                 (searched.empty() ? std::string("any package path (give package_paths, or set ROS_PACKAGE_PATH)")
                                   : searched)};
  }
  fs::path path(uri.rfind(kFile, 0) == 0 ? uri.substr(kFile.size()) : uri);
  if (m_files.confinedTo) {
    Expected<std::string> inside = resolveContainedFile((fs::path(m_files.directory) / path).string(), *m_files.confinedTo);
    if (!inside) return Error{linkAt(link) + ": mesh '" + uri + "': " + inside.error().message};
    return inside;
  }
  if (path.is_relative() && !m_files.directory.empty()) path = fs::path(m_files.directory) / path;
  if (!isFile(path)) return Error{linkAt(link) + ": mesh '" + uri + "': no such file (" + path.string() + ")"};
  return path.lexically_normal().string();
}

// package://NAME/inside of a confined robot: looked up in its package
// paths only, each inside the spawn directory.
Expected<std::string> RobotBuilder::confinedPackageFile(const std::string& uri, const std::string& package,
                                                        const std::string& inside, const std::string& link) const {
  namespace fs = std::filesystem;
  std::string why = "no package paths given";
  for (const std::string& directory : m_files.packagePaths) {
    const fs::path base(directory);
    std::vector<fs::path> candidates{base / package / inside};
    if (base.filename() == package) candidates.push_back(base / inside);
    for (const fs::path& candidate : candidates) {
      Expected<std::string> found = resolveContainedFile(candidate.string(), *m_files.confinedTo);
      if (found) return found;
      why = found.error().message;
    }
  }
  return Error{linkAt(link) + ": mesh '" + uri + "': package '" + package +
               "' not found in the package paths inside the spawn directory (" + why + ")"};
}

// A collision mesh collides as its convex hull: real descriptions' meshes
// are often open (many unmatched edges), and the mass comes from
// <inertial>, so only the hull matters. The hull is closed by construction.
Expected<CompoundPartShape> RobotBuilder::makeMesh(const urdf::Mesh& mesh, const std::string& link) {
  Expected<std::string> path = meshFile(mesh.filename, link);
  if (!path) return path.error();
  Expected<TriangleMesh> loaded = loadMesh(*path);
  if (!loaded) {
    std::string message = loaded.error().message;
    // A confined robot's sender learns nothing of the host's directories.
    if (m_files.confinedTo)
      for (std::size_t at = message.find(*path); at != std::string::npos; at = message.find(*path, at))
        message.replace(at, path->size(), mesh.filename);
    return Error{linkAt(link) + ": " + message};
  }
  const Vec3 scale = vectorOf(mesh.scale);
  if (!scale.allFinite() || scale.cwiseAbs().minCoeff() <= 0.0 || scale.cwiseAbs().maxCoeff() > kMaxLength)
    return Error{linkAt(link) + ": mesh '" + mesh.filename + "' has scale " + vectorText(scale) +
                 ": each factor must be nonzero and finite"};
  for (Vec3& vertex : loaded->vertices) {
    vertex = vertex.cwiseProduct(scale);
    if (!vertex.allFinite() || vertex.cwiseAbs().maxCoeff() > kMaxLength)
      return Error{linkAt(link) + ": mesh '" + mesh.filename + "' has a vertex that is not finite or lies beyond 1e6 m"};
  }
  // A mirroring scale turns the triangles inside out; the hull does not care.
  const Expected<bool> closed = validateClosedMesh(*loaded, *path);
  Expected<SimplifiedHullMesh> hull =
      simplifiedConvexHullMesh(loaded->vertices, m_placement.hullMaxVertices, m_placement.hullTolerance,
                               linkAt(link) + ": mesh '" + mesh.filename + "'");
  if (!hull) return hull.error();
  const std::size_t kept = hull->mesh.vertices.size();
  std::string simplified;
  if (kept < hull->fullVertexCount) {
    std::ostringstream text;
    text << ", simplified to " << kept << " vertices, the full hull within " << std::fixed
         << std::setprecision(2) << hull->outside * 1000.0 << " mm of their faces";
    simplified = text.str();
  }
  m_out.report.push_back("link '" + link + "': mesh '" + mesh.filename + "' (" +
                         std::to_string(loaded->triangles.size()) + " triangles, " +
                         (closed ? std::string("closed") : "open: " + closed.error().message) +
                         ") collides as its convex hull (" + std::to_string(hull->fullVertexCount) + " vertices" +
                         simplified + ")");
  return CompoundPartShape{MeshShape{mesh.filename, std::make_shared<const TriangleMesh>(std::move(hull->mesh))}};
}

Expected<CompoundPartShape> RobotBuilder::makeShape(const urdf::Geometry& geometry, const std::string& link) {
  const auto size = [](double v) { return std::isfinite(v) && v > 0.0 && v <= kMaxLength; };
  switch (geometry.type) {
    case urdf::Geometry::SPHERE: {
      const double radius = static_cast<const urdf::Sphere&>(geometry).radius;
      if (!size(radius)) return Error{linkAt(link) + ": a collision sphere's radius must be > 0, got " + number(radius)};
      return CompoundPartShape{SphereShape{radius}};
    }
    case urdf::Geometry::BOX: {
      const Vec3 dimensions = vectorOf(static_cast<const urdf::Box&>(geometry).dim);
      if (!size(dimensions.x()) || !size(dimensions.y()) || !size(dimensions.z()))
        return Error{linkAt(link) + ": a collision box's size must be > 0 on each axis, got " + vectorText(dimensions)};
      return CompoundPartShape{BoxShape{0.5 * dimensions}};
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
      if (!size(cylinder.radius) || !size(cylinder.length))
        return Error{linkAt(link) + ": a collision cylinder's radius and length must be > 0, got " +
                     number(cylinder.radius) + " and " + number(cylinder.length)};
      return CompoundPartShape{CylinderShape{cylinder.radius, 0.5 * cylinder.length}};  // along z, as URDF's
    }
    case urdf::Geometry::MESH:
      return makeMesh(static_cast<const urdf::Mesh&>(geometry), link);
  }
  return Error{linkAt(link) + ": a collision geometry of unknown type"};
}

Expected<BodyDef> RobotBuilder::makeBody(const std::string& top) {
  BodyDef body;
  body.name = prefixed(top);
  const Pose& frame = m_linkPose.at(top);
  body.position = frame.position;
  body.orientation = frame.orientation;
  body.isStatic = top == m_root && m_rootStatic;

  // The links this body is made of, as written, and where each sits in
  // the body's (top link's) frame.
  std::vector<std::string> members;
  for (const std::string& link : m_document.linkOrder)
    if (m_bodyOf.count(link) && m_bodyOf.at(link) == top) members.push_back(link);
  const Pose toBody = inverse(frame);
  std::vector<CompoundPart> parts;
  std::vector<PlacedMassProperties> masses;
  bool onlyTopMass = true;  // the mass is the top link's own
  for (const std::string& name : members) {
    const urdf::Link& link = *m_model->getLink(name);
    const Pose inBody = name == top ? Pose{} : compose(toBody, m_linkPose.at(name));
    for (const urdf::CollisionSharedPtr& collision : link.collision_array) {
      if (!collision || !collision->geometry) continue;
      Expected<CompoundPartShape> shape = makeShape(*collision->geometry, name);
      if (!shape) return shape.error();
      const Pose placed = compose(inBody, poseOf(collision->origin));
      parts.push_back(CompoundPart{std::move(*shape), placed.position, placed.orientation, std::nullopt});
    }
    for (const urdf::VisualSharedPtr& visual : link.visual_array) {
      if (!visual || !visual->geometry) continue;
      if (std::optional<Visual> made = makeVisual(*visual, name, inBody))
        m_out.visuals[body.name].push_back(std::move(*made));
    }
    if (!body.isStatic && hasMass(link)) {
      const urdf::Inertial& inertial = *link.inertial;
      Mat3 tensor;
      tensor << inertial.ixx, inertial.ixy, inertial.ixz, inertial.ixy, inertial.iyy, inertial.iyz, inertial.ixz,
          inertial.iyz, inertial.izz;
      // URDF gives the tensor in the <inertial>'s frame: R I Rᵀ in the link's.
      const Pose inertialFrame = poseOf(inertial.origin);
      const Mat3 rotation = inertialFrame.orientation.toRotationMatrix();
      const Mat3 inLink = rotation * tensor * rotation.transpose();
      if (!tensor.allFinite()) return Error{linkAt(name) + ": its <inertia> is not finite"};
      if (const std::optional<std::string> problem = inertiaTensorProblem(inLink))
        return Error{linkAt(name) + ": its <inertia> is not one a rigid body can have: " + *problem};
      MassProperties properties;
      properties.mass = inertial.mass;
      properties.centerOfMass = inertialFrame.position;
      properties.inertia = inLink;
      masses.push_back({properties, Transform::fromPose(inBody.position, inBody.orientation)});
      onlyTopMass = onlyTopMass && name == top;
    }
  }
  if (!body.isStatic) {
    // One link: its own numbers, as written (so that a robot and the same
    // bodies written in YAML are the same bits); several: their union.
    if (masses.empty()) return Error{linkAt(top) + ": has no mass"};
    const MassProperties whole = onlyTopMass ? masses.front().properties : combinedMassProperties(masses);
    body.mass = whole.mass;
    body.inertia = whole.inertia;
    body.centerOfMass = whole.centerOfMass;
  }
  if (parts.empty()) {
    // Nothing to collide with: the body is drawn as a small marker at its
    // frame; its mass properties are the given ones.
    body.collides = false;
    body.shape = SphereShape{0.01};
    m_out.report.push_back("body '" + body.name + "': no <collision>: collides with nothing");
  } else if (parts.size() == 1 && parts.front().position.isZero(0.0) &&
             parts.front().orientation.w == 1.0) {
    body.shape = toShape(parts.front().shape);
  } else {
    body.shape = CompoundShape{std::move(parts)};
  }
  m_out.report.push_back("body '" + body.name + "': " + (body.isStatic ? std::string("static") : number(*body.mass) + " kg") +
                         ", shape " + shapeTypeName(body.shape) +
                         (members.size() > 1 ? ", links " + std::to_string(members.size()) : std::string()));
  return body;
}

double RobotBuilder::initialPosition(const urdf::Joint& joint) const {
  const auto given = m_placement.jointPositions.find(joint.name);
  if (given != m_placement.jointPositions.end()) return given->second;
  if (joint.mimic) {  // checkJoints saw the leader and that the chain ends
    const urdf::Joint& leader = *m_model->joints_.at(joint.mimic->joint_name);
    return joint.mimic->multiplier * initialPosition(leader) + joint.mimic->offset;
  }
  return 0.0;
}

// Where the viewer fetches a visual mesh: its path relative to the
// directory the bridge serves under the robot's mesh route, when it lies
// there by the rules spawned files follow (contained_path.h: no link
// leading out, a regular file); "" otherwise.
std::string RobotBuilder::meshUrl(const std::string& path) const {
  namespace fs = std::filesystem;
  if (m_files.meshRoute.empty()) return "";
  std::error_code error;
  const fs::path root = fs::canonical(m_files.meshRouteDirectory.empty() ? "." : m_files.meshRouteDirectory, error);
  if (error) return "";
  const fs::path file = fs::canonical(path, error);
  if (error) return "";
  const fs::path relative = file.lexically_relative(root);
  if (relative.empty() || *relative.begin() == ".." || relative.is_absolute()) return "";
  if (!resolveContainedFile(relative.string(), root.string())) return "";
  return m_files.meshRoute + "/" + relative.generic_string();
}

// A <visual> as the viewer draws it, in the body's shape frame; nullopt
// (and a line in the report) when it cannot be drawn: drawing is no reason
// to refuse a robot.
std::optional<Visual> RobotBuilder::makeVisual(const urdf::Visual& visual, const std::string& link,
                                               const Pose& inBody) {
  const auto size = [](double v) { return std::isfinite(v) && v > 0.0 && v <= kMaxLength; };
  const auto skip = [&](const std::string& why) {
    m_out.report.push_back("link '" + link + "': a <visual> is not drawn: " + why);
    return std::nullopt;
  };
  Visual out;
  const Pose placed = compose(inBody, poseOf(visual.origin));
  if (!placed.position.allFinite() || placed.position.cwiseAbs().maxCoeff() > kMaxLength)
    return skip("its origin is not finite or lies beyond 1e6 m");
  out.position = placed.position;
  out.orientation = placed.orientation;
  std::string what;
  const urdf::Geometry& geometry = *visual.geometry;
  switch (geometry.type) {
    case urdf::Geometry::SPHERE:
      out.kind = Visual::Kind::Sphere;
      out.radius = static_cast<const urdf::Sphere&>(geometry).radius;
      if (!size(out.radius)) return skip("a sphere's radius must be > 0");
      what = "sphere";
      break;
    case urdf::Geometry::BOX: {
      out.kind = Visual::Kind::Box;
      const Vec3 dimensions = vectorOf(static_cast<const urdf::Box&>(geometry).dim);
      if (!size(dimensions.x()) || !size(dimensions.y()) || !size(dimensions.z()))
        return skip("a box's size must be > 0 on each axis");
      out.halfExtents = 0.5 * dimensions;
      what = "box";
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
      out.kind = Visual::Kind::Cylinder;
      out.radius = cylinder.radius;
      out.halfLength = 0.5 * cylinder.length;
      if (!size(cylinder.radius) || !size(cylinder.length)) return skip("a cylinder's radius and length must be > 0");
      what = "cylinder";
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
      out.kind = Visual::Kind::Mesh;
      out.meshFile = mesh.filename;
      std::string extension = std::filesystem::path(mesh.filename).extension().string();
      std::transform(extension.begin(), extension.end(), extension.begin(),
                     [](unsigned char c) { return std::tolower(c); });
      if (extension != ".stl" && extension != ".obj" && extension != ".dae")
        return skip("mesh '" + mesh.filename + "': the viewer draws STL, OBJ and COLLADA (.dae) files");
      out.scale = vectorOf(mesh.scale);
      if (!out.scale.allFinite() || out.scale.cwiseAbs().minCoeff() <= 0.0 || out.scale.cwiseAbs().maxCoeff() > kMaxLength)
        return skip("mesh '" + mesh.filename + "': each scale factor must be nonzero and finite");
      Expected<std::string> path = meshFile(mesh.filename, link);
      if (!path) return skip(path.error().message);
      out.meshUrl = meshUrl(*path);
      what = "mesh '" + mesh.filename + "' " +
             (out.meshUrl.empty() ? "(outside the directory the viewer serves (" +
                                        (m_files.meshRoute.empty() ? std::string("none") : m_files.meshRoute) +
                                        "): drawn from the collision shape)"
                                  : "(served as " + out.meshUrl + ")");
      break;
    }
    default:
      return skip("a geometry of unknown type");
  }
  // URDF's materials: inline, or by the name of a robot-level <material>
  // (urdfdom resolves the name for a link's first visual only).
  urdf::MaterialSharedPtr material = visual.material;
  if (!visual.material_name.empty())
    if (urdf::MaterialSharedPtr named = m_model->getMaterial(visual.material_name)) material = named;
  if (material) {
    const urdf::Color& c = material->color;
    const bool defaultColor = c.r == 0.0f && c.g == 0.0f && c.b == 0.0f && c.a == 1.0f;
    // urdfdom leaves (0, 0, 0, 1) where a material gave a texture or only a
    // name: no colour of its own then.
    const bool unresolvedName = !material->name.empty() && !m_model->getMaterial(material->name) && defaultColor;
    if (!(defaultColor && !material->texture_filename.empty()) && !unresolvedName) {
      out.hasColor = true;
      const auto unit = [](float v) { return std::isfinite(v) ? std::clamp(static_cast<double>(v), 0.0, 1.0) : 0.0; };
      out.rgba = {unit(c.r), unit(c.g), unit(c.b), unit(c.a)};
      what += ", colour (" + number(out.rgba[0]) + ", " + number(out.rgba[1]) + ", " + number(out.rgba[2]) + ", " +
              number(out.rgba[3]) + ")";
    }
  }
  m_out.report.push_back("link '" + link + "': drawn as " + what);
  return out;
}

std::optional<Error> RobotBuilder::makeJoint(const urdf::Joint& joint) {
  const std::string& parent = m_bodyOf.at(joint.parent_link_name);
  const std::string& child = m_bodyOf.at(joint.child_link_name);
  if (parent == child) return std::nullopt;  // merged
  if (joint.type == urdf::Joint::FLOATING) {
    m_out.report.push_back("joint '" + joint.name + "' (floating): '" + prefixed(child) + "' moves freely");
    return std::nullopt;
  }
  NamedJointDef out;
  JointDef& def = out.def;
  def.name = prefixed(joint.name);
  out.bodyA = prefixed(parent);
  out.bodyB = prefixed(child);
  out.source = jointAt(joint.name);
  // The joint's frame in the world, with the joint at its initial position.
  const Pose frame = compose(m_linkPose.at(joint.parent_link_name), poseOf(joint.parent_to_joint_origin_transform));
  def.anchor = frame.position;
  if (moves(joint.type)) def.axis = frame.orientation.rotate(vectorOf(joint.axis).normalized());
  def.position = initialPosition(joint);
  std::string detail;
  switch (joint.type) {
    case urdf::Joint::FIXED:
      def.type = JointType::Fixed;
      break;
    case urdf::Joint::PRISMATIC:
    case urdf::Joint::REVOLUTE:
      def.type = joint.type == urdf::Joint::PRISMATIC ? JointType::Prismatic : JointType::Revolute;
      if (joint.limits) {
        def.limit = {true, joint.limits->lower, joint.limits->upper};
        detail += ", limits [" + number(def.limit.lower) + ", " + number(def.limit.upper) + "]";
      }
      break;
    case urdf::Joint::CONTINUOUS:
      def.type = JointType::Revolute;
      break;
    default:
      return Error{jointAt(joint.name) + ": type " + jointTypeText(joint.type) + " is not supported"};
  }
  if (joint.mimic) {
    def.mimic = {true, prefixed(joint.mimic->joint_name), joint.mimic->multiplier, joint.mimic->offset};
    detail += ", follows '" + def.mimic.leader + "' (× " + number(def.mimic.multiplier) + " + " +
              number(def.mimic.offset) + ")";
  }
  if (joint.dynamics) {
    def.damping = joint.dynamics->damping;
    def.friction = joint.dynamics->friction;
    if (def.damping > 0.0 || def.friction > 0.0)
      detail += ", damping " + number(def.damping) + ", friction " + number(def.friction);
  }
  m_out.report.push_back("joint '" + def.name + "': " + jointTypeText(joint.type) + " '" + out.bodyA + "' -> '" +
                         out.bodyB + "'" + (moves(joint.type) ? ", axis " + vectorText(def.axis) : std::string()) +
                         detail);
  // A zero pose beyond a limit (published legs often have one): the body
  // starts where the description puts it and the limit brings it back.
  if (def.limit.enabled && (def.position < def.limit.lower || def.position > def.limit.upper)) {
    const bool below = def.position < def.limit.lower;
    const double by = below ? def.limit.lower - def.position : def.position - def.limit.upper;
    m_out.report.push_back("joint '" + def.name + "' starts at " + number(def.position) + ", " + number(by) +
                           (joint.type == urdf::Joint::PRISMATIC ? " m" : " rad") + (below ? " below" : " above") +
                           " its " + (below ? "lower" : "upper") + " limit " +
                           number(below ? def.limit.lower : def.limit.upper) +
                           ": the limit brings it back over its first steps (positions only, no velocity)");
  }
  // <limit effort velocity> bound the joint's actuator, whatever it is
  // commanded. Descriptions of passive joints often write 0 for either,
  // meaning "not given": that leaves it uncapped, and the report says so.
  if (joint.limits && moves(joint.type)) {
    const bool prismatic = joint.type == urdf::Joint::PRISMATIC;
    std::string limits;
    const auto take = [&](double value, double& into, const char* what, const char* unit) {
      if (!limits.empty()) limits += ", ";
      if (value > 0.0) {
        into = value;
        limits += std::string(what) + " " + number(value) + " " + unit;
      } else {
        limits += std::string(what) + " " + number(value) + " (none: uncapped)";
      }
    };
    take(joint.limits->effort, def.actuatorLimits.effort, "effort", prismatic ? "N" : "N·m");
    take(joint.limits->velocity, def.actuatorLimits.rate, "rate", prismatic ? "m/s" : "rad/s");
    m_out.report.push_back("joint '" + def.name + "': actuator limits " + limits);
  }
  m_out.joints.push_back(std::move(out));
  return std::nullopt;
}

Expected<RobotModel> RobotBuilder::build() {
  if (auto error = checkJoints()) return *error;
  const urdf::LinkConstSharedPtr root = m_model->getRoot();
  if (!root) return Error{m_files.sourceName + ": the robot has no root link"};
  m_out.report.push_back("robot '" + m_placement.name + "' from " + m_files.sourceName + " (URDF robot '" +
                         m_model->getName() + "'): " + std::to_string(m_model->links_.size()) + " links, " +
                         std::to_string(m_model->joints_.size()) + " joints");
  placeLinks(*root, {m_placement.position, m_placement.orientation});
  if (auto error = assignBodies()) return *error;
  for (const std::string& link : m_document.linkOrder) {
    if (!m_bodyOf.count(link)) {
      return Error{linkAt(link) + ": is not joined to the root link '" + m_root + "'"};
    }
    if (m_bodyOf.at(link) != link) continue;
    Expected<BodyDef> body = makeBody(link);
    if (!body) return body.error();
    m_out.bodies.push_back(std::move(*body));
  }
  for (const std::string& link : m_document.linkOrder) m_out.linkBodies.emplace_back(link, prefixed(m_bodyOf.at(link)));
  // Joints in the order their child links are written.
  for (const std::string& link : m_document.linkOrder) {
    const urdf::LinkConstSharedPtr l = m_model->getLink(link);
    if (l && l->parent_joint)
      if (auto error = makeJoint(*l->parent_joint)) return *error;
  }
  // A follower after its leader (the world resolves a mimic's leader when
  // the follower is made): stable, leaders in the order above.
  std::vector<NamedJointDef> ordered;
  std::set<std::string> made;
  while (ordered.size() < m_out.joints.size()) {
    const std::size_t before = ordered.size();
    for (NamedJointDef& joint : m_out.joints) {
      if (made.count(joint.def.name) || (joint.def.mimic.enabled && !made.count(joint.def.mimic.leader))) continue;
      made.insert(joint.def.name);
      ordered.push_back(joint);
    }
    if (ordered.size() == before)  // checkJoints rules this out; a guard, not a loop forever
      return Error{m_files.sourceName + ": a <mimic> leader is not a joint rbsim makes"};
  }
  m_out.joints = std::move(ordered);
  for (const UnusedUrdfElement& unused : m_document.unused)
    m_out.report.push_back("not used: " + m_files.sourceName + ":" + std::to_string(unused.line) + ": " +
                           unused.element + ": " + unused.reason);
  return std::move(m_out);
}

}  // namespace

Expected<RobotModel> buildRobot(const std::string& xml, const RobotPlacement& placement, const RobotFiles& files) {
  Expected<UrdfDocument> document = readUrdfDocument(xml, files.sourceName);
  if (!document) return document.error();
  Expected<urdf::ModelInterfaceSharedPtr> model = parseModel(xml, files.sourceName, *document);
  if (!model) return model.error();
  return RobotBuilder(placement, files, std::move(*document), std::move(*model)).build();
}

Expected<RobotModel> loadRobot(const std::string& path, const RobotPlacement& placement, RobotFiles files) {
  // A description is text of a few hundred kB at most; this bounds what an
  // untrusted path can make the loader read.
  constexpr std::uintmax_t kMaxUrdfBytes = 64u << 20;
  const std::string unreadable =
      files.sourceName + ": cannot read the URDF file" + (files.confinedTo ? std::string() : " (" + path + ")");
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error || !std::filesystem::is_regular_file(path, error)) return Error{unreadable};
  if (size > kMaxUrdfBytes) return Error{files.sourceName + ": larger than 64 MiB: not a robot description"};
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) return Error{unreadable};
  // Confined, the directory is the sender's (relative to the spawn
  // directory), never the host's.
  if (files.directory.empty() && !files.confinedTo) files.directory = std::filesystem::path(path).parent_path().string();
  return buildRobot(text.str(), placement, files);
}

}  // namespace rbsim
