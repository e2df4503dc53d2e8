#include "daemon/server.h"

#include <poll.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include <rbsim/ack_t.hpp>

#include "rbsim/client/lcm_url.h"
#include <rbsim/command_t.hpp>
#include <rbsim/handled_t.hpp>
#include <rbsim/status_t.hpp>
#include <rbsim/wrench_t.hpp>

#include "bridge/robot_messages.h"
#include "bridge/sensor_messages.h"
#include "bridge/wire_convert.h"
#include "daemon/log.h"
#include "persist/checkpoint_file.h"

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

Server::Server(ServerSettings settings, World initialWorld, std::string spawnMeshDirectory, BodyVisuals visuals,
               RobotPublishingMap robotPublishing, std::vector<SensorDef> sensors)
    : m_settings(std::move(settings)),
      m_session(std::move(initialWorld), m_settings.startPaused),
      m_commands(m_session, m_settings, std::move(spawnMeshDirectory)),
      m_clock(m_session.world().settings().dt, m_settings.realTimeFactor, m_settings.catchUp,
              m_settings.maxBurst) {
  m_session.setVisuals(std::move(visuals));
  m_session.addRobotPublishing(robotPublishing);
  const double dt = world().settings().dt;
  m_sensors = SensorSuite(std::move(sensors), dt);
  for (std::size_t i = 0; i < m_sensors.size(); ++i)
    m_sensorChannels.push_back(sensorChannel(m_settings.channelPrefix, m_sensors.definition(i).name));
  m_stateEverySteps =
      m_settings.stateRate <= 0.0
          ? 1
          : std::max<int64_t>(1, static_cast<int64_t>(std::llround(1.0 / (m_settings.stateRate * dt))));
}

Expected<bool> Server::open() {
  const double dt = world().settings().dt;
  m_contactsEverySteps =
      m_settings.contactsRate <= 0.0
          ? 0
          : std::max<int64_t>(1, static_cast<int64_t>(std::llround(1.0 / (m_settings.contactsRate * dt))));
  m_lcm = std::make_unique<lcm::LCM>(m_settings.lcmUrl);
  if (!m_lcm->good())
    return Error{client::explainLcmOpenFailure(m_settings.lcmUrl)};
  // Before publishing anything: is another server on this URL and prefix?
  if (m_settings.instanceCheckSeconds > 0.0) {
    const auto other = listenForOtherInstance(
        *m_lcm, m_settings.channelPrefix,
        static_cast<Nanoseconds>(std::llround(m_settings.instanceCheckSeconds * 1e9)));
    if (other) {
      const std::string message =
          "another server publishes on channel prefix '" + m_settings.channelPrefix + "' of " +
          m_settings.lcmUrl + " (heard on " + other->channel +
          (other->instanceId.empty() ? "" : ", instance " + other->instanceId) +
          "): two servers on one prefix interleave their states";
      if (!m_settings.allowOtherInstances)
        return Error{message + "; stop it, give this one another --channel-prefix, or pass "
                               "--allow-other-instances to run anyway"};
      logWarning(message + "; running anyway (--allow-other-instances)");
    }
  }
  logInfo("instance " + m_instances.ownId());
  // Channel names are exact: the prefix was checked to hold no regex characters.
  m_lcm->subscribe(m_commands.wrenchChannel(), &Server::onInput, this)->setQueueCapacity(10000);
  m_lcm->subscribe(m_commands.commandChannel(), &Server::onInput, this)->setQueueCapacity(10000);
  m_lcm->subscribe(m_commands.jointCommandChannel(), &Server::onInput, this)->setQueueCapacity(10000);
  m_lcm->subscribe(m_commands.robotCommandChannel(), &Server::onInput, this)->setQueueCapacity(10000);
  m_lcm->subscribe(channel("STATUS"), &Server::onStatus, this);
  if (m_settings.checkpointEvery > 0.0) {
    if (m_settings.checkpointDirectory.empty())
      return Error{"checkpoint_every needs a checkpoint directory (server.checkpoint_dir or --checkpoint-dir)"};
    m_checkpointEverySteps = std::max<int64_t>(1, std::llround(m_settings.checkpointEvery / dt));
  }
  if (!m_settings.checkpointDirectory.empty()) {
    std::error_code error;
    std::filesystem::create_directories(m_settings.checkpointDirectory, error);
    if (error || !std::filesystem::is_directory(m_settings.checkpointDirectory))
      return Error{"cannot use checkpoint directory '" + m_settings.checkpointDirectory + "': " +
                   (error ? error.message() : std::string("not a directory"))};
  }
  if (!m_settings.recordPath.empty()) {
    const auto opened = m_recorder.open(m_settings.recordPath);
    if (!opened) return opened.error();
  }
  return true;
}

