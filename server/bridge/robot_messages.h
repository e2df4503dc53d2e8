#pragma once
// Robots on the wire: robot_command_t in, robot_state_t out.
//
// A robot is the set of joints named "<robot>/…" (a URDF robot of the world
// file or of a SPAWN names its joints so, urdf_robot.h). Its joints, in the
// order both messages use, are its revolute and prismatic joints in the
// world's creation order; its bodies are those named "<robot>/…". Nothing
// is kept about a robot but how its state is published (RobotPublishing):
// which robots there are follows from the world, so RESET, REMOVE, SPAWN
// and checkpoints need no bookkeeping.

#include <cstdint>
#include <string>
#include <vector>

#include <rbsim/robot_command_t.hpp>
#include <rbsim/robot_state_t.hpp>

#include "config/server_settings.h"
#include "rbsim/physics/expected.h"
#include "rbsim/physics/world.h"
#include "session/joint_command_scheduler.h"

namespace rbsim {

// The robots of the world (the distinct "<robot>/" prefixes of revolute and
// prismatic joints), in the order of their first joint.
std::vector<std::string> robotNames(const World& world);

// Robot `robot`'s joints in command and state order (empty: no such robot).
std::vector<JointId> robotJoints(const World& world, const std::string& robot);

// What one robot_command_t asks for, checked against the world and the
// limits. Every joint request shares one firstStep, so the scheduler sets
// them all before the same step, in entry order.
struct RobotCommandRequest {
  std::vector<JointCommandRequest> joints;  // MODE_KEEP entries left out
  int64_t firstStep = 0;
  // robot_command_t.state_rate: 0 leaves the rate, < 0 back to the world
  // state's, > 0 Hz.
  double stateRate = 0.0;
  int stateDynamics = -1;  // -1 leaves it, 0 off, 1 on
  int32_t steps = 0;       // to take after it (the server must be paused)
};

// Errors name the field and, for an entry, its joint: the whole command is
// refused for one bad entry.
Expected<RobotCommandRequest> robotCommandRequestFrom(const rbsim::robot_command_t& message, const World& world,
                                                      int64_t nextStep, const WrenchLimits& limits);

// The robot's state now; with `dynamics`, its joint-space dynamics too
// (JointSpaceDynamics), or num_dofs 0 and dynamics_note saying why not.
rbsim::robot_state_t robotStateMessage(const World& world, const std::string& robot, bool dynamics, int64_t utime,
                                       int64_t revision);

}  // namespace rbsim
