#include "bridge/command_handler.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <rbsim/command_t.hpp>
#include <rbsim/joint_command_t.hpp>
#include <rbsim/robot_command_t.hpp>
#include <rbsim/wrench_t.hpp>

#include "bridge/message_decode.h"
#include "bridge/robot_messages.h"
#include "bridge/wire_convert.h"
#include "config/config_loader.h"
#include "persist/checkpoint_file.h"
#include "persist/session_checkpoint.h"

namespace rbsim {

namespace {

rbsim::ack_t ackFor(const std::string& client, int64_t seq, int8_t kind, int8_t request) {
  rbsim::ack_t ack;
  ack.utime = 0;
  ack.client = client;
  ack.seq = seq;
  ack.kind = kind;
  ack.request = request;
  ack.accepted = false;
  ack.effective_step = -1;
  ack.wrenches_cleared = 0;
  return ack;
}

CommandOutcome rejected(rbsim::ack_t ack, std::string reason) {
  CommandOutcome outcome;
  outcome.ack = std::move(ack);
  outcome.ack.accepted = false;
  outcome.ack.reason = std::move(reason);
  outcome.ack.effective_step = -1;
  return outcome;
}

CommandOutcome accepted(rbsim::ack_t ack, int64_t effectiveStep, std::string note = "") {
  CommandOutcome outcome;
  outcome.ack = std::move(ack);
  outcome.ack.accepted = true;
  outcome.ack.reason = std::move(note);
  outcome.ack.effective_step = effectiveStep;
  return outcome;
}

// The names of the joints that hold `body`.
std::vector<std::string> jointsOf(const World& world, BodyId body) {
  std::vector<std::string> names;
  for (int i = 0; i < world.jointCount(); ++i) {
    const JointDef& def = world.jointDefinitionAt(i);
    if (def.bodyA == body || def.bodyB == body) names.push_back(def.name);
  }
  return names;
}

// The sender's text (its client name, the names in its URDF) as one log
// line: control characters (a newline would forge a line) shown as '?'.
std::string printable(std::string text) {
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return text;
}

// Adds a parsed spawn to the world, all or nothing: the World's own checks
// (a joint's length, two joints of one name, ...) can still refuse a part,
// and then what was added is taken out again, joints first. The reason names
// the part as the spawn's text does ("spawn_yaml:4:5: joints[0]: ...").
std::optional<std::string> addSpawn(World& world, const SpawnDef& spawn) {
  std::vector<BodyId> bodies;
  std::vector<JointId> joints;
  const auto undo = [&](std::string reason) {
    for (auto joint = joints.rbegin(); joint != joints.rend(); ++joint) world.removeJoint(*joint);
    for (auto body = bodies.rbegin(); body != bodies.rend(); ++body) world.removeBody(*body);
    return std::optional<std::string>(std::move(reason));
  };
  for (const BodyDef& def : spawn.bodies) {
    const auto id = world.createBody(def);
    if (!id) return undo(id.error().message);
    bodies.push_back(*id);
  }
  for (const NamedJointDef& named : spawn.joints) {
    JointDef def = named.def;
    def.bodyA = named.bodyA == "world" ? BodyId{} : world.findBody(named.bodyA);
    def.bodyB = named.bodyB == "world" ? BodyId{} : world.findBody(named.bodyB);
    const auto id = world.createJoint(def);
    if (!id) return undo(named.source + ": " + id.error().message);
    joints.push_back(*id);
  }
  // Pairs of the new robots' bodies (removing the bodies would drop them).
  for (const ExcludedPair& pair : spawn.excludedPairs) {
    const auto set = world.setPairCollision(world.findBody(pair.bodyA), world.findBody(pair.bodyB), false);
    if (!set) return undo(set.error().message);
  }
  return std::nullopt;
}

}  // namespace

CommandHandler::CommandHandler(Session& session, ServerSettings settings,
                               std::string spawnMeshDirectory)
    : m_session(session),
      m_settings(std::move(settings)),
      m_spawnMeshDirectory(std::move(spawnMeshDirectory)),
      m_wrenchChannel(m_settings.channelPrefix + "WRENCH"),
      m_commandChannel(m_settings.channelPrefix + "COMMAND"),
      m_jointCommandChannel(m_settings.channelPrefix + "JOINT_COMMAND"),
      m_robotCommandChannel(m_settings.channelPrefix + "ROBOT_COMMAND"),
      m_rateLimiter(m_settings.clientRate, m_settings.clientBurst) {}

std::optional<std::string> CommandHandler::sizeRefusal(std::size_t size) const {
  if (static_cast<int64_t>(size) <= m_settings.maxMessageBytes) return std::nullopt;
  return "message of " + std::to_string(size) + " bytes exceeds limits.max_message_bytes (" +
         std::to_string(m_settings.maxMessageBytes) + ")";
}

std::optional<std::string> CommandHandler::admissionRefusal(const std::string& client, int64_t receivedAt) {
  if (m_settings.readOnly) return std::string("the server is read-only: it takes no wrenches or commands");
  if (!m_rateLimiter.allow(client, receivedAt))
    return "rate limit: client '" + client + "' sends more than " + std::to_string(m_settings.clientRate) +
           " messages/s (burst " + std::to_string(m_settings.clientBurst) + "); message dropped";
  return std::nullopt;
}

std::optional<CommandOutcome> CommandHandler::handle(std::string_view channel, const void* data,
                                                     std::size_t size, int64_t receivedAt) {
  if (channel == m_wrenchChannel) return handleWrench(data, size, receivedAt);
  if (channel == m_commandChannel) return handleCommand(data, size, receivedAt);
  if (channel == m_jointCommandChannel) return handleJointCommand(data, size, receivedAt);
  if (channel == m_robotCommandChannel) return handleRobotCommand(data, size, receivedAt);
  return std::nullopt;
}

CommandOutcome CommandHandler::handleWrench(const void* data, std::size_t size, int64_t receivedAt) {
  if (auto refusal = sizeRefusal(size)) return rejected(ackFor("", -1, rbsim::ack_t::KIND_WRENCH, -1), *refusal);
  rbsim::wrench_t message;
  if (!decodeWholeMessage(message, data, size))
    return rejected(ackFor("", -1, rbsim::ack_t::KIND_WRENCH, -1),
                    "undecodable wrench_t message (" + std::to_string(size) + " bytes)");
  rbsim::ack_t ack = ackFor(message.client, message.seq, rbsim::ack_t::KIND_WRENCH, message.mode);
  if (auto refusal = admissionRefusal(message.client, receivedAt)) return rejected(std::move(ack), *refusal);
  if (m_settings.wrenchBodies && !message.body.empty() &&
      std::find(m_settings.wrenchBodies->begin(), m_settings.wrenchBodies->end(), message.body) ==
          m_settings.wrenchBodies->end())
    return rejected(std::move(ack), "body '" + message.body +
                                        "' does not accept external wrenches (not in limits.wrench_bodies)");
  World& world = m_session.world();
  const auto request = wrenchRequestFrom(message, world, world.stepCount() + 1, m_settings.limits);
  if (!request) return rejected(std::move(ack), request.error().message);
  const int cleared = isClear(request->mode) ? m_session.wrenches().countClearedBy(*request) : 0;
  m_session.wrenches().add(*request);
  CommandOutcome outcome = accepted(std::move(ack), request->firstStep);
  outcome.ack.wrenches_cleared = cleared;
  return outcome;
}

CommandOutcome CommandHandler::handleJointCommand(const void* data, std::size_t size, int64_t receivedAt) {
  const int8_t kind = rbsim::ack_t::KIND_JOINT_COMMAND;
  if (auto refusal = sizeRefusal(size)) return rejected(ackFor("", -1, kind, -1), *refusal);
  rbsim::joint_command_t message;
  if (!decodeWholeMessage(message, data, size))
    return rejected(ackFor("", -1, kind, -1),
                    "undecodable joint_command_t message (" + std::to_string(size) + " bytes)");
  rbsim::ack_t ack = ackFor(message.client, message.seq, kind, message.mode);
  if (auto refusal = admissionRefusal(message.client, receivedAt)) return rejected(std::move(ack), *refusal);
  World& world = m_session.world();
  const auto request = jointCommandRequestFrom(message, world, world.stepCount() + 1, m_settings.limits);
  if (!request) return rejected(std::move(ack), request.error().message);
  // Every command goes through the scheduler, the next step's too, so that
  // a command takes effect at the start of its step however it was sent.
  m_session.jointCommands().add(*request);
  return accepted(std::move(ack), request->firstStep);
}

CommandOutcome CommandHandler::handleRobotCommand(const void* data, std::size_t size, int64_t receivedAt) {
  const int8_t kind = rbsim::ack_t::KIND_ROBOT_COMMAND;
  if (auto refusal = sizeRefusal(size)) return rejected(ackFor("", -1, kind, -1), *refusal);
  rbsim::robot_command_t message;
  if (!decodeWholeMessage(message, data, size))
    return rejected(ackFor("", -1, kind, -1),
                    "undecodable robot_command_t message (" + std::to_string(size) + " bytes)");
  rbsim::ack_t ack = ackFor(message.client, message.seq, kind, 0);
  if (auto refusal = admissionRefusal(message.client, receivedAt)) return rejected(std::move(ack), *refusal);
  World& world = m_session.world();
  const auto request = robotCommandRequestFrom(message, world, world.stepCount() + 1, m_settings.limits);
  if (!request) return rejected(std::move(ack), request.error().message);
  if (request->steps > 0) {
    if (!m_session.paused())
      return rejected(std::move(ack), "steps needs the server to be paused (send PAUSE first)");
    if (request->steps > m_settings.maxStepsPerCommand)
      return rejected(std::move(ack), "steps must be at most " + std::to_string(m_settings.maxStepsPerCommand));
  }
  // All of it or none: every entry was checked above. The scheduler sets
  // them before one step, in entry order.
  for (const JointCommandRequest& joint : request->joints) m_session.jointCommands().add(joint);
  RobotPublishing& publishing = m_session.robotPublishing(message.robot);
  if (request->stateRate > 0.0) publishing.stateRate = request->stateRate;
  if (request->stateRate < 0.0) publishing.stateRate = 0.0;
  if (request->stateDynamics >= 0) publishing.dynamics = request->stateDynamics == 1;
  CommandOutcome outcome = accepted(std::move(ack), request->firstStep);
  if (request->steps > 0) {
    m_session.requestSteps(request->steps);
    outcome.paceChanged = true;
  }
  return outcome;
}

CommandOutcome CommandHandler::handleCommand(const void* data, std::size_t size, int64_t receivedAt) {
  if (auto refusal = sizeRefusal(size)) return rejected(ackFor("", -1, rbsim::ack_t::KIND_COMMAND, -1), *refusal);
  rbsim::command_t message;
  if (!decodeWholeMessage(message, data, size))
    return rejected(ackFor("", -1, rbsim::ack_t::KIND_COMMAND, -1),
                    "undecodable command_t message (" + std::to_string(size) + " bytes)");
  return applyCommand(message, receivedAt);
}

CommandOutcome CommandHandler::applyCommand(const rbsim::command_t& message, int64_t receivedAt) {
  rbsim::ack_t ack = ackFor(message.client, message.seq, rbsim::ack_t::KIND_COMMAND, message.command);
  if (auto refusal = admissionRefusal(message.client, receivedAt)) return rejected(std::move(ack), *refusal);
  World& world = m_session.world();
  const int64_t nextStep = world.stepCount() + 1;
  const auto reject = [&](std::string reason) { return rejected(std::move(ack), std::move(reason)); };

  switch (message.command) {
    case rbsim::command_t::PAUSE: {
      m_session.pause();
      CommandOutcome outcome = accepted(std::move(ack), nextStep);
      outcome.paceChanged = true;
      return outcome;
    }
    case rbsim::command_t::RESUME: {
      m_session.resume();
      CommandOutcome outcome = accepted(std::move(ack), nextStep);
      outcome.paceChanged = true;
      return outcome;
    }
    case rbsim::command_t::STEP: {
      if (!m_session.paused()) return reject("STEP needs the server to be paused (send PAUSE first)");
      if (message.num_steps < 1 || message.num_steps > m_settings.maxStepsPerCommand)
        return reject("num_steps must be between 1 and " +
                      std::to_string(m_settings.maxStepsPerCommand));
      // The first of these steps comes after the steps still pending from
      // earlier STEP commands.
      CommandOutcome outcome = accepted(std::move(ack), nextStep + m_session.stepsRequested());
      m_session.requestSteps(message.num_steps);
      outcome.paceChanged = true;
      return outcome;
    }
    case rbsim::command_t::RESET: {
      if (message.path.empty()) {
        m_session.resetToInitialWorld();
      } else {
        const auto path = checkpointPathIn(m_settings.checkpointDirectory, message.path);
        if (!path) return reject(path.error().message);
        auto state = loadSessionCheckpoint(*path, m_session.initialWorld().settings(), true);
        if (!state) return reject(state.error().message);
        m_session.replaceWorld(std::move(state->world), std::move(state->wrenches));
      }
      CommandOutcome outcome = accepted(std::move(ack), nextStep);
      outcome.paceChanged = true;
      outcome.publishWorld = true;
      outcome.publishState = true;
      return outcome;
    }
    case rbsim::command_t::SET_REAL_TIME_FACTOR: {
      if (!std::isfinite(message.real_time_factor) || message.real_time_factor < 0.0 ||
          message.real_time_factor > m_settings.maxRealTimeFactor)
        return reject("real_time_factor must be 0 (as fast as possible) or positive up to " +
                      std::to_string(m_settings.maxRealTimeFactor));
      CommandOutcome outcome = accepted(std::move(ack), nextStep);
      outcome.realTimeFactor = message.real_time_factor;
      outcome.paceChanged = true;
      return outcome;
    }
    case rbsim::command_t::SPAWN: {
      const auto existing = [&world](const std::string& name) -> std::optional<bool> {
        const BodyId id = world.findBody(name);
        if (id.isNull()) return std::nullopt;
        return !world.body(id).isStatic();
      };
      const auto worldBodies = [&world] {
        std::vector<std::string> all;
        for (BodyView body : world.bodies()) all.push_back(body.name());
        return all;
      };
      const auto spawn = parseSpawnDef(message.spawn_yaml, "spawn_yaml", m_spawnMeshDirectory, existing, worldBodies);
      if (!spawn) return reject(spawn.error().message);
      if (static_cast<int64_t>(world.bodyCount()) + static_cast<int64_t>(spawn->bodies.size()) > m_settings.maxBodies)
        return reject("the world has " + std::to_string(world.bodyCount()) + " bodies; " +
                      std::to_string(spawn->bodies.size()) + " more would exceed limits.max_bodies (" +
                      std::to_string(m_settings.maxBodies) + ")");
      if (static_cast<int64_t>(world.jointCount()) + static_cast<int64_t>(spawn->joints.size()) > m_settings.maxJoints)
        return reject("the world has " + std::to_string(world.jointCount()) + " joints; " +
                      std::to_string(spawn->joints.size()) + " more would exceed limits.max_joints (" +
                      std::to_string(m_settings.maxJoints) + ")");
      if (auto refusal = addSpawn(world, *spawn)) return reject(std::move(*refusal));
      std::vector<std::string> names;
      for (const BodyDef& def : spawn->bodies) names.push_back(def.name);
      m_session.addSpawnedVisuals(names, spawn->visuals);
      m_session.addRobotPublishing(spawn->robotPublishing);
      m_session.noteWorldChanged();
      CommandOutcome outcome = accepted(std::move(ack), nextStep);
      outcome.publishWorld = true;
      for (const std::string& line : spawn->robotReport)
        outcome.logLines.push_back(printable("spawn from '" + message.client + "': robots: " + line));
      return outcome;
    }
    case rbsim::command_t::REMOVE: {
      if (message.body.empty() == message.joint.empty())
        return reject("REMOVE names a body (body) or a joint (joint), exactly one of the two");
      if (!message.joint.empty()) {
        const JointId id = world.findJoint(message.joint);
        if (id.isNull()) return reject(unknownJointReason(world, message.joint));
        world.removeJoint(id);
        m_session.jointCommands().removeJoint(message.joint);
      } else {
        const BodyId id = world.findBody(message.body);
        if (id.isNull()) return reject(unknownBodyReason(world, message.body));
        // Its joints go with it, and so do the commands waiting for them.
        for (const std::string& joint : jointsOf(world, id)) m_session.jointCommands().removeJoint(joint);
        world.removeBody(id);
        m_session.wrenches().removeBody(message.body);
      }
      m_session.noteWorldChanged();
      CommandOutcome outcome = accepted(std::move(ack), nextStep);
      outcome.publishWorld = true;
      return outcome;
    }
    case rbsim::command_t::PUBLISH_WORLD: {
      CommandOutcome outcome = accepted(std::move(ack), nextStep);
      outcome.publishWorld = true;
      return outcome;
    }
    case rbsim::command_t::SAVE_CHECKPOINT: {
      const std::string name =
          message.path.empty() ? "checkpoint-" + std::to_string(world.stepCount()) + ".rbck" : message.path;
      const auto path = checkpointPathIn(m_settings.checkpointDirectory, name);
      if (!path) return reject(path.error().message);
      const auto saved = saveSessionCheckpoint(m_session, *path);
      if (!saved) return reject("checkpoint not saved: " + saved.error().message);
      return accepted(std::move(ack), nextStep, "saved " + *path);
    }
    default:
      return reject("unknown command " + std::to_string(message.command));
  }
}

}  // namespace rbsim
