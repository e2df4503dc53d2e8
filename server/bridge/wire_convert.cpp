#include "bridge/wire_convert.h"

#include "config/closest_names.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

namespace rbsim {

namespace {

template <std::size_t N>
void copyTo(double (&out)[N], const Vec3& v) {
  static_assert(N == 3);
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

void copyTo(double (&out)[4], const Quaternion& q) {
  out[0] = q.w;
  out[1] = q.x;
  out[2] = q.y;
  out[3] = q.z;
}

Vec3 vec3From(const double (&in)[3]) { return {in[0], in[1], in[2]}; }

// The guard's reason as one word for the wire: "linear speed" -> "linear_speed".
std::string frozenToken(BodyView body) {
  if (!body.isFrozen()) return "";
  std::string token(freezeReasonName(body.freezeReason()));
  std::replace(token.begin(), token.end(), ' ', '_');
  std::replace(token.begin(), token.end(), '-', '_');
  return token;
}

rbsim::body_state_t bodyState(BodyView body) {
  rbsim::body_state_t out;
  out.frozen = frozenToken(body);
  out.id = body.serial();
  out.name = body.name();
  copyTo(out.position, body.position());
  copyTo(out.orientation, body.orientation());
  copyTo(out.linear_velocity, body.linearVelocity());
  copyTo(out.angular_velocity, body.angularVelocity());
  return out;
}

// The dimensions of a solid, into the same-named fields of a
// body_description_t or a compound_part_t (zero for the other shapes').
template <class Message>
void copyDimensions(Message& out, const CompoundPartShape& shape) {
  out.radius = 0.0;
  out.half_length = 0.0;
  copyTo(out.half_extents, Vec3::Zero());
  out.num_vertices = 0;
  out.num_triangles = 0;
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, SphereShape>) {
          out.radius = s.radius;
        } else if constexpr (std::is_same_v<S, BoxShape>) {
          copyTo(out.half_extents, s.halfExtents);
        } else if constexpr (std::is_same_v<S, CylinderShape> || std::is_same_v<S, CapsuleShape>) {
          out.radius = s.radius;
          out.half_length = s.halfLength;
        } else {
          static_assert(std::is_same_v<S, MeshShape>);
          out.mesh_file = s.file;
          // Vertices in the shape's (or part's) own frame.
          const TriangleMesh& mesh = *s.mesh;
          out.num_vertices = static_cast<int32_t>(mesh.vertices.size());
          out.vertices.resize(mesh.vertices.size(), std::vector<double>(3));
          for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
            for (int k = 0; k < 3; ++k)
              out.vertices[i][static_cast<std::size_t>(k)] = mesh.vertices[i][k];
          out.num_triangles = static_cast<int32_t>(mesh.triangles.size());
          out.triangles.resize(mesh.triangles.size(), std::vector<int32_t>(3));
          for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
            for (std::size_t k = 0; k < 3; ++k) out.triangles[i][k] = mesh.triangles[i][k];
        }
      },
      shape);
}

rbsim::compound_part_t compoundPart(const CompoundPart& part) {
  rbsim::compound_part_t out;
  out.shape_type = shapeTypeName(part.shape);
  copyTo(out.position, part.position);
  copyTo(out.orientation, part.orientation.normalized());
  copyDimensions(out, part.shape);
  return out;
}

