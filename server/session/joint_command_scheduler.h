#pragma once
// Joint commands accepted from clients (joint_command_t), kept until the step
// they were scheduled for and then set on the joint through the World's
// setters, right before that step is taken.
//
// Steps are numbered as on the wire (see wrench_scheduler.h). A command for
// step k sets the joint's motor, drive and effort before step k, and they
// stay so until the next command on that joint: unlike wrenches, nothing is
// retired. Commands due at the same step are applied in acceptance order,
// so the result depends only on the sequence of accepted requests.

#include <cstdint>
#include <string>
#include <vector>

#include "rbsim/physics/joint_definition.h"
#include "rbsim/physics/types.h"
#include "rbsim/physics/world.h"

namespace rbsim {

// The modes are exclusive: each sets all three actuators (joint_command_t).
enum class JointCommandMode { Off, Velocity, Position, Effort };

struct JointCommandRequest {
  std::string client;
  int64_t seq = 0;
  std::string joint;
  JointCommandMode mode = JointCommandMode::Off;
  double target = 0.0;     // rad/s or m/s; rad or m; N·m or N (by mode)
  double maxEffort = 0.0;  // N·m or N; Position: infinity for uncapped
  double stiffness = 0.0;  // Position: N·m/rad or N/m
  double damping = 0.0;    // Position: N·m·s/rad or N·s/m
  // Position: the rate the damping pulls toward, rad/s or m/s (a
  // trajectory's velocity: robot_command_t); 0 holds the joint still.
  double targetRate = 0.0;
  // Position and Velocity: an effort added to the drive's or the motor's
  // (a controller's feed-forward: robot_command_t), N·m or N.
  double feedForward = 0.0;
  int64_t firstStep = 0;   // the step before which it is set
};

// The motor, drive and effort a request sets (the two it does not use off).
struct JointActuation {
  JointMotor motor;
  JointDrive drive;
  double effort = 0.0;
};
JointActuation actuationOf(const JointCommandRequest& request);

// Sets the request's actuation on joint `id` now (the World's setters wake
// its bodies). Errors are the World's, for a joint that cannot take it.
Expected<bool> applyJointCommand(World& world, JointId id, const JointCommandRequest& request);

class JointCommandScheduler {
 public:
  // The request must already be validated (joint exists and has an axis,
  // finite values, firstStep not in the past).
  void add(const JointCommandRequest& request) { m_pending.push_back(request); }

  // Sets the commands due at `step` (= world.stepCount() + 1): call right
  // before world.step(). A command whose joint no longer exists (its body
  // was removed) is dropped.
  void applyForStep(World& world, int64_t step);

  // Drops the commands waiting for joint `name` (REMOVE took it away), so
  // that a later joint of the same name does not receive them.
  void removeJoint(const std::string& name);
  void clearAll() { m_pending.clear(); }
  int pendingCount() const { return static_cast<int>(m_pending.size()); }
  const std::vector<JointCommandRequest>& pending() const { return m_pending; }

 private:
  std::vector<JointCommandRequest> m_pending;  // not yet due, acceptance order
};

}  // namespace rbsim