bool Server::durationReached() const {
  return m_settings.duration &&
         world().time() >= *m_settings.duration - 0.5 * world().settings().dt;
}

bool Server::shouldStep() const {
  return (!m_session.paused() || m_session.stepsRequested() > 0) && !durationReached();
}

int Server::run(SignalEvents& signals) {
  const Nanoseconds statusPeriod = periodOf(m_settings.statusRate);
  const Nanoseconds pausedStatePeriod =
      m_settings.stateRate > 0.0 ? periodOf(m_settings.stateRate) : periodOf(100.0);
  Nanoseconds now = monotonicNow();
  m_lastStatus = now;
  m_stepAtLastStatus = world().stepCount();
  publishWorld();
  publishState();
  publishStatus(now);
  m_clock.anchor(now);
  const Nanoseconds runStart = now;
  logInfo("stepping " + std::to_string(world().bodyCount()) + " bodies at dt = " +
          std::to_string(world().settings().dt) + " s on " +
          std::to_string(resolveThreadCount(world().settings().threads)) + " thread(s), real-time factor " +
          std::to_string(m_settings.realTimeFactor) + (m_session.paused() ? " (paused)" : ""));

  pollfd fds[2] = {{m_lcm->getFileno(), POLLIN, 0}, {signals.fileDescriptor(), POLLIN, 0}};
  bool wasStepping = shouldStep();
  bool wasRunning = !m_session.paused();
  m_runningRate.mark(now, false);
  while (!m_stopRequested && !durationReached()) {
    now = monotonicNow();
    m_runningRate.mark(now, wasRunning);
    wasRunning = !m_session.paused();
    const bool stepping = shouldStep();
    if (stepping && !wasStepping) m_clock.anchor(now);  // resumed: no burst for the pause
    wasStepping = stepping;

    Nanoseconds wakeAt = m_lastStatus + statusPeriod;
    if (stepping) {
      wakeAt = m_session.stepsRequested() > 0 ? now : std::min(wakeAt, m_clock.nextDeadline(now));
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
    if (shouldStep() && (m_session.stepsRequested() > 0 || now >= m_clock.nextDeadline(now))) stepOnce();
    now = monotonicNow();
    if (!shouldStep() && now >= m_lastPausedStatePublish + pausedStatePeriod) {
      publishState();
      m_lastPausedStatePublish = now;
    }
    if (now >= m_lastStatus + statusPeriod) publishStatus(now);
  }

  m_runningRate.mark(monotonicNow(), wasRunning);
  // Clean exit: a last state and status, then close the record file.
  drainMessages();
  publishState();
  publishStatus(monotonicNow());
  m_recorder.close();
  m_checkpoints.finish();
  if (m_checkpointEverySteps > 0)
    logInfo("periodic checkpoints: " + std::to_string(m_checkpoints.written()) + " written, " +
            std::to_string(m_checkpoints.failed()) + " failed, " + std::to_string(m_checkpoints.superseded()) +
            " superseded by a newer one before they were written");
  const auto micros = [](Nanoseconds ns) { return std::to_string(static_cast<double>(ns) * 1e-3); };
  const double wallSeconds = static_cast<double>(monotonicNow() - runStart) * 1e-9;
  logInfo("stopped at step " + std::to_string(world().stepCount()) + " (t = " +
          std::to_string(world().time()) + " s), " + std::to_string(m_clock.overruns()) +
          " overruns, " + std::to_string(m_clock.slips()) + " slips, worst step " +
          std::to_string(m_worstStepEver * 1e3) + " ms; step-start lateness over " +
          std::to_string(m_lateness.count()) + " paced steps: p50 " +
          micros(m_lateness.percentile(0.5)) + " us, p99 " + micros(m_lateness.percentile(0.99)) +
          " us, max " + micros(m_lateness.maximum()) + " us; achieved real-time factor " +
          std::to_string(m_runningRate.factor(world().settings().dt)) + " over " +
          std::to_string(m_runningRate.runningSeconds()) + " s running (" +
          std::to_string(wallSeconds - m_runningRate.runningSeconds()) + " s paused not counted)");
  return 0;
}

void Server::drainMessages() {
  // handleTimeout(0) returns at once when nothing is pending.
  while (m_lcm->handleTimeout(0) > 0) {
  }
}

void Server::resumeFrom(SessionState state) {
  m_session.resumeFrom(std::move(state.world), std::move(state.wrenches), state.worldRevision, state.paused,
                       state.stepsRequested, std::move(state.jointCommands));
  // --paused (server.start_paused) wins over the pause state saved.
  if (m_settings.startPaused) m_session.pause();
}

void Server::checkpointIfDue() {
  if (m_checkpointEverySteps <= 0 || world().stepCount() % m_checkpointEverySteps != 0) return;
  auto payload = encodeSessionCheckpoint(m_session);
  if (!payload) {
    logWarning("periodic checkpoint skipped: " + payload.error().message);
    return;
  }
  m_checkpoints.submit((std::filesystem::path(m_settings.checkpointDirectory) / kPeriodicCheckpointName).string(),
                       checkpointFileBytes(*payload), world().stepCount());
}

void Server::stepOnce() {
  const bool requested = m_session.takeRequestedStep();
  if (!requested) m_lateness.add(m_clock.beginStep(monotonicNow()));
  if (!requested) m_runningRate.stepped();
  m_sensors.beforeStep(world());
  const Nanoseconds start = monotonicNow();
  m_session.step();
  const double seconds = static_cast<double>(monotonicNow() - start) * 1e-9;
  for (const FreezeEvent& event : world().freezeEvents()) logWarning(describeFreeze(event));
  // Which body froze is part of the description: say it now, not at the next change.
  if (!world().freezeEvents().empty()) publishWorld();
  m_stepTimes.sum += seconds;
  m_stepTimes.worst = std::max(m_stepTimes.worst, seconds);
  ++m_stepTimes.count;
  m_worstStepEver = std::max(m_worstStepEver, seconds);

  checkpointIfDue();
  const bool lastRequested = requested && m_session.stepsRequested() == 0;
  const bool worldState = world().stepCount() % m_stateEverySteps == 0 || lastRequested;
  if (worldState) publishState(false);
  publishRobotStatesAfterStep(worldState, lastRequested);
  if (m_contactsEverySteps > 0 && (world().stepCount() % m_contactsEverySteps == 0 || lastRequested))
    publishContacts();
  publishSensors();
  if (!requested) m_clock.endStep(monotonicNow());
}

void Server::acknowledge(rbsim::ack_t ack) {
  ack.utime = wallMicroseconds();
  ack.instance_id = m_instances.ownId();
  if (ack.accepted) {
    ++m_counters.accepted;
  } else {
    ++m_counters.rejected;
    const char* kind = ack.kind == rbsim::ack_t::KIND_WRENCH          ? "wrench"
                       : ack.kind == rbsim::ack_t::KIND_JOINT_COMMAND ? "joint command"
                       : ack.kind == rbsim::ack_t::KIND_ROBOT_COMMAND ? "robot command"
                                                                      : "command";
    logDebug("rejected " + std::string(kind) + " from '" +
             ack.client + "' seq " + std::to_string(ack.seq) + ": " + ack.reason);
  }
  publish(channel("ACK"), ack);
}

void Server::onInput(const lcm::ReceiveBuffer* buffer, const std::string& channelName) {
  record(channelName, buffer->data, buffer->data_size, buffer->recv_utime);
  if (m_recorder.isOpen()) {
    // Where the message is handled, for an exact replay of the record file.
    rbsim::handled_t handled;
    handled.utime = wallMicroseconds();
    handled.step = world().stepCount();
    handled.world_revision = m_session.worldRevision();
    std::vector<uint8_t> bytes(static_cast<std::size_t>(handled.getEncodedSize()));
    handled.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    record(channel("HANDLED"), bytes.data(), bytes.size(), handled.utime);
  }
  auto outcome = m_commands.handle(channelName, buffer->data, buffer->data_size, monotonicNow());
  if (!outcome) return;
  if (outcome->realTimeFactor) m_clock.setRealTimeFactor(*outcome->realTimeFactor, monotonicNow());
  if (outcome->paceChanged) ++m_controlVersion;
  acknowledge(std::move(outcome->ack));
  for (const std::string& line : outcome->logLines) logInfo(line);
  if (outcome->publishWorld) publishWorld();
  if (outcome->publishState) publishState();
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

void Server::publishState(bool withRobots) {
  for (const auto& page : worldStatePages(world(), wallMicroseconds(), m_session.worldRevision()))
    publish(channel("STATE"), page);
  // The joints of the same step, after its bodies (none for a world without).
  if (world().jointCount() > 0)
    for (const auto& page : jointStatePages(world(), wallMicroseconds(), m_session.worldRevision()))
      publish(channel("JOINTS"), page);
  if (!withRobots) return;
  for (const std::string& robot : robotNames(world())) {
    const auto found = m_session.robotPublishing().find(robot);
    publishRobotState(robot, found != m_session.robotPublishing().end() && found->second.dynamics);
  }
}

void Server::publishRobotStatesAfterStep(bool worldStatePublished, bool lastRequested) {
  const double dt = world().settings().dt;
  for (const std::string& robot : robotNames(world())) {
    RobotPublishing publishing;
    if (const auto found = m_session.robotPublishing().find(robot); found != m_session.robotPublishing().end())
      publishing = found->second;
    bool due = lastRequested;
    if (publishing.stateRate > 0.0) {
      const int64_t every = std::max<int64_t>(1, std::llround(1.0 / (publishing.stateRate * dt)));
      due = due || world().stepCount() % every == 0;
    } else {
      due = due || worldStatePublished;
    }
    if (due) publishRobotState(robot, publishing.dynamics);
  }
}

void Server::publishRobotState(const std::string& robot, bool dynamics) {
  publish(channel("ROBOT_STATE"),
          robotStateMessage(world(), robot, dynamics, wallMicroseconds(), m_session.worldRevision()));
}

void Server::publishContacts() {
  for (const auto& page : contactPages(world(), wallMicroseconds())) publish(channel("CONTACTS"), page);
}

void Server::publishSensors() {
  if (m_sensors.empty()) return;
  m_sensors.readAfterStep(world(), m_sensorReadings);
  const int64_t utime = wallMicroseconds();
  for (const SensorReading& reading : m_sensorReadings) {
    const std::string& channelName = m_sensorChannels[reading.sensorIndex];
    std::visit([&](const auto& value) { publish(channelName, sensorMessage(reading, value, utime)); },
               reading.value);
  }
}

void Server::publishWorld() {
  for (const auto& page :
       worldDescriptionPages(world(), wallMicroseconds(), m_session.worldRevision(), &m_session.visuals()))
    publish(channel("WORLD"), page);
}

void Server::onStatus(const lcm::ReceiveBuffer*, const std::string& channelName,
                      const rbsim::status_t* status) {
  constexpr Nanoseconds kLogEvery = 10 * kNanosecondsPerSecond;
  if (m_instances.heard(status->instance_id, monotonicNow(), kLogEvery))
    logWarning("another server publishes on " + channelName + " (instance " + status->instance_id +
               ", this one is " + m_instances.ownId() +
               "): clients see both worlds' states interleaved; stop one of them");
}

void Server::publishStatus(Nanoseconds now) {
  rbsim::status_t status;
  status.utime = wallMicroseconds();
  status.step = world().stepCount();
  status.sim_time = world().time();
  status.world_revision = m_session.worldRevision();
  status.dt = world().settings().dt;
  status.paused = m_session.paused();
  status.target_real_time_factor = m_clock.realTimeFactor();
  const double window = static_cast<double>(now - m_lastStatus) * 1e-9;
  const int64_t steps = world().stepCount() - m_stepAtLastStatus;
  status.window = window;
  status.measured_real_time_factor =
      window > 0.0 && steps > 0 ? static_cast<double>(steps) * world().settings().dt / window : 0.0;
  status.step_time_mean =
      m_stepTimes.count > 0 ? m_stepTimes.sum / static_cast<double>(m_stepTimes.count) : 0.0;
  status.step_time_worst = m_stepTimes.worst;
  status.overruns = m_clock.overruns();
  status.commands_accepted = m_counters.accepted;
  status.commands_rejected = m_counters.rejected;
  status.num_bodies = world().bodyCount();
  status.num_frozen_bodies = world().frozenBodyCount();
  status.num_sleeping_bodies = world().sleepingBodyCount();
  status.num_active_wrenches = m_session.wrenches().activeCount();
  status.num_contacts = world().contactPointCount();
  status.instance_id = m_instances.ownId();
  constexpr Nanoseconds kRecent = 5 * kNanosecondsPerSecond;
  status.other_instance_id = m_instances.recentOther(now, kRecent);
  publish(channel("STATUS"), status);
  m_recorder.flush();
  m_lastStatus = now;
  m_stepAtLastStatus = world().stepCount();
  m_stepTimes = {};
}

}  // namespace rbsim
