#include "daemon/server.h"

#include <poll.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include <rbsim/ack_t.hpp>
#include <rbsim/command_t.hpp>
#include <rbsim/status_t.hpp>
#include <rbsim/wrench_t.hpp>

#include "config/config_loader.h"
#include "daemon/log.h"
#include "daemon/message_decode.h"
#include "daemon/wire_convert.h"

namespace rbsim {

namespace {

int64_t wallMicroseconds() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

constexpr Nanoseconds kNanosecondsPerSecond = 1000000000;

Nanoseconds periodOf(double hertz) {
  return static_cast<Nanoseconds>(std::llround(1e9 / hertz));
}

}  // namespace

Server::Server(ServerSettings settings, World initialWorld, std::string configDirectory)
    : m_settings(std::move(settings)),
      m_initialWorld(initialWorld),
      m_world(std::move(initialWorld)),
      m_configDirectory(std::move(configDirectory)),
      m_clock(m_world.settings().dt, m_settings.realTimeFactor, m_settings.catchUp,
              m_settings.maxBurst),
      m_paused(m_settings.startPaused) {
  const double dt = m_world.settings().dt;
  m_stateEverySteps =
      m_settings.stateRate <= 0.0
          ? 1
          : std::max<int64_t>(1, static_cast<int64_t>(std::llround(1.0 / (m_settings.stateRate * dt))));
}

Expected<bool> Server::open() {
  const double dt = m_world.settings().dt;
  m_contactsEverySteps =
      m_settings.contactsRate <= 0.0
          ? 0
          : std::max<int64_t>(1, static_cast<int64_t>(std::llround(1.0 / (m_settings.contactsRate * dt))));
  m_lcm = std::make_unique<lcm::LCM>(m_settings.lcmUrl);
  if (!m_lcm->good())
    return Error{"cannot open LCM with URL '" + m_settings.lcmUrl +
                 "' (is there a route for multicast, e.g. `ip route add 224.0.0.0/4 dev lo`?)"};
  // Channel names are exact: the prefix was checked to hold no regex characters.
  m_lcm->subscribe(channel("WRENCH"), &Server::onWrench, this)->setQueueCapacity(10000);
  m_lcm->subscribe(channel("COMMAND"), &Server::onCommand, this)->setQueueCapacity(10000);
  if (!m_settings.recordPath.empty()) {
    const auto opened = m_recorder.open(m_settings.recordPath);
    if (!opened) return opened.error();
  }
  return true;
}

bool Server::durationReached() const {
  return m_settings.duration &&
         m_world.time() >= *m_settings.duration - 0.5 * m_world.settings().dt;
}

bool Server::shouldStep() const { return (!m_paused || m_stepsRequested > 0) && !durationReached(); }

int Server::run(SignalEvents& signals) {
  const Nanoseconds statusPeriod = periodOf(m_settings.statusRate);
  const Nanoseconds pausedStatePeriod =
      m_settings.stateRate > 0.0 ? periodOf(m_settings.stateRate) : periodOf(100.0);
  Nanoseconds now = monotonicNow();
  m_lastStatus = now;
  m_stepAtLastStatus = m_world.stepCount();
  publishWorld();
  publishState();
  publishStatus(now);
  m_clock.anchor(now);
  const Nanoseconds runStart = now;
  const int64_t stepAtStart = m_world.stepCount();
  logInfo("stepping " + std::to_string(m_world.bodyCount()) + " bodies at dt = " +
          std::to_string(m_world.settings().dt) + " s, real-time factor " +
          std::to_string(m_settings.realTimeFactor) + (m_paused ? " (paused)" : ""));

  pollfd fds[2] = {{m_lcm->getFileno(), POLLIN, 0}, {signals.fileDescriptor(), POLLIN, 0}};
  bool wasStepping = shouldStep();
  while (!m_stopRequested && !durationReached()) {
    now = monotonicNow();
    const bool stepping = shouldStep();
    if (stepping && !wasStepping) m_clock.anchor(now);  // resumed: no burst for the pause
    wasStepping = stepping;

    Nanoseconds wakeAt = m_lastStatus + statusPeriod;
    if (stepping) {
      wakeAt = m_stepsRequested > 0 ? now : std::min(wakeAt, m_clock.nextDeadline(now));
    } else {
      wakeAt = std::min(wakeAt, m_lastPausedStatePublish + pausedStatePeriod);
    }

    // Wait for the deadline, taking messages and signals as they come.
    const int64_t controlVersion = m_controlVersion;
    while (now < wakeAt && !m_stopRequested && controlVersion == m_controlVersion) {
      // Sleep until `spin` before the deadline, then poll without sleeping:
      // a timer wake-up on a virtual machine can come tens of µs late, a
      // spin cannot. Messages and signals are still taken while spinning.
      const Nanoseconds remaining = wakeAt - now;
      const Nanoseconds spin = stepping ? m_settings.spinNanoseconds : 0;
      const Nanoseconds sleep = remaining > spin ? remaining - spin : 0;
      timespec timeout{static_cast<time_t>(sleep / kNanosecondsPerSecond),
                       static_cast<long>(sleep % kNanosecondsPerSecond)};
      fds[0].revents = fds[1].revents = 0;
      if (ppoll(fds, 2, &timeout, nullptr) > 0) {
        if (fds[1].revents & POLLIN) {
          const SignalEvent event = signals.read();
          if (event == SignalEvent::Stop) {
            logInfo("stop signal received: finishing");
            m_stopRequested = true;
          } else if (event == SignalEvent::Hangup) {
            logInfo("SIGHUP ignored: send a RESET command to return to the initial world");
          }
        }
        if (fds[0].revents & POLLIN) drainMessages();
      }
      now = monotonicNow();
    }
    if (m_stopRequested) break;
    if (controlVersion != m_controlVersion) continue;  // pause/resume/rate changed: re-plan

    drainMessages();  // everything that arrived up to the step boundary
    now = monotonicNow();
    if (shouldStep() && (m_stepsRequested > 0 || now >= m_clock.nextDeadline(now))) stepOnce();
    now = monotonicNow();
    if (!shouldStep() && now >= m_lastPausedStatePublish + pausedStatePeriod) {
      publishState();
      m_lastPausedStatePublish = now;
    }
    if (now >= m_lastStatus + statusPeriod) publishStatus(now);
  }

  // Clean exit: a last state and status, then close the record file.
  drainMessages();
  publishState();
  publishStatus(monotonicNow());
  m_recorder.close();
  const auto micros = [](Nanoseconds ns) { return std::to_string(static_cast<double>(ns) * 1e-3); };
  const double wallSeconds = static_cast<double>(monotonicNow() - runStart) * 1e-9;
  const double achievedFactor =
      wallSeconds > 0.0
          ? static_cast<double>(m_world.stepCount() - stepAtStart) * m_world.settings().dt / wallSeconds
          : 0.0;
  logInfo("stopped at step " + std::to_string(m_world.stepCount()) + " (t = " +
          std::to_string(m_world.time()) + " s), " + std::to_string(m_clock.overruns()) +
          " overruns, " + std::to_string(m_clock.slips()) + " slips, worst step " +
          std::to_string(m_worstStepEver * 1e3) + " ms; step-start lateness over " +
          std::to_string(m_lateness.count()) + " paced steps: p50 " +
          micros(m_lateness.percentile(0.5)) + " us, p99 " + micros(m_lateness.percentile(0.99)) +
          " us, max " + micros(m_lateness.maximum()) + " us; achieved real-time factor " +
          std::to_string(achievedFactor) + " over " + std::to_string(wallSeconds) + " s");
  return 0;
}

void Server::drainMessages() {
  // handleTimeout(0) returns at once when nothing is pending.
  while (m_lcm->handleTimeout(0) > 0) {
  }
}

void Server::stepOnce() {
  const bool requested = m_stepsRequested > 0;
  if (requested) {
    --m_stepsRequested;
  } else {
    m_lateness.add(m_clock.beginStep(monotonicNow()));
  }
  const int64_t stepNumber = m_world.stepCount() + 1;
  m_wrenches.applyForStep(m_world, stepNumber);
  const Nanoseconds start = monotonicNow();
  m_world.step();
  const double seconds = static_cast<double>(monotonicNow() - start) * 1e-9;
  m_wrenches.finishStep(stepNumber);
  m_stepTimes.sum += seconds;
  m_stepTimes.worst = std::max(m_stepTimes.worst, seconds);
  ++m_stepTimes.count;
  m_worstStepEver = std::max(m_worstStepEver, seconds);

  const bool lastRequested = requested && m_stepsRequested == 0;
  if (m_world.stepCount() % m_stateEverySteps == 0 || lastRequested) publishState();
  if (m_contactsEverySteps > 0 && (m_world.stepCount() % m_contactsEverySteps == 0 || lastRequested))
    publishContacts();
  if (!requested) m_clock.endStep(monotonicNow());
}

void Server::acknowledge(const std::string& client, int64_t seq, int8_t kind, int8_t request,
                         bool accepted, const std::string& reason, int64_t effectiveStep) {
  rbsim::ack_t ack;
  ack.utime = wallMicroseconds();
  ack.client = client;
  ack.seq = seq;
  ack.kind = kind;
  ack.request = request;
  ack.accepted = accepted;
  ack.reason = reason;
  ack.effective_step = accepted ? effectiveStep : -1;
  if (accepted) {
    ++m_counters.accepted;
  } else {
    ++m_counters.rejected;
    logDebug("rejected " + std::string(kind == rbsim::ack_t::KIND_WRENCH ? "wrench" : "command") +
             " from '" + client + "' seq " + std::to_string(seq) + ": " + reason);
  }
  publish(channel("ACK"), ack);
}

void Server::onWrench(const lcm::ReceiveBuffer* buffer, const std::string& channelName) {
  record(channelName, buffer->data, buffer->data_size, buffer->recv_utime);
  rbsim::wrench_t message;
  if (!decodeWholeMessage(message, buffer->data, buffer->data_size)) {
    acknowledge("", -1, rbsim::ack_t::KIND_WRENCH, -1, false,
                "undecodable wrench_t message (" + std::to_string(buffer->data_size) + " bytes)", -1);
    return;
  }
  const auto request =
      wrenchRequestFrom(message, m_world, m_world.stepCount() + 1, m_settings.limits);
  if (!request) {
    acknowledge(message.client, message.seq, rbsim::ack_t::KIND_WRENCH, message.mode, false,
                request.error().message, -1);
    return;
  }
  m_wrenches.add(*request);
  acknowledge(message.client, message.seq, rbsim::ack_t::KIND_WRENCH, message.mode, true, "",
              request->firstStep);
}

void Server::onCommand(const lcm::ReceiveBuffer* buffer, const std::string& channelName) {
  record(channelName, buffer->data, buffer->data_size, buffer->recv_utime);
  rbsim::command_t message;
  if (!decodeWholeMessage(message, buffer->data, buffer->data_size)) {
    acknowledge("", -1, rbsim::ack_t::KIND_COMMAND, -1, false,
                "undecodable command_t message (" + std::to_string(buffer->data_size) + " bytes)",
                -1);
    return;
  }
  const auto reject = [&](const std::string& reason) {
    acknowledge(message.client, message.seq, rbsim::ack_t::KIND_COMMAND, message.command, false,
                reason, -1);
  };
  const auto accept = [&](const std::string& note = "") {
    acknowledge(message.client, message.seq, rbsim::ack_t::KIND_COMMAND, message.command, true,
                note, m_world.stepCount() + 1);
  };
  const auto controlChanged = [&] { ++m_controlVersion; };

  switch (message.command) {
    case rbsim::command_t::PAUSE:
      m_paused = true;
      m_stepsRequested = 0;
      controlChanged();
      accept();
      return;
    case rbsim::command_t::RESUME:
      m_paused = false;
      m_stepsRequested = 0;
      controlChanged();
      accept();
      return;
    case rbsim::command_t::STEP:
      if (!m_paused) return reject("STEP needs the server to be paused (send PAUSE first)");
      if (message.num_steps < 1 || message.num_steps > m_settings.maxStepsPerCommand)
        return reject("num_steps must be between 1 and " +
                      std::to_string(m_settings.maxStepsPerCommand));
      // The first of these steps comes after the steps still pending from
      // earlier STEP commands.
      acknowledge(message.client, message.seq, rbsim::ack_t::KIND_COMMAND, message.command, true,
                  "", m_world.stepCount() + 1 + m_stepsRequested);
      m_stepsRequested += message.num_steps;
      controlChanged();
      return;
    case rbsim::command_t::RESET:
      if (!message.path.empty()) return reject("reset from a checkpoint file is not supported yet");
      {
        // Ids handed out to spawned bodies stay taken (body ids are never reused).
        const int32_t lastSerial = m_world.lastSerial();
        m_world = m_initialWorld;
        m_world.continueSerialsAfter(lastSerial);
      }
      m_wrenches.clearAll();
      m_stepsRequested = 0;
      ++m_worldRevision;
      controlChanged();
      accept();
      publishWorld();
      publishState();
      return;
    case rbsim::command_t::SET_REAL_TIME_FACTOR:
      if (!std::isfinite(message.real_time_factor) || message.real_time_factor < 0.0 ||
          message.real_time_factor > m_settings.maxRealTimeFactor)
        return reject("real_time_factor must be 0 (as fast as possible) or positive up to " +
                      std::to_string(m_settings.maxRealTimeFactor));
      m_clock.setRealTimeFactor(message.real_time_factor, monotonicNow());
      controlChanged();
      accept();
      return;
    case rbsim::command_t::SPAWN: {
      const auto def = parseBodyDef(message.spawn_yaml, "spawn_yaml", m_configDirectory);
      if (!def) return reject(def.error().message);
      const auto id = m_world.createBody(*def);
      if (!id) return reject(id.error().message);
      ++m_worldRevision;
      accept();
      publishWorld();
      return;
    }
    case rbsim::command_t::REMOVE: {
      const BodyId id = m_world.findBody(message.body);
      if (id.isNull()) return reject("unknown body '" + message.body + "'");
      m_world.removeBody(id);
      m_wrenches.removeBody(message.body);
      ++m_worldRevision;
      accept();
      publishWorld();
      return;
    }
    case rbsim::command_t::PUBLISH_WORLD:
      accept();
      publishWorld();
      return;
    case rbsim::command_t::SAVE_CHECKPOINT:
      return reject("checkpoints are not supported by this server version");
    default:
      return reject("unknown command " + std::to_string(message.command));
  }
}

template <class Message>
void Server::publish(const std::string& channelName, const Message& message) {
  const int size = message.getEncodedSize();
  m_encodeBuffer.resize(static_cast<std::size_t>(size));
  message.encode(m_encodeBuffer.data(), 0, size);
  m_lcm->publish(channelName, m_encodeBuffer.data(), static_cast<unsigned int>(size));
  record(channelName, m_encodeBuffer.data(), m_encodeBuffer.size(), wallMicroseconds());
}

void Server::record(const std::string& channelName, const void* data, std::size_t size,
                    int64_t utime) {
  m_recorder.write(channelName, data, size, utime);
}

void Server::publishState() {
  for (const auto& page : worldStatePages(m_world, wallMicroseconds(), m_worldRevision))
    publish(channel("STATE"), page);
}

void Server::publishContacts() {
  for (const auto& page : contactPages(m_world, wallMicroseconds())) publish(channel("CONTACTS"), page);
}

void Server::publishWorld() {
  for (const auto& page : worldDescriptionPages(m_world, wallMicroseconds(), m_worldRevision))
    publish(channel("WORLD"), page);
}

void Server::publishStatus(Nanoseconds now) {
  rbsim::status_t status;
  status.utime = wallMicroseconds();
  status.step = m_world.stepCount();
  status.sim_time = m_world.time();
  status.world_revision = m_worldRevision;
  status.dt = m_world.settings().dt;
  status.paused = m_paused;
  status.target_real_time_factor = m_clock.realTimeFactor();
  const double window = static_cast<double>(now - m_lastStatus) * 1e-9;
  const int64_t steps = m_world.stepCount() - m_stepAtLastStatus;
  status.window = window;
  status.measured_real_time_factor =
      window > 0.0 && steps > 0 ? static_cast<double>(steps) * m_world.settings().dt / window : 0.0;
  status.step_time_mean =
      m_stepTimes.count > 0 ? m_stepTimes.sum / static_cast<double>(m_stepTimes.count) : 0.0;
  status.step_time_worst = m_stepTimes.worst;
  status.overruns = m_clock.overruns();
  status.commands_accepted = m_counters.accepted;
  status.commands_rejected = m_counters.rejected;
  status.num_bodies = m_world.bodyCount();
  status.num_frozen_bodies = 0;
  status.num_active_wrenches = m_wrenches.activeCount();
  status.num_contacts = m_world.contactPointCount();
  publish(channel("STATUS"), status);
  m_recorder.flush();
  m_lastStatus = now;
  m_stepAtLastStatus = m_world.stepCount();
  m_stepTimes = {};
}

}  // namespace rbsim
