#include "session/joint_command_scheduler.h"

#include <algorithm>

namespace rbsim {

JointActuation actuationOf(const JointCommandRequest& request) {
  JointActuation out;
  switch (request.mode) {
    case JointCommandMode::Off:
      break;
    case JointCommandMode::Velocity:
      out.motor.enabled = true;
      out.motor.targetRate = request.target;
      out.motor.maxEffort = request.maxEffort;
      out.effort = request.feedForward;
      break;
    case JointCommandMode::Position:
      out.drive.enabled = true;
      out.drive.target = request.target;
      out.drive.stiffness = request.stiffness;
      out.drive.damping = request.damping;
      out.drive.maxEffort = request.maxEffort;
      out.drive.targetRate = request.targetRate;
      out.effort = request.feedForward;
      break;
    case JointCommandMode::Effort:
      out.effort = request.target;
      break;
  }
  return out;
}

Expected<bool> applyJointCommand(World& world, JointId id, const JointCommandRequest& request) {
  JointActuation actuation = actuationOf(request);
  // A drive's gravity compensation is the joint's setting (the world
  // file's), not the command's: a new target keeps it.
  if (world.isValid(id)) actuation.drive.gravityCompensation = world.jointDefinition(id).drive.gravityCompensation;
  // Turn off before turning on: the World lets at most one of motor and
  // drive be enabled, and enabling one turns the other off anyway.
  if (!actuation.motor.enabled) {
    if (auto set = world.setJointMotor(id, actuation.motor); !set) return set;
    if (auto set = world.setJointDrive(id, actuation.drive); !set) return set;
  } else {
    if (auto set = world.setJointDrive(id, actuation.drive); !set) return set;
    if (auto set = world.setJointMotor(id, actuation.motor); !set) return set;
  }
  return world.setJointEffort(id, actuation.effort);
}

void JointCommandScheduler::applyForStep(World& world, int64_t step) {
  if (m_pending.empty()) return;
  // Stable: commands due together keep their acceptance order.
  const auto due = std::stable_partition(m_pending.begin(), m_pending.end(),
                                         [&](const JointCommandRequest& r) { return r.firstStep > step; });
  for (auto it = due; it != m_pending.end(); ++it) {
    const JointId id = world.findJoint(it->joint);
    // Validated when accepted; what can fail now is a joint removed since.
    if (!id.isNull()) (void)applyJointCommand(world, id, *it);
  }
  m_pending.erase(due, m_pending.end());
}

void JointCommandScheduler::removeJoint(const std::string& name) {
  m_pending.erase(std::remove_if(m_pending.begin(), m_pending.end(),
                                 [&](const JointCommandRequest& request) { return request.joint == name; }),
                  m_pending.end());
}

}  // namespace rbsim
