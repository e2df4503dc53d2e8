#pragma once
// How a robot's state goes out (robot_state_t): how often, and whether with
// its dynamics. Presentation, not physics, as visual.h is: the server keeps
// it by robot name beside the world, from the world file's robots (and a
// SPAWN's), changed by robot_command_t; RESET and checkpoints leave it.

#include <functional>
#include <map>
#include <string>

namespace rbsim {

struct RobotPublishing {
  double stateRate = 0.0;  // Hz of simulated time, > 0; 0: with every world state (server.state_rate)
  bool dynamics = false;   // M, h, g, link poses and Jacobians in robot_state_t
};

using RobotPublishingMap = std::map<std::string, RobotPublishing, std::less<>>;

}  // namespace rbsim