rbsim::body_description_t bodyDescription(BodyView body) {
  const BodyDescription& d = body.description();
  rbsim::body_description_t out;
  out.id = body.serial();
  out.name = d.name;
  out.frozen = frozenToken(body);
  out.is_static = d.isStatic;
  out.mass = body.mass();
  copyTo(out.inertia, body.dynamics().inertiaBody);
  out.mass_properties_given = d.massPropertiesGiven;
  out.collides = d.collides;
  out.collision_group = d.collisionFilter.group;
  out.collision_mask = d.collisionFilter.mask;
  out.linear_damping = body.dynamics().linearDamping;
  out.angular_damping = body.dynamics().angularDamping;
  out.shape_type = shapeTypeName(d.shape);
  copyTo(out.shape_position, d.shapeTranslation);
  copyTo(out.shape_orientation, Quaternion::fromRotationMatrix(d.shapeRotation));
  out.radius = 0.0;
  out.half_length = 0.0;
  out.plane_offset = 0.0;
  copyTo(out.half_extents, Vec3::Zero());
  copyTo(out.plane_normal, Vec3::Zero());
  out.num_vertices = 0;
  out.num_triangles = 0;
  out.num_parts = 0;
  out.num_visuals = 0;
  if (const auto* plane = std::get_if<PlaneShape>(&d.shape)) {
    copyTo(out.plane_normal, plane->normal);
    out.plane_offset = plane->offset;
  } else if (const auto* compound = std::get_if<CompoundShape>(&d.shape)) {
    // Each part is placed in the shape frame, which shape_position and
    // shape_orientation place in body space, as for any shape.
    for (const CompoundPart& part : compound->parts) out.parts.push_back(compoundPart(part));
    out.num_parts = static_cast<int32_t>(out.parts.size());
  } else if (const auto* trimesh = std::get_if<TriangleMeshShape>(&d.shape)) {
    // Sent as a mesh is (vertices and triangles in the shape frame); only
    // shape_type says "trimesh".
    copyDimensions(out, CompoundPartShape{MeshShape{trimesh->file, trimesh->mesh}});
  } else if (auto solid = toPartShape(d.shape)) {
    copyDimensions(out, *solid);
  }
  return out;
}

rbsim::visual_t visualMessage(const Visual& visual) {
  rbsim::visual_t out;
  switch (visual.kind) {
    case Visual::Kind::Box: out.kind = "box"; break;
    case Visual::Kind::Sphere: out.kind = "sphere"; break;
    case Visual::Kind::Cylinder: out.kind = "cylinder"; break;
    case Visual::Kind::Mesh: out.kind = "mesh"; break;
  }
  copyTo(out.position, visual.position);
  copyTo(out.orientation, visual.orientation.normalized());
  copyTo(out.half_extents, visual.halfExtents);
  out.radius = visual.radius;
  out.half_length = visual.halfLength;
  out.mesh_url = visual.meshUrl;
  copyTo(out.scale, visual.kind == Visual::Kind::Mesh ? visual.scale : Vec3::Zero());
  out.has_color = visual.hasColor;
  for (std::size_t k = 0; k < 4; ++k) out.rgba[k] = visual.hasColor ? visual.rgba[k] : 0.0;
  return out;
}

// A joint's side by body name; the world (a null id) is "world", as world
// files name it.
std::string sideName(const World& world, BodyId id) {
  if (id.isNull() || !world.isValid(id)) return "world";
  return world.body(id).name();
}

rbsim::joint_state_t jointStateMessage(const JointState& state) {
  rbsim::joint_state_t out;
  out.name = state.name;
  out.position = state.position;
  out.rate = state.rate;
  copyTo(out.rotation, state.rotation);
  copyTo(out.force, state.force);
  copyTo(out.torque, state.torque);
  out.effort = state.axisEffort;
  out.at_limit = static_cast<int8_t>(state.atLimit);
  out.error = state.error;
  out.active = state.active;
  return out;
}

