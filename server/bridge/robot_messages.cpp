#include "bridge/robot_messages.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <rbsim/joint_command_t.hpp>

#include "config/closest_names.h"
#include "bridge/wire_convert.h"
#include "rbsim/physics/joint_space_dynamics.h"

namespace rbsim {

namespace {

bool hasAxis(const JointDef& def) { return def.type == JointType::Revolute || def.type == JointType::Prismatic; }

// "arm" of "arm/joint1"; empty for a name without a robot prefix.
std::string_view robotOf(std::string_view jointName) {
  const auto slash = jointName.find('/');
  return slash == std::string_view::npos || slash == 0 ? std::string_view() : jointName.substr(0, slash);
}

bool startsWith(std::string_view text, std::string_view prefix) {
  return text.size() > prefix.size() && text.compare(0, prefix.size(), prefix) == 0;
}

template <class Array>
void copy3(Array& out, const Vec3& v) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

template <class Array>
void copyQuaternion(Array& out, const Quaternion& q) {
  out[0] = q.w;
  out[1] = q.x;
  out[2] = q.y;
  out[3] = q.z;
}

// The frame a body was given in (a URDF link's frame): its shape frame.
struct FramePose {
  Vec3 origin;
  Quaternion orientation;
};
FramePose framePose(BodyView body) {
  const BodyDescription& d = body.description();
  return {body.bodyToWorld(d.shapeTranslation),
          body.orientation() * Quaternion::fromRotationMatrix(d.shapeRotation)};
}

// The robot's base: the body its joints hang from, the parent side of a
// joint that is no joint's child. A robot hung from the world has as base
// the child of its first joint to the world.
BodyId robotBase(const World& world, const std::string& prefix, bool& fixed) {
  std::vector<BodyId> parents, children;  // in joint order: the first base found is the same every time
  BodyId childOfWorld;
  bool weldedToWorld = false;
  for (int i = 0; i < world.jointCount(); ++i) {
    const JointDef& def = world.jointDefinitionAt(i);
    if (!startsWith(def.name, prefix)) continue;
    if (!def.bodyB.isNull()) children.push_back(def.bodyB);
    if (!def.bodyA.isNull()) parents.push_back(def.bodyA);
    if (def.bodyA.isNull() && childOfWorld.isNull()) {
      childOfWorld = def.bodyB;
      weldedToWorld = def.type == JointType::Fixed;
    }
  }
  for (const BodyId id : parents)
    if (std::find(children.begin(), children.end(), id) == children.end() && world.isValid(id)) {
      fixed = world.body(id).isStatic();
      return id;
    }
  fixed = weldedToWorld;
  return childOfWorld;
}

}  // namespace

std::vector<std::string> robotNames(const World& world) {
  std::vector<std::string> names;
  for (int i = 0; i < world.jointCount(); ++i) {
    const JointDef& def = world.jointDefinitionAt(i);
    if (!hasAxis(def)) continue;
    const std::string_view robot = robotOf(def.name);
    if (!robot.empty() && std::find(names.begin(), names.end(), robot) == names.end()) names.emplace_back(robot);
  }
  return names;
}

std::vector<JointId> robotJoints(const World& world, const std::string& robot) {
  std::vector<JointId> joints;
  const std::string prefix = robot + "/";
  for (int i = 0; i < world.jointCount(); ++i) {
    const JointDef& def = world.jointDefinitionAt(i);
    if (hasAxis(def) && startsWith(def.name, prefix)) joints.push_back(world.jointIdAt(i));
  }
  return joints;
}

Expected<RobotCommandRequest> robotCommandRequestFrom(const rbsim::robot_command_t& message, const World& world,
                                                      int64_t nextStep, const WrenchLimits& limits) {
  const std::vector<JointId> joints = robotJoints(world, message.robot);
  if (joints.empty())
    return Error{"robot: unknown robot '" + message.robot + "'" + didYouMean(message.robot, robotNames(world))};
  const auto count = static_cast<std::size_t>(joints.size());
  const auto entries = static_cast<std::size_t>(message.num_joints);
  if (message.num_names == 0 && entries != 0 && entries != count)
    return Error{"num_joints: " + std::to_string(message.num_joints) + " entries in joint order, but robot '" +
                 message.robot + "' has " + std::to_string(count) +
                 " joints (give all of them, or name the ones commanded in joint_names)"};
  if (message.num_names != 0 && message.num_names != message.num_joints)
    return Error{"num_names: " + std::to_string(message.num_names) + " names for " +
                 std::to_string(message.num_joints) + " entries (0, or one name per entry)"};

  RobotCommandRequest out;
  // The step, checked once for all entries (as a joint command checks it).
  if (message.apply_at_step == -1) {
    out.firstStep = nextStep;
  } else if (message.apply_at_step < nextStep) {
    return Error{"apply_at_step " + std::to_string(message.apply_at_step) + " is in the past (next step is " +
                 std::to_string(nextStep) + ")"};
  } else if (message.apply_at_step - nextStep > limits.maxStepsAhead) {
    return Error{"apply_at_step " + std::to_string(message.apply_at_step) + " is more than " +
                 std::to_string(limits.maxStepsAhead) + " steps ahead"};
  } else {
    out.firstStep = message.apply_at_step;
  }
  if (!std::isfinite(message.state_rate) || (message.state_rate < 0.0 && message.state_rate != -1.0))
    return Error{"state_rate must be > 0 Hz, 0 (leave it) or -1 (the world state's rate)"};
  out.stateRate = message.state_rate;
  if (message.state_dynamics < -1 || message.state_dynamics > 1)
    return Error{"state_dynamics must be 1 (on), 0 (off) or -1 (leave it)"};
  out.stateDynamics = message.state_dynamics;
  if (message.steps < 0) return Error{"steps must be >= 0"};
  out.steps = message.steps;

  const std::string prefix = message.robot + "/";
  std::vector<std::string> jointNames;
  for (const JointId id : joints) jointNames.push_back(world.jointDefinition(id).name);
  std::set<std::string> seen;
  for (std::size_t i = 0; i < entries; ++i) {
    std::string name;
    if (message.num_names == 0) {
      name = jointNames[i];
    } else {
      const std::string& given = message.joint_names[i];
      name = startsWith(given, prefix) ? given : prefix + given;
      if (std::find(jointNames.begin(), jointNames.end(), name) == jointNames.end())
        return Error{"joint_names[" + std::to_string(i) + "]: robot '" + message.robot + "' has no joint '" + given +
                     "'" + didYouMean(name, jointNames)};
      if (!seen.insert(name).second)
        return Error{"joint_names[" + std::to_string(i) + "]: joint '" + name + "' is given twice"};
    }
    const std::string where = "entry " + std::to_string(i) + " (" + name + "): ";
    const int8_t mode = message.mode[i];
    if (mode == rbsim::robot_command_t::MODE_KEEP) continue;
    if (mode < rbsim::robot_command_t::MODE_OFF || mode > rbsim::robot_command_t::MODE_EFFORT)
      return Error{where + "mode: unknown mode " + std::to_string(mode) +
                   " (KEEP -1, OFF 0, VELOCITY 1, POSITION 2, EFFORT 3)"};
    const JointDef& def = world.jointDefinition(world.findJoint(name));
    if (def.mimic.enabled)
      return Error{where + "follows joint '" + def.mimic.leader +
                   "' (mimic): give it MODE_KEEP and command its leader, which moves both"};
    // Each entry as the joint command of its mode, checked by the same rules.
    rbsim::joint_command_t single;
    single.client = message.client;
    single.seq = message.seq;
    single.joint = name;
    single.mode = mode;
    single.target = mode == rbsim::robot_command_t::MODE_POSITION   ? message.position[i]
                    : mode == rbsim::robot_command_t::MODE_VELOCITY ? message.velocity[i]
                                                                    : message.effort[i];
    single.max_effort = message.max_effort[i];
    single.stiffness = message.stiffness[i];
    single.damping = message.damping[i];
    single.apply_at_step = out.firstStep;
    auto request = jointCommandRequestFrom(single, world, nextStep, limits);
    if (!request) return Error{where + request.error().message};
    if (mode == rbsim::robot_command_t::MODE_POSITION) {
      if (!std::isfinite(message.velocity[i])) return Error{where + "velocity must be finite"};
      request->targetRate = message.velocity[i];
    }
    if (mode == rbsim::robot_command_t::MODE_POSITION || mode == rbsim::robot_command_t::MODE_VELOCITY) {
      const double feedForward = message.effort[i];
      const double effortLimit = def.type == JointType::Revolute ? limits.maxTorque : limits.maxForce;
      if (!std::isfinite(feedForward)) return Error{where + "effort (the feed-forward) must be finite"};
      if (std::abs(feedForward) > effortLimit)
        return Error{where + "effort " + std::to_string(feedForward) + " exceeds the limit of " +
                     std::to_string(effortLimit) +
                     (def.type == JointType::Revolute ? " N·m (limits.max_torque)" : " N (limits.max_force)")};
      request->feedForward = feedForward;
    }
    out.joints.push_back(std::move(*request));
  }
  return out;
}

rbsim::robot_state_t robotStateMessage(const World& world, const std::string& robot, bool dynamics, int64_t utime,
                                       int64_t revision) {
  rbsim::robot_state_t out;
  out.utime = utime;
  out.step = world.stepCount();
  out.sim_time = world.time();
  out.world_revision = revision;
  out.robot = robot;
  const std::vector<JointId> joints = robotJoints(world, robot);
  out.num_joints = static_cast<int32_t>(joints.size());
  for (const JointId id : joints) {
    const JointState state = world.jointState(id);
    const JointDef& def = world.jointDefinition(id);
    int32_t leader = -1;
    if (def.mimic.enabled)
      for (std::size_t j = 0; j < joints.size(); ++j)
        if (world.jointDefinition(joints[j]).name == def.mimic.leader) leader = static_cast<int32_t>(j);
    out.joint_names.push_back(def.name);
    out.leader.push_back(leader);
    out.position.push_back(state.position);
    out.velocity.push_back(state.rate);
    out.effort.push_back(state.axisEffort);
  }

  const std::string prefix = robot + "/";
  bool fixed = false;
  const BodyId base = robotBase(world, prefix, fixed);
  copyQuaternion(out.base_orientation, Quaternion::identity());
  copy3(out.base_position, Vec3::Zero());
  copy3(out.base_linear_velocity, Vec3::Zero());
  copy3(out.base_angular_velocity, Vec3::Zero());
  if (!base.isNull() && world.isValid(base)) {
    const BodyView body = world.body(base);
    const FramePose pose = framePose(body);
    out.base = body.name();
    copy3(out.base_position, pose.origin);
    copyQuaternion(out.base_orientation, pose.orientation);
    copy3(out.base_linear_velocity, body.velocityAtPoint(pose.origin));
    copy3(out.base_angular_velocity, body.angularVelocity());
  }
  out.base_fixed = fixed;

  out.num_dofs = 0;
  out.num_links = 0;
  if (!dynamics) return out;
  const auto model = JointSpaceDynamics::ofRobot(world, prefix);
  if (!model) {
    out.dynamics_note = model.error().message;
    return out;
  }
  const int n = model->dofCount();
  out.num_dofs = n;
  const Eigen::MatrixXd mass = model->massMatrix();
  const Eigen::VectorXd bias = model->biasForces();
  const Eigen::VectorXd gravity = model->gravityTorques();
  out.mass_matrix.assign(static_cast<std::size_t>(n), std::vector<double>(static_cast<std::size_t>(n)));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) out.mass_matrix[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] = mass(r, c);
  out.bias.assign(bias.data(), bias.data() + n);
  out.gravity.assign(gravity.data(), gravity.data() + n);
  for (const std::string& name : model->bodyNames()) {
    const BodyId id = world.findBody(name);
    if (id.isNull()) continue;
    const FramePose pose = framePose(world.body(id));
    const auto jacobian = model->jacobian(name, pose.origin);
    if (!jacobian) continue;
    out.link_names.push_back(name);
    out.link_position.push_back({pose.origin.x(), pose.origin.y(), pose.origin.z()});
    out.link_orientation.push_back({pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z});
    std::vector<std::vector<double>> rows(6, std::vector<double>(static_cast<std::size_t>(n)));
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < n; ++c) rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] = (*jacobian)(r, c);
    out.link_jacobian.push_back(std::move(rows));
  }
  out.num_links = static_cast<int32_t>(out.link_names.size());
  return out;
}

}  // namespace rbsim
