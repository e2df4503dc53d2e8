#pragma once
// What the checkpoint tests share: a command_t that names a checkpoint file
// (SAVE_CHECKPOINT, RESET to a file), which the client library does not send
// with an arbitrary path, and the bit-for-bit comparison of two states.

#include <cstdint>
#include <cstring>
#include <string>

#include <rbsim/command_t.hpp>
#include <rbsim/world_state_t.hpp>

#include "e2e_paths.h"
#include "rbsim/client/client.h"

namespace rbsim::e2e {

// A command_t with any path, sent as `via` (its acks come back to it).
inline client::Request sendPathCommand(client::Client& via, int8_t command, const std::string& path) {
  static int64_t seq = 1000000;
  rbsim::command_t message{};
  message.client = via.clientId();
  message.seq = ++seq;
  message.command = command;
  message.path = path;
  lcm::LCM lcm(kUrl);
  lcm.publish(via.channel("COMMAND"), &message);
  return client::Request{message.seq, client::AckKind::Command, true};
}

// The same bodies with the same bits of pose and velocity.
inline bool sameBodies(const rbsim::world_state_t& a, const rbsim::world_state_t& b) {
  if (a.bodies.size() != b.bodies.size()) return false;
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const auto& x = a.bodies[i];
    const auto& y = b.bodies[i];
    if (x.name != y.name || std::memcmp(x.position, y.position, sizeof x.position) != 0 ||
        std::memcmp(x.orientation, y.orientation, sizeof x.orientation) != 0 ||
        std::memcmp(x.linear_velocity, y.linear_velocity, sizeof x.linear_velocity) != 0 ||
        std::memcmp(x.angular_velocity, y.angular_velocity, sizeof x.angular_velocity) != 0)
      return false;
  }
  return true;
}

}  // namespace rbsim::e2e