rbsim::joint_description_t jointDescription(const World& world, int denseIndex) {
  const JointState state = world.jointStateAt(denseIndex);
  const JointDef& def = world.jointDefinitionAt(denseIndex);
  rbsim::joint_description_t out;
  out.name = state.name;
  out.type = jointTypeName(state.type);
  out.body_a = sideName(world, state.bodyA);
  out.body_b = sideName(world, state.bodyB);
  copyTo(out.anchor_a, state.anchorA);
  copyTo(out.anchor_b, state.anchorB);
  copyTo(out.axis, state.axis);
  out.limit_enabled = def.limit.enabled;
  out.lower_limit = def.limit.lower;
  out.upper_limit = def.limit.upper;
  // createJoint resolved a rod's length from its anchors where none was given.
  const bool spring = state.type == JointType::Distance && def.drive.enabled;
  out.length = state.type == JointType::Distance && (!def.limit.enabled || spring) ? def.length : 0.0;
  out.spring = spring;
  out.cone_angle = state.type == JointType::Spherical ? def.coneAngle : 0.0;
  // The unlimited actuator (infinite in JointDef) is 0 on the wire, where
  // a limit is always positive.
  const bool axial = state.type == JointType::Revolute || state.type == JointType::Prismatic;
  const auto limitOrZero = [axial](double limit) { return axial && std::isfinite(limit) ? limit : 0.0; };
  out.initial_position = axial ? def.position : 0.0;
  out.effort_limit = limitOrZero(def.actuatorLimits.effort);
  out.rate_limit = limitOrZero(def.actuatorLimits.rate);
  out.damping = axial ? def.damping : 0.0;
  out.friction = axial ? def.friction : 0.0;
  return out;
}

// Splits items into pages whose encoded size stays under the budget. The
// Fields policy names the page type's list and counters (bodies for states
// and world descriptions, contacts for contacts).
struct BodyFields {
  template <class Page>
  static auto& items(Page& page) { return page.bodies; }
  template <class Page>
  static void setCounts(Page& page, int32_t first, int32_t count, int32_t total) {
    page.first_body_index = first;
    page.num_bodies = count;
    page.total_bodies = total;
  }
};
struct JointFields {
  template <class Page>
  static auto& items(Page& page) { return page.joints; }
  template <class Page>
  static void setCounts(Page& page, int32_t first, int32_t count, int32_t total) {
    page.first_joint_index = first;
    page.num_joints = count;
    page.total_joints = total;
  }
};
struct ContactFields {
  template <class Page>
  static auto& items(Page& page) { return page.contacts; }
  template <class Page>
  static void setCounts(Page& page, int32_t first, int32_t count, int32_t total) {
    page.first_contact_index = first;
    page.num_contacts = count;
    page.total_contacts = total;
  }
};

// `header` needs only its own fields: paginate sets every paging field.
template <class Fields, class Page, class Item>
std::vector<Page> paginate(Page header, std::vector<Item> items) {
  header.page = 0;
  header.num_pages = 1;
  Fields::setCounts(header, 0, 0, 0);
  std::vector<Page> pages;
  std::vector<int32_t> firstIndex;
  Page current = header;
  const auto emptySize = static_cast<std::size_t>(header.getEncodedSize());
  std::size_t size = emptySize;
  int32_t index = 0;
  firstIndex.push_back(0);
  for (Item& item : items) {
    const auto itemSize = static_cast<std::size_t>(item._getEncodedSizeNoHash());
    if (!Fields::items(current).empty() && size + itemSize > kMaxPagePayloadBytes) {
      pages.push_back(std::move(current));
      current = header;
      firstIndex.push_back(index);
      size = emptySize;
    }
    Fields::items(current).push_back(std::move(item));
    size += itemSize;
    ++index;
  }
  pages.push_back(std::move(current));
  for (std::size_t i = 0; i < pages.size(); ++i) {
    pages[i].page = static_cast<int32_t>(i);
    pages[i].num_pages = static_cast<int32_t>(pages.size());
    Fields::setCounts(pages[i], firstIndex[i], static_cast<int32_t>(Fields::items(pages[i]).size()),
                      index);
  }
  return pages;
}

bool finite3(const double (&v)[3]) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

}  // namespace

std::vector<rbsim::world_state_t> worldStatePages(const World& world, int64_t utime,
                                                  int64_t revision) {
  rbsim::world_state_t header;
  header.utime = utime;
  header.step = world.stepCount();
  header.sim_time = world.time();
  header.world_revision = revision;
  std::vector<rbsim::body_state_t> bodies;
  bodies.reserve(world.bodies().size());
  for (const BodyView body : world.bodies()) bodies.push_back(bodyState(body));
  return paginate<BodyFields>(header, std::move(bodies));
}

