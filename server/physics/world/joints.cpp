// Joints in the world: made, changed and removed between steps, and what a
// joint reports (its state, its definition). The joint step itself is
// joint_step.cpp.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "physics/body/body.h"
#include "physics/common/step_part.h"
#include "physics/joint/joint_constraint.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

namespace rbsim {

namespace {

void wakeJointBodies(WorldData& world, const JointDef& def) {
  for (const BodyId body : {def.bodyA, def.bodyB})
    if (!body.isNull() && invalidIdReason(world, body).empty()) bodyRef(world, body).wake();
  world.maybeAsleep = true;
}

// What a follower's commands are refused with.
std::string followerRefusal(const JointConstraint& joint) {
  return "joint '" + joint.def.name + "' follows joint '" + joint.def.mimic.leader +
         "' (mimic): command its leader, which moves both";
}

}  // namespace

JointSidePose jointSidePose(const Body& body) {
  return {body.position(), body.orientation(), body.rotation()};
}

Expected<JointId> createJoint(WorldData& world, const JointDef& def) {
  const std::string where = "joint '" + def.name + "'";
  if (def.name.empty()) return Error{"a joint needs a name"};
  if (!findJointByName(world, def.name).isNull()) return Error{where + ": the name is taken by another joint"};
  if (world.settings.contact.model == ContactModel::Penalty)
    return Error{where + ": joints need the impulse contact model (contact.model: impulse)"};
  JointSidePose poses[2];
  bool moves[2] = {false, false};
  const BodyId ids[2] = {def.bodyA, def.bodyB};
  for (int side = 0; side < 2; ++side) {
    if (ids[side].isNull()) continue;  // the world
    if (const std::string why = invalidIdReason(world, ids[side]); !why.empty())
      return Error{where + ": body_" + (side == 0 ? "a" : "b") + ": " + why};
    const Body& body = world.bodies[denseIndexOf(world, ids[side])];
    poses[side] = jointSidePose(body);
    moves[side] = !body.isStatic();
  }
  if (!ids[0].isNull() && ids[0] == ids[1]) return Error{where + ": joins a body to itself"};
  if (!moves[0] && !moves[1]) return Error{where + ": neither side moves (both are the world or static)"};
  Expected<JointConstraint> made = makeJointConstraint(def, poses[0], poses[1]);
  if (!made.ok()) return made.error();
  if (def.mimic.enabled) {
    if (auto leader = resolveMimicLeader(world, made.value()); !leader) return Error{where + ": " + leader.error().message};
    // The coupling's error as created: the follower reads def.position.
    const JointConstraint& leader = world.joints[static_cast<std::size_t>(
        world.jointSlots[static_cast<std::size_t>(made.value().mimicLeader.index - 1)].denseIndex)];
    const double leaderPosition = jointStateAt(world, static_cast<int>(&leader - world.joints.data())).position;
    made.value().mimicError = def.position - def.mimic.multiplier * leaderPosition - def.mimic.offset;
  }

  int32_t slot;
  if (!world.freeJointSlots.empty()) {
    const auto lowest = std::min_element(world.freeJointSlots.begin(), world.freeJointSlots.end());
    slot = *lowest;
    world.freeJointSlots.erase(lowest);
  } else {
    slot = static_cast<int32_t>(world.jointSlots.size());
    world.jointSlots.push_back({});
  }
  world.jointSlots[static_cast<std::size_t>(slot)].denseIndex = static_cast<int32_t>(world.joints.size());
  const JointId id{slot + 1, world.jointSlots[static_cast<std::size_t>(slot)].generation, world.tag};
  world.joints.push_back(std::move(made.value()));
  world.jointIds.push_back(id);
  for (const BodyId body : ids)
    if (!body.isNull()) bodyRef(world, body).wake();
  world.maybeAsleep = true;
  return id;
}

Expected<bool> removeJoint(WorldData& world, JointId id) {
  if (const std::string why = invalidJointReason(world, id); !why.empty()) return Error{"cannot remove: " + why};
  IdSlot& slot = world.jointSlots[static_cast<std::size_t>(id.index - 1)];
  const auto dense = static_cast<std::size_t>(slot.denseIndex);
  for (const BodyId body : {world.joints[dense].def.bodyA, world.joints[dense].def.bodyB})
    if (!body.isNull() && invalidIdReason(world, body).empty()) bodyRef(world, body).wake();
  // Its followers are free from now on.
  for (JointConstraint& other : world.joints)
    if (other.def.mimic.enabled && other.mimicLeader == id) {
      other.def.mimic.enabled = false;
      other.mimicLeader = JointId{};
    }
  world.joints.erase(world.joints.begin() + static_cast<std::ptrdiff_t>(dense));
  world.jointIds.erase(world.jointIds.begin() + static_cast<std::ptrdiff_t>(dense));
  for (std::size_t i = dense; i < world.jointIds.size(); ++i)
    world.jointSlots[static_cast<std::size_t>(world.jointIds[i].index - 1)].denseIndex = static_cast<int32_t>(i);
  slot.denseIndex = -1;
  ++slot.generation;
  world.freeJointSlots.push_back(id.index - 1);
  return true;
}

Expected<bool> setJointMotor(WorldData& world, JointId id, const JointMotor& motor) {
  if (const std::string why = invalidJointReason(world, id); !why.empty()) return Error{"cannot set the motor: " + why};
  JointConstraint& joint = world.joints[static_cast<std::size_t>(world.jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex)];
  if (motor.enabled && !joint.hasAxis()) return Error{"joint '" + joint.def.name + "': only revolute and prismatic joints take a motor"};
  if (motor.enabled && joint.def.mimic.enabled) return Error{followerRefusal(joint)};
  if (motor.enabled && (!std::isfinite(motor.targetRate) || !std::isfinite(motor.maxEffort) || motor.maxEffort < 0.0))
    return Error{"joint '" + joint.def.name + "': the motor needs a finite target rate and a finite, non-negative max effort"};
  joint.def.motor = motor;
  if (motor.enabled) joint.def.drive.enabled = false;
  wakeJointBodies(world, joint.def);
  return true;
}

Expected<bool> setJointDrive(WorldData& world, JointId id, const JointDrive& drive) {
  if (const std::string why = invalidJointReason(world, id); !why.empty()) return Error{"cannot set the drive: " + why};
  JointConstraint& joint = world.joints[static_cast<std::size_t>(world.jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex)];
  // A distance joint made with a spring takes a new rest length (the
  // drive's target) and gains; its drive is what it is, so it stays on.
  if (drive.enabled && joint.def.mimic.enabled) return Error{followerRefusal(joint)};
  const bool spring = joint.hasSpring();
  if (spring && !drive.enabled)
    return Error{"joint '" + joint.def.name + "': a spring cannot be turned off (its drive is the spring)"};
  if (drive.enabled && !joint.hasAxis() && !spring)
    return Error{"joint '" + joint.def.name +
                 "': only revolute and prismatic joints take a drive (and distance joints made with a spring)"};
  if (drive.enabled) {
    if (const std::string why = invalidDriveReason(drive); !why.empty()) return Error{"joint '" + joint.def.name + "': " + why};
  }
  if (spring && drive.target < 0.0)
    return Error{"joint '" + joint.def.name + "': the spring's rest length must not be negative (got " +
                 std::to_string(drive.target) + ")"};
  joint.def.drive = drive;
  if (spring) joint.length = joint.def.length = drive.target;
  if (drive.enabled) joint.def.motor.enabled = false;
  wakeJointBodies(world, joint.def);
  return true;
}

Expected<bool> setJointEffort(WorldData& world, JointId id, double effort) {
  if (const std::string why = invalidJointReason(world, id); !why.empty()) return Error{"cannot set the effort: " + why};
  JointConstraint& joint = world.joints[static_cast<std::size_t>(world.jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex)];
  if (!joint.hasAxis() && effort != 0.0) return Error{"joint '" + joint.def.name + "': only revolute and prismatic joints take an effort"};
  if (!std::isfinite(effort)) return Error{"joint '" + joint.def.name + "': the effort is not finite"};
  if (effort != 0.0 && joint.def.mimic.enabled) return Error{followerRefusal(joint)};
  joint.def.effort = effort;
  wakeJointBodies(world, joint.def);
  return true;
}


std::vector<std::string> removeJointsOf(WorldData& world, BodyId body) {
  std::vector<std::string> removed;
  for (std::size_t i = 0; i < world.joints.size();) {
    const JointDef& def = world.joints[i].def;
    if (def.bodyA != body && def.bodyB != body) {
      ++i;
      continue;
    }
    removed.push_back(def.name);
    (void)removeJoint(world, world.jointIds[i]);
  }
  return removed;
}

Expected<bool> resolveMimicLeader(const WorldData& world, JointConstraint& follower) {
  const JointMimic& mimic = follower.def.mimic;
  const JointId leader = findJointByName(world, mimic.leader);
  if (leader.isNull())
    return Error{"mimic: no joint '" + mimic.leader + "' to follow (a leader is created before its followers)"};
  const JointConstraint& joint =
      world.joints[static_cast<std::size_t>(world.jointSlots[static_cast<std::size_t>(leader.index - 1)].denseIndex)];
  if (!joint.hasAxis())
    return Error{"mimic: joint '" + mimic.leader + "' is " + jointTypeName(joint.def.type) +
                 ": only a revolute or prismatic joint leads"};
  follower.mimicLeader = leader;
  return true;
}

void computeGravityFeedForward(WorldData& world) {
  const StepPartScope inJoints(StepPart::Joints);
  // Most worlds have no compensated drive: nothing to walk.
  bool any = false;
  for (JointConstraint& joint : world.joints) {
    joint.gravityFeedForward = 0.0;
    any = any || (joint.def.drive.enabled && joint.def.drive.gravityCompensation && joint.hasAxis());
  }
  if (!any) return;
  const std::size_t n = world.bodies.size();
  // The joints at each body (indices), to walk the joint graph.
  std::vector<std::vector<std::size_t>> jointsAt(n);
  for (std::size_t j = 0; j < world.joints.size(); ++j) {
    const JointDef& def = world.joints[j].def;
    if (!jointIsEnforced(world, world.joints[j])) continue;
    for (const BodyId id : {def.bodyA, def.bodyB})
      if (!id.isNull()) jointsAt[denseIndexOf(world, id)].push_back(j);
  }
  const Vec3 gravity = world.settings.gravity;
  std::vector<char> seen(n, 0);
  std::vector<std::size_t> pending, reached;
  for (std::size_t j = 0; j < world.joints.size(); ++j) {
    JointConstraint& joint = world.joints[j];
    const JointDef& def = joint.def;
    if (!(def.drive.enabled && def.drive.gravityCompensation && joint.hasAxis()) || def.bodyB.isNull() ||
        !jointIsEnforced(world, joint))
      continue;
    // What B's side carries: the bodies reached from B through the other
    // joints, stopping at static bodies (and the world); reaching A is a
    // loop, whose load the joint does not carry alone.
    std::fill(seen.begin(), seen.end(), 0);
    const std::size_t start = denseIndexOf(world, def.bodyB);
    const std::size_t sideA = def.bodyA.isNull() ? n : denseIndexOf(world, def.bodyA);
    pending.assign(1, start);
    reached.clear();
    seen[start] = 1;
    bool loop = false;
    while (!pending.empty() && !loop) {
      const std::size_t b = pending.back();
      pending.pop_back();
      reached.push_back(b);
      for (const std::size_t k : jointsAt[b]) {
        if (k == j) continue;
        const JointDef& other = world.joints[k].def;
        for (const BodyId id : {other.bodyA, other.bodyB}) {
          if (id.isNull()) continue;
          const std::size_t next = denseIndexOf(world, id);
          if (next == sideA) loop = true;
          if (seen[next] || world.bodies[next].isStatic()) continue;
          seen[next] = 1;
          pending.push_back(next);
        }
      }
    }
    if (loop) continue;
    // Gravity's torque about the axis (or force along it) on what it
    // carries; the drive gives its opposite.
    const JointSidePose a = def.bodyA.isNull() ? JointSidePose{} : jointSidePose(world.bodies[sideA]);
    const Vec3 axis = a.rotation * joint.axisA;
    const Vec3 anchor = a.position + a.rotation * joint.anchorA;
    double load = 0.0;
    for (const std::size_t b : reached) {
      const Body& body = world.bodies[b];
      const Vec3 weight = body.mass() * gravity;
      load += def.type == JointType::Prismatic ? axis.dot(weight) : axis.dot((body.position() - anchor).cross(weight));
    }
    joint.gravityFeedForward = -load;
  }
}

int enforcedLeaderOf(const WorldData& world, const JointConstraint& follower) {
  if (!follower.def.mimic.enabled || !invalidJointReason(world, follower.mimicLeader).empty()) return -1;
  const int dense = world.jointSlots[static_cast<std::size_t>(follower.mimicLeader.index - 1)].denseIndex;
  return jointIsEnforced(world, world.joints[static_cast<std::size_t>(dense)]) ? dense : -1;
}

JointId findJointByName(const WorldData& world, std::string_view name) {
  for (std::size_t i = 0; i < world.joints.size(); ++i)
    if (world.joints[i].def.name == name) return world.jointIds[i];
  return {};
}

std::string invalidJointReason(const WorldData& world, JointId id) {
  // As for bodies, the message is made only for an id that fails: a robot
  // client's joint commands and state reads look joints up every cycle.
  const auto named = [&] {
    return "joint id (index " + std::to_string(id.index) + ", generation " + std::to_string(id.generation) +
           ", world " + std::to_string(id.world) + ")";
  };
  if (id.isNull()) return "a null joint id";
  if (id.world != world.tag) return named() + " is of another world";
  if (id.index < 1 || static_cast<std::size_t>(id.index) > world.jointSlots.size())
    return named() + " names no slot of this world";
  const IdSlot& slot = world.jointSlots[static_cast<std::size_t>(id.index - 1)];
  if (slot.denseIndex < 0 || slot.generation != id.generation) return named() + " is stale: its joint was removed";
  return {};
}

bool jointIsEnforced(const WorldData& world, const JointConstraint& joint) {
  for (const BodyId body : {joint.def.bodyA, joint.def.bodyB})
    if (!body.isNull() && world.bodies[denseIndexOf(world, body)].isFrozen()) return false;
  return true;
}

JointState jointStateAt(const WorldData& world, int denseIndex) {
  const JointConstraint& joint = world.joints[static_cast<std::size_t>(denseIndex)];
  JointState out;
  out.name = joint.def.name;
  out.type = joint.def.type;
  out.bodyA = joint.def.bodyA;
  out.bodyB = joint.def.bodyB;
  JointSidePose poses[2];
  Vec3 linear[2] = {Vec3::Zero(), Vec3::Zero()};
  Vec3 angular[2] = {Vec3::Zero(), Vec3::Zero()};
  const BodyId ids[2] = {joint.def.bodyA, joint.def.bodyB};
  for (int side = 0; side < 2; ++side) {
    if (ids[side].isNull()) continue;
    const Body& body = world.bodies[denseIndexOf(world, ids[side])];
    poses[side] = jointSidePose(body);
    linear[side] = body.linearVelocity();
    angular[side] = body.angularVelocity();
  }
  out.position = joint.coordinate(poses[0], poses[1]);
  out.rate = joint.coordinateRate(poses[0], poses[1], linear[0], angular[0], linear[1], angular[1]);
  out.anchorA = poses[0].position + poses[0].rotation * joint.anchorA;
  out.anchorB = poses[1].position + poses[1].rotation * joint.anchorB;
  out.axis = poses[0].rotation * joint.axisA;
  out.rotation = (poses[0].orientation.conjugate() * poses[1].orientation * joint.restRelative.conjugate()).normalized();
  double errors[kMaxJointRows];
  joint.errors(poses[0], poses[1], joint.basisAt(poses[0]), errors);
  for (int r = 0; r < joint.rowCount(); ++r) out.error = std::max(out.error, std::abs(errors[r]));
  if (joint.hasLimit()) {  // a bound passed counts as an error too
    out.error = std::max({out.error, joint.limitLower() - out.position, out.position - joint.limitUpper()});
  }
  out.force = joint.lastForce;
  out.torque = joint.lastTorque;
  out.axisEffort = joint.lastAxisEffort;
  out.atLimit = joint.lastAtLimit;
  out.active = jointIsEnforced(world, joint);
  return out;
}

}  // namespace rbsim
