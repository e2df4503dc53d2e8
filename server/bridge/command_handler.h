#pragma once
// The server's command path without LCM and without a clock: raw bytes of a
// wrench_t, command_t, joint_command_t or robot_command_t in, the ack_t and what the caller must do out. The
// same handler serves rbserver, a replay of a recorded session and fuzz
// targets, so all three take exactly the same decisions.
//
// Every message gets exactly one ack, accepted or rejected with a reason;
// nothing in the session changes unless the message is accepted.
//
// Limits and access control, in the order they are checked: the message
// size (limits.max_message_bytes, before decoding), read-only mode
// (server.read_only), the sender's rate (limits.client_rate/client_burst),
// then per message: bodies that accept wrenches (limits.wrench_bodies),
// the wrench limits (which bound joint efforts too), and the number of
// bodies and joints for SPAWN (limits.max_bodies, limits.max_joints).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <rbsim/ack_t.hpp>
#include <rbsim/command_t.hpp>

#include "bridge/client_rate_limiter.h"
#include "config/server_settings.h"
#include "session/session.h"

namespace rbsim {

// What handling one message asks of the caller, besides publishing the ack.
struct CommandOutcome {
  rbsim::ack_t ack;  // utime is 0: the caller stamps it when it publishes
  bool publishWorld = false;  // the description changed or was asked for
  bool publishState = false;  // the state jumped (RESET)
  bool paceChanged = false;   // pause, resume, step or rate: re-plan the next deadline
  std::optional<double> realTimeFactor;  // SET_REAL_TIME_FACTOR: the new target
  // For the server's log: a spawned robot's load report (robot/urdf_robot.h:
  // what its links and joints were made into, what of its URDF went unused).
  std::vector<std::string> logLines;
};

class CommandHandler {
 public:
  // `settings` gives the channel prefix and the limits; mesh files of spawned
  // bodies must lie under `spawnMeshDirectory` (see parseSpawnDef). The
  // session must outlive the handler.
  CommandHandler(Session& session, ServerSettings settings, std::string spawnMeshDirectory);

  // A message received on `channel`: <prefix>WRENCH, <prefix>COMMAND,
  // <prefix>JOINT_COMMAND or <prefix>ROBOT_COMMAND.
  // Nullopt for any other channel (no ack is due). `receivedAt` (ns of a
  // monotonic clock) is the only notion of time the handler has.
  std::optional<CommandOutcome> handle(std::string_view channel, const void* data,
                                       std::size_t size, int64_t receivedAt);
  CommandOutcome handleWrench(const void* data, std::size_t size, int64_t receivedAt);
  CommandOutcome handleCommand(const void* data, std::size_t size, int64_t receivedAt);
  CommandOutcome handleJointCommand(const void* data, std::size_t size, int64_t receivedAt);
  CommandOutcome handleRobotCommand(const void* data, std::size_t size, int64_t receivedAt);

  const std::string& wrenchChannel() const { return m_wrenchChannel; }
  const std::string& commandChannel() const { return m_commandChannel; }
  const std::string& jointCommandChannel() const { return m_jointCommandChannel; }
  const std::string& robotCommandChannel() const { return m_robotCommandChannel; }

 private:
  CommandOutcome applyCommand(const rbsim::command_t& message, int64_t receivedAt);
  // The checks every message goes through before its content: read-only
  // mode and the sender's rate. A reason when it must be rejected.
  std::optional<std::string> admissionRefusal(const std::string& client, int64_t receivedAt);
  std::optional<std::string> sizeRefusal(std::size_t size) const;

  Session& m_session;
  ServerSettings m_settings;
  std::string m_spawnMeshDirectory;
  std::string m_wrenchChannel;
  std::string m_commandChannel;
  std::string m_jointCommandChannel;
  std::string m_robotCommandChannel;
  ClientRateLimiter m_rateLimiter;
};

}  // namespace rbsim