std::vector<rbsim::world_t> worldDescriptionPages(const World& world, int64_t utime,
                                                  int64_t revision, const BodyVisuals* visuals) {
  rbsim::world_t header;
  header.utime = utime;
  header.step = world.stepCount();
  header.sim_time = world.time();
  header.world_revision = revision;
  header.dt = world.settings().dt;
  copyTo(header.gravity, world.settings().gravity);
  header.integrator = std::string(integratorName(world.settings().integrator));
  header.linear_damping = world.settings().linearDamping;
  header.angular_damping = world.settings().angularDamping;
  header.total_joints = 0;
  header.first_joint_index = 0;
  header.num_joints = 0;
  std::vector<rbsim::body_description_t> bodies;
  bodies.reserve(world.bodies().size());
  for (const BodyView body : world.bodies()) {
    bodies.push_back(bodyDescription(body));
    if (visuals == nullptr) continue;
    const auto looks = visuals->find(body.name());
    if (looks == visuals->end()) continue;
    for (const Visual& visual : looks->second) bodies.back().visuals.push_back(visualMessage(visual));
    bodies.back().num_visuals = static_cast<int32_t>(bodies.back().visuals.size());
  }
  std::vector<rbsim::world_t> pages = paginate<BodyFields>(header, std::move(bodies));

  // The joints after the bodies: into the last page while it has room, then
  // into pages of their own (whose body counters say no bodies, from the
  // end of the list).
  const int32_t totalJoints = world.jointCount();
  const int32_t totalBodies = pages.back().total_bodies;
  rbsim::world_t* current = &pages.back();
  auto size = static_cast<std::size_t>(current->getEncodedSize());
  for (int32_t i = 0; i < totalJoints; ++i) {
    rbsim::joint_description_t joint = jointDescription(world, i);
    const auto jointSize = static_cast<std::size_t>(joint._getEncodedSizeNoHash());
    if ((current->num_bodies > 0 || current->num_joints > 0) && size + jointSize > kMaxPagePayloadBytes) {
      rbsim::world_t next = header;
      BodyFields::setCounts(next, totalBodies, 0, totalBodies);
      next.first_joint_index = i;
      pages.push_back(std::move(next));
      current = &pages.back();
      size = static_cast<std::size_t>(current->getEncodedSize());
    }
    current->joints.push_back(std::move(joint));
    current->num_joints = static_cast<int32_t>(current->joints.size());
    size += jointSize;
  }
  int32_t firstJoint = 0;
  for (std::size_t i = 0; i < pages.size(); ++i) {
    pages[i].page = static_cast<int32_t>(i);
    pages[i].num_pages = static_cast<int32_t>(pages.size());
    pages[i].total_joints = totalJoints;
    pages[i].first_joint_index = firstJoint;
    firstJoint += pages[i].num_joints;
  }
  return pages;
}

std::vector<rbsim::joints_t> jointStatePages(const World& world, int64_t utime, int64_t revision) {
  rbsim::joints_t header;
  header.utime = utime;
  header.step = world.stepCount();
  header.sim_time = world.time();
  header.world_revision = revision;
  std::vector<rbsim::joint_state_t> joints;
  joints.reserve(static_cast<std::size_t>(world.jointCount()));
  for (int i = 0; i < world.jointCount(); ++i) joints.push_back(jointStateMessage(world.jointStateAt(i)));
  return paginate<JointFields>(header, std::move(joints));
}

