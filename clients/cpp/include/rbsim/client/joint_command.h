#pragma once
// A joint command as a C++ value; Client::commandJoint turns it into a
// joint_command_t (lcmtypes/rbsim/joint_command_t.lcm has the full semantics).

#include <cstdint>
#include <string>

namespace rbsim::client {

// The values are those of joint_command_t::MODE_* (checked in client.cpp).
// The modes are exclusive: each turns the joint's other actuators off.
enum class JointMode : int8_t {
  Off = 0,       // motor, drive and effort off
  Velocity = 1,  // the motor drives the rate to `target` with at most `maxEffort`
  Position = 2,  // a spring and damper pull the coordinate to `target`
  Effort = 3,    // a constant force or torque `target` along the axis
};

struct JointCommand {
  std::string joint;  // the joint's name (world_t's joints)
  JointMode mode = JointMode::Off;
  // Velocity: rad/s or m/s; Position: rad or m; Effort: N·m or N.
  double target = 0.0;
  // N·m or N. Velocity: the motor's largest effort, >= 0. Position: the
  // drive's cap, 0 or less: uncapped.
  double maxEffort = 0.0;
  double stiffness = 0.0;    // Position: N·m/rad or N/m, >= 0
  double damping = 0.0;      // Position: N·m·s/rad or N·s/m, >= 0
  int64_t applyAtStep = -1;  // the step from which it acts; -1 = the next step
};

}  // namespace rbsim::client
