#pragma once
// Encoded wrench_t and command_t messages for driving a CommandHandler
// without LCM, as the server would receive them.

#include <cstdint>
#include <string>
#include <vector>

#include <rbsim/command_t.hpp>
#include <rbsim/wrench_t.hpp>

#include "bridge/command_handler.h"

namespace rbsim::test {

template <class Message>
std::vector<uint8_t> encoded(const Message& message) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

inline rbsim::wrench_t wrenchMessage(const std::string& client, int64_t seq, const std::string& body,
                                     double fx = 1.0) {
  rbsim::wrench_t w{};
  w.client = client;
  w.seq = seq;
  w.body = body;
  w.frame = rbsim::wrench_t::FRAME_WORLD;
  w.force[0] = fx;
  w.mode = rbsim::wrench_t::MODE_ONE_STEP;
  w.apply_at_step = -1;
  return w;
}

inline rbsim::command_t commandMessage(const std::string& client, int64_t seq, int8_t command) {
  rbsim::command_t c{};
  c.client = client;
  c.seq = seq;
  c.command = command;
  return c;
}

inline CommandOutcome send(CommandHandler& handler, const rbsim::wrench_t& message, int64_t now = 0) {
  const auto bytes = encoded(message);
  return handler.handleWrench(bytes.data(), bytes.size(), now);
}

inline CommandOutcome send(CommandHandler& handler, const rbsim::command_t& message, int64_t now = 0) {
  const auto bytes = encoded(message);
  return handler.handleCommand(bytes.data(), bytes.size(), now);
}

}  // namespace rbsim::test