std::vector<rbsim::contacts_t> contactPages(const World& world, int64_t utime) {
  rbsim::contacts_t header;
  header.utime = utime;
  header.step = world.stepCount();
  header.sim_time = world.time();
  const double epsilon = world.settings().contact.classificationEpsilon;
  std::vector<rbsim::contact_t> contacts;
  for (const SolvedManifold& m : world.contacts()) {
    for (int p = 0; p < m.pointCount; ++p) {
      const SolvedContactPoint& point = m.points[p];
      rbsim::contact_t c;
      c.body_a = m.serialA;
      c.body_b = m.serialB;
      copyTo(c.position, point.point);
      copyTo(c.normal, m.normal);
      c.depth = point.depth;
      c.normal_velocity = point.relativeNormalVelocity;
      switch (classifyContact(point.relativeNormalVelocity, epsilon)) {
        case ContactKind::Colliding:
          c.classification = rbsim::contact_t::COLLIDING;
          break;
        case ContactKind::Resting:
          c.classification = rbsim::contact_t::RESTING;
          break;
        case ContactKind::Separating:
          c.classification = rbsim::contact_t::SEPARATING;
          break;
      }
      c.normal_impulse = point.normalImpulse;
      copyTo(c.friction_impulse, point.tangentImpulse);
      contacts.push_back(c);
    }
  }
  return paginate<ContactFields>(header, std::move(contacts));
}

namespace {

Expected<WrenchFrame> wrenchFrameFrom(int8_t value, const char* field) {
  if (value == rbsim::wrench_t::FRAME_WORLD) return WrenchFrame::World;
  if (value == rbsim::wrench_t::FRAME_BODY) return WrenchFrame::ShapeFrame;
  return Error{std::string("unknown ") + field + " " + std::to_string(value)};
}

}  // namespace

std::string unknownJointReason(const World& world, const std::string& name) {
  std::vector<std::string> names;
  names.reserve(static_cast<std::size_t>(world.jointCount()));
  for (int i = 0; i < world.jointCount(); ++i) names.push_back(world.jointDefinitionAt(i).name);
  return "unknown joint '" + name + "'" + didYouMean(name, names);
}

std::string unknownBodyReason(const World& world, const std::string& name) {
  std::vector<std::string> names;
  names.reserve(static_cast<std::size_t>(world.bodyCount()));
  for (BodyView body : world.bodies()) names.push_back(body.name());
  return "unknown body '" + name + "'" + didYouMean(name, names);
}

Expected<JointCommandRequest> jointCommandRequestFrom(const rbsim::joint_command_t& message,
                                                      const World& world, int64_t nextStep,
                                                      const WrenchLimits& limits) {
  JointCommandRequest request;
  request.client = message.client;
  request.seq = message.seq;
  request.joint = message.joint;
  switch (message.mode) {
    case rbsim::joint_command_t::MODE_OFF:
      request.mode = JointCommandMode::Off;
      break;
    case rbsim::joint_command_t::MODE_VELOCITY:
      request.mode = JointCommandMode::Velocity;
      break;
    case rbsim::joint_command_t::MODE_POSITION:
      request.mode = JointCommandMode::Position;
      break;
    case rbsim::joint_command_t::MODE_EFFORT:
      request.mode = JointCommandMode::Effort;
      break;
    default:
      return Error{"mode: unknown mode " + std::to_string(message.mode) +
                   " (OFF 0, VELOCITY 1, POSITION 2, EFFORT 3)"};
  }

  const JointId id = world.findJoint(message.joint);
  if (id.isNull()) return Error{"joint: " + unknownJointReason(world, message.joint)};
  const JointDef& def = world.jointDefinition(id);
  const bool revolute = def.type == JointType::Revolute;
  // A distance joint made with a spring: MODE_POSITION sets its rest length
  // and gains.
  const bool spring = def.type == JointType::Distance && def.drive.enabled;
  if (!revolute && def.type != JointType::Prismatic && !spring)
    return Error{"joint: '" + message.joint + "' is a " + jointTypeName(def.type) +
                 " joint, which has no axis to actuate (only revolute and prismatic joints take joint commands, "
                 "and distance joints made with a spring MODE_POSITION)"};
  if (def.mimic.enabled && request.mode != JointCommandMode::Off)
    return Error{"joint: '" + message.joint + "' follows joint '" + def.mimic.leader +
                 "' (mimic): command its leader, which moves both"};
  if (spring && request.mode != JointCommandMode::Position)
    return Error{"mode: '" + message.joint +
                 "' is a distance spring, which takes only MODE_POSITION (target: its rest length in m; stiffness, "
                 "damping, max_effort)"};

  if (message.apply_at_step == -1) {
    request.firstStep = nextStep;
  } else if (message.apply_at_step < nextStep) {
    return Error{"apply_at_step " + std::to_string(message.apply_at_step) +
                 " is in the past (next step is " + std::to_string(nextStep) + ")"};
  } else if (message.apply_at_step - nextStep > limits.maxStepsAhead) {
    return Error{"apply_at_step " + std::to_string(message.apply_at_step) + " is more than " +
                 std::to_string(limits.maxStepsAhead) + " steps ahead"};
  } else {
    request.firstStep = message.apply_at_step;
  }
  if (request.mode == JointCommandMode::Off) return request;

  // Efforts are bounded as a wrench's torque (revolute) or force (prismatic) is.
  const double effortLimit = revolute ? limits.maxTorque : limits.maxForce;
  const std::string effortUnit = revolute ? " N·m" : " N";
  const auto overLimit = [&](const char* field, double value) {
    return Error{std::string(field) + " " + std::to_string(value) + effortUnit + " exceeds the limit of " +
                 std::to_string(effortLimit) + effortUnit + " (limits." +
                 (revolute ? "max_torque" : "max_force") + ")"};
  };
  if (!std::isfinite(message.target)) return Error{"target must be finite"};
  if (spring && message.target < 0.0)
    return Error{"target (the spring's rest length) must be >= 0 m (got " + std::to_string(message.target) + ")"};
  request.target = message.target;
  switch (request.mode) {
    case JointCommandMode::Velocity:
      if (!std::isfinite(message.max_effort) || message.max_effort < 0.0)
        return Error{"max_effort must be finite and >= 0 for MODE_VELOCITY (the motor's largest effort)"};
      if (message.max_effort > effortLimit) return overLimit("max_effort", message.max_effort);
      request.maxEffort = message.max_effort;
      if (request.maxEffort == 0.0) {
        // A motor without effort does nothing, so 0 (the field's default,
        // what `rbctl joint J velocity 0.5` sends) asks for what the joint's
        // actuator can give, within what a client may command.
        const double jointLimit = def.actuatorLimits.effort;
        if (!std::isfinite(jointLimit))
          return Error{"max_effort: give --max-effort (max_effort > 0): joint '" + message.joint +
                       "' has no effort limit to default to, and a motor with max_effort 0 would do nothing"};
        request.maxEffort = std::min(jointLimit, effortLimit);
      }
      break;
    case JointCommandMode::Position:
      if (std::isnan(message.max_effort))
        return Error{"max_effort must be a number (0 or less: uncapped)"};
      if (!std::isfinite(message.stiffness) || message.stiffness < 0.0)
        return Error{"stiffness must be finite and >= 0"};
      if (!std::isfinite(message.damping) || message.damping < 0.0)
        return Error{"damping must be finite and >= 0"};
      if (message.stiffness == 0.0 && message.damping == 0.0)
        return Error{"stiffness and damping are both 0: the drive would do nothing (use MODE_OFF)"};
      request.stiffness = message.stiffness;
      request.damping = message.damping;
      request.maxEffort = message.max_effort > 0.0 ? message.max_effort : std::numeric_limits<double>::infinity();
      break;
    case JointCommandMode::Effort:
      if (std::abs(message.target) > effortLimit) return overLimit("target", std::abs(message.target));
      break;
    case JointCommandMode::Off:
      break;
  }
  return request;
}

Expected<WrenchRequest> wrenchRequestFrom(const rbsim::wrench_t& message, const World& world,
                                          int64_t nextStep, const WrenchLimits& limits) {
  WrenchRequest request;
  request.client = message.client;
  request.seq = message.seq;
  request.body = message.body;

  switch (message.mode) {
    case rbsim::wrench_t::MODE_ONE_STEP:
      request.mode = WrenchMode::OneStep;
      break;
    case rbsim::wrench_t::MODE_DURATION:
      request.mode = WrenchMode::Duration;
      break;
    case rbsim::wrench_t::MODE_PERSISTENT:
      request.mode = WrenchMode::Persistent;
      break;
    case rbsim::wrench_t::MODE_CLEAR:
      request.mode = WrenchMode::Clear;
      break;
    case rbsim::wrench_t::MODE_CLEAR_ALL_CLIENTS:
      request.mode = WrenchMode::ClearAllClients;
      break;
    default:
      return Error{"unknown mode " + std::to_string(message.mode)};
  }
  const auto frame = wrenchFrameFrom(message.frame, "frame");
  if (!frame) return frame.error();
  request.frame = *frame;
  // The centre of mass is a point fixed in the body: its place in the shape
  // frame, the frame body points are given in, once the body is known below.
  const bool atCenterOfMass = message.point_frame == rbsim::wrench_t::POINT_FRAME_CENTER_OF_MASS;
  if (atCenterOfMass) {
    request.pointFrame = WrenchFrame::ShapeFrame;
  } else {
    const auto pointFrame = wrenchFrameFrom(message.point_frame, "point_frame");
    if (!pointFrame) return pointFrame.error();
    request.pointFrame = *pointFrame;
  }

  const bool clearEverything = isClear(request.mode) && message.body.empty();
  const BodyId id = world.findBody(message.body);
  if (!clearEverything && id.isNull()) return Error{unknownBodyReason(world, message.body)};

  if (message.apply_at_step == -1) {
    request.firstStep = nextStep;
  } else if (message.apply_at_step < nextStep) {
    return Error{"apply_at_step " + std::to_string(message.apply_at_step) +
                 " is in the past (next step is " + std::to_string(nextStep) + ")"};
  } else if (message.apply_at_step - nextStep > limits.maxStepsAhead) {
    return Error{"apply_at_step " + std::to_string(message.apply_at_step) + " is more than " +
                 std::to_string(limits.maxStepsAhead) + " steps ahead"};
  } else {
    request.firstStep = message.apply_at_step;
  }

  if (isClear(request.mode)) return request;

  if (!finite3(message.force) || !finite3(message.torque) || (!atCenterOfMass && !finite3(message.point)))
    return Error{"force, torque and point must be finite"};
  request.force = vec3From(message.force);
  request.torque = vec3From(message.torque);
  request.point = vec3From(message.point);
  if (atCenterOfMass) request.point = world.body(id).description().bodyToShapePoint(Vec3::Zero());
  if (request.force.norm() > limits.maxForce)
    return Error{"force magnitude " + std::to_string(request.force.norm()) + " N exceeds the limit of " +
                 std::to_string(limits.maxForce) + " N"};
  if (request.torque.norm() > limits.maxTorque)
    return Error{"torque magnitude " + std::to_string(request.torque.norm()) +
                 " N·m exceeds the limit of " + std::to_string(limits.maxTorque) + " N·m"};
  const BodyView body = world.body(id);
  if (body.isStatic()) return Error{"body '" + message.body + "' is static"};
  if (body.isFrozen())
    return Error{"body '" + message.body + "' is frozen (" +
                 std::string(freezeReasonName(body.freezeReason())) +
                 "); RESET or REMOVE it"};
  const double leverArm = request.pointFrame == WrenchFrame::World
                              ? (request.point - body.position()).norm()
                              : body.description().shapeToBodyPoint(request.point).norm();
  if (leverArm > limits.maxLeverArm)
    return Error{"point is " + std::to_string(leverArm) + " m from the centre of mass (limit " +
                 std::to_string(limits.maxLeverArm) + " m)"};

  if (request.mode == WrenchMode::Duration) {
    if (!std::isfinite(message.duration) || message.duration <= 0.0)
      return Error{"duration must be a positive number of seconds"};
    if (message.duration > limits.maxDuration)
      return Error{"duration " + std::to_string(message.duration) + " s exceeds the limit of " +
                   std::to_string(limits.maxDuration) + " s"};
    const double steps = std::round(message.duration / world.settings().dt);
    request.durationSteps = std::max<int64_t>(1, static_cast<int64_t>(steps));
  }
  return request;
}

}  // namespace rbsim
