#include "replay/replay.h"

#include <algorithm>
#include <deque>
#include <map>
#include <set>
#include <tuple>
#include <variant>

#include <rbsim/ack_t.hpp>
#include <rbsim/command_t.hpp>
#include <rbsim/handled_t.hpp>
#include <rbsim/robot_command_t.hpp>
#include <rbsim/joint_command_t.hpp>
#include <rbsim/joints_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <rbsim/world_t.hpp>
#include <rbsim/wrench_t.hpp>

#include "bridge/message_decode.h"
#include "bridge/sensor_messages.h"
#include "bridge/wire_convert.h"
#include "replay/state_comparison.h"

namespace rbsim {

namespace {

template <class Message>
std::optional<Message> decodeWhole(const std::vector<uint8_t>& data) {
  Message message;
  if (!decodeWholeMessage(message, data.data(), data.size())) return std::nullopt;
  return message;
}

template <class Message>
std::vector<uint8_t> encode(const Message& message) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// Which acks stand for a change of the simulated world.
bool changesTheWorld(const rbsim::ack_t& ack) {
  if (ack.kind == rbsim::ack_t::KIND_WRENCH || ack.kind == rbsim::ack_t::KIND_JOINT_COMMAND ||
      ack.kind == rbsim::ack_t::KIND_ROBOT_COMMAND)
    return true;
  return ack.kind == rbsim::ack_t::KIND_COMMAND &&
         (ack.request == rbsim::command_t::SPAWN || ack.request == rbsim::command_t::REMOVE ||
          ack.request == rbsim::command_t::RESET);
}

std::string describe(const rbsim::ack_t& ack) {
  const char* kind = ack.kind == rbsim::ack_t::KIND_WRENCH          ? "wrench"
                     : ack.kind == rbsim::ack_t::KIND_JOINT_COMMAND ? "joint command"
                     : ack.kind == rbsim::ack_t::KIND_ROBOT_COMMAND ? "robot command"
                                                                    : "command";
  return std::string(kind) + " seq " +
         std::to_string(ack.seq) + " from '" + ack.client + "'";
}

}  // namespace

// A received message waiting for its ack, by (kind, client, seq).
struct Replay::Input {
  std::string channel;
  std::vector<uint8_t> data;
  int64_t eventNumber = 0;
  std::optional<int64_t> handledStep;  // from a handled_t (--record files)
  std::optional<int64_t> handledRevision;
  int64_t applyAtStep = -1;            // wrenches and joint commands: as requested
};

struct Replay::Pending {
  using Key = std::tuple<int8_t, std::string, int64_t>;
  std::map<Key, std::deque<Input>> byKey;
  Input* latest = nullptr;  // the last message read, for the handled_t after it
  // Every sequence number each client's messages and acks show: a client
  // numbers its messages one after another, so a gap is a message the log
  // lost together with its ack.
  std::map<std::string, std::set<int64_t>, std::less<>> seqsByClient;
};

Replay::Replay(Session& session, CommandHandler& handler, std::string channelPrefix, bool verify,
               Output output, std::vector<SensorDef> sensors)
    : m_session(session),
      m_handler(handler),
      m_prefix(std::move(channelPrefix)),
      m_verify(verify),
      m_output(std::move(output)),
      m_pending(std::make_unique<Pending>()),
      m_sensors(std::move(sensors), session.world().settings().dt) {
  // The replay takes the steps the log shows, never on a clock: to the
  // command handler it is a paused server, so that a robot_command_t whose
  // `steps` the recorded (paused) server accepted is accepted here too.
  // The steps it asks for are the log's, taken by run().
  m_session.pause();
}

Replay::~Replay() = default;

Expected<ReplayReport> Replay::run(const std::string& logPath) {
  LcmLogReader reader;
  if (auto opened = reader.open(logPath); !opened) return opened.error();
  m_report = {};
  emitWorld(0);
  const std::string wrench = m_prefix + "WRENCH", command = m_prefix + "COMMAND",
                    jointCommand = m_prefix + "JOINT_COMMAND", robotCommand = m_prefix + "ROBOT_COMMAND",
                    handled = m_prefix + "HANDLED", ack = m_prefix + "ACK", state = m_prefix + "STATE",
                    joints = m_prefix + "JOINTS", sensor = m_prefix + "SENSOR_";
  while (!m_report.difference) {
    auto event = reader.next();
    if (!event) return event.error();
    if (!event->has_value()) break;
    const LogEvent& e = **event;
    ++m_report.eventsRead;
    if (!m_firstTimestamp) {
      m_firstTimestamp = e.timestamp;
      m_firstStep = m_session.world().stepCount();
    }
    m_eventTimestamp = e.timestamp;
    Expected<bool> done = true;
    if (e.channel == wrench || e.channel == command || e.channel == jointCommand || e.channel == robotCommand) {
      done = onInput(e);
    } else if (e.channel == handled) {
      done = onHandled(e);
    } else if (e.channel == ack) {
      done = onAck(e);
    } else if (e.channel == state) {
      done = onState(e);
    } else if (e.channel == joints) {
      done = onJoints(e);
    } else if (e.channel.starts_with(sensor)) {
      done = onSensor(e);
    }
    if (!done) return Error{"log '" + logPath + "', event " + std::to_string(e.eventNumber) + " (" +
                            e.channel + "): " + done.error().message};
  }
  if (m_report.difference) {
    // A bus log that lost a message and its ack both shows it only by the
    // gap in its client's numbers, which the messages after the difference
    // may be the first to show: read on for them before blaming the
    // simulation.
    while (true) {
      auto event = reader.next();
      if (!event || !event->has_value()) break;
      const LogEvent& e = **event;
      std::optional<std::pair<std::string, int64_t>> numbered;
      if (e.channel == ack) {
        if (const auto a = decodeWhole<rbsim::ack_t>(e.data)) numbered = {{a->client, a->seq}};
      } else if (e.channel == wrench) {
        if (const auto w = decodeWhole<rbsim::wrench_t>(e.data)) numbered = {{w->client, w->seq}};
      } else if (e.channel == command) {
        if (const auto c = decodeWhole<rbsim::command_t>(e.data)) numbered = {{c->client, c->seq}};
      } else if (e.channel == jointCommand) {
        if (const auto j = decodeWhole<rbsim::joint_command_t>(e.data)) numbered = {{j->client, j->seq}};
      } else if (e.channel == robotCommand) {
        if (const auto r = decodeWhole<rbsim::robot_command_t>(e.data)) numbered = {{r->client, r->seq}};
      }
      if (numbered) m_pending->seqsByClient[numbered->first].insert(numbered->second);
    }
    if (const auto gap = seqGap())
      return Error{"log '" + logPath + "': the states differ from the log (" + *m_report.difference +
                   ") and the log holds no message or ack of '" + gap->first + "' seq " + std::to_string(gap->second) +
                   " (lost by the logger?): the session cannot be replayed"};
  }
  return m_report;
}

std::optional<std::pair<std::string, int64_t>> Replay::seqGap() const {
  for (const auto& [client, seqs] : m_pending->seqsByClient) {
    int64_t previous = *seqs.begin();
    for (const int64_t seq : seqs) {
      if (seq > previous + 1) return std::pair<std::string, int64_t>{client, previous + 1};
      previous = seq;
    }
  }
  return std::nullopt;
}

Expected<bool> Replay::onInput(const LogEvent& event) {
  Input input;
  input.channel = event.channel;
  input.data = event.data;
  input.eventNumber = event.eventNumber;
  Pending::Key key{0, "", -1};  // an undecodable message is answered as client "", seq -1
  if (event.channel == m_prefix + "WRENCH") {
    std::get<0>(key) = rbsim::ack_t::KIND_WRENCH;
    if (const auto w = decodeWhole<rbsim::wrench_t>(event.data)) {
      key = {rbsim::ack_t::KIND_WRENCH, w->client, w->seq};
      input.applyAtStep = w->apply_at_step;
    }
  } else if (event.channel == m_prefix + "JOINT_COMMAND") {
    std::get<0>(key) = rbsim::ack_t::KIND_JOINT_COMMAND;
    if (const auto j = decodeWhole<rbsim::joint_command_t>(event.data)) {
      key = {rbsim::ack_t::KIND_JOINT_COMMAND, j->client, j->seq};
      input.applyAtStep = j->apply_at_step;
    }
  } else if (event.channel == m_prefix + "ROBOT_COMMAND") {
    std::get<0>(key) = rbsim::ack_t::KIND_ROBOT_COMMAND;
    if (const auto r = decodeWhole<rbsim::robot_command_t>(event.data)) {
      key = {rbsim::ack_t::KIND_ROBOT_COMMAND, r->client, r->seq};
      input.applyAtStep = r->apply_at_step;
    }
  } else {
    std::get<0>(key) = rbsim::ack_t::KIND_COMMAND;
    if (const auto c = decodeWhole<rbsim::command_t>(event.data))
      key = {rbsim::ack_t::KIND_COMMAND, c->client, c->seq};
  }
  m_pending->seqsByClient[std::get<1>(key)].insert(std::get<2>(key));
  auto& queue = m_pending->byKey[key];
  queue.push_back(std::move(input));
  m_pending->latest = &queue.back();
  return true;
}

Expected<bool> Replay::onHandled(const LogEvent& event) {
  const auto handled = decodeWhole<rbsim::handled_t>(event.data);
  if (!handled) return Error{"undecodable handled_t"};
  if (m_pending->latest == nullptr) return Error{"a handled_t that follows no wrench or command"};
  m_pending->latest->handledStep = handled->step;
  m_pending->latest->handledRevision = handled->world_revision;
  m_pending->latest = nullptr;
  return true;
}

Expected<bool> Replay::onAck(const LogEvent& event) {
  const auto ack = decodeWhole<rbsim::ack_t>(event.data);
  if (!ack) return Error{"undecodable ack_t"};
  m_pending->latest = nullptr;
  m_pending->seqsByClient[ack->client].insert(ack->seq);
  const auto found = m_pending->byKey.find({ack->kind, ack->client, ack->seq});
  if (found == m_pending->byKey.end() || found->second.empty()) {
    if (ack->accepted && changesTheWorld(*ack))
      return Error{"the server accepted " + describe(*ack) + " but the log holds no such message "
                   "before its ack (lost by the logger?): the session cannot be replayed"};
    return true;  // a rejection, or an accepted message with no effect on the states
  }
  Input input = std::move(found->second.front());
  found->second.pop_front();
  if (found->second.empty()) m_pending->byKey.erase(found);
  if (!ack->accepted || !changesTheWorld(*ack)) return true;

  // Where the server handled it: recorded, or the latest point the ack allows.
  int64_t step = m_session.world().stepCount();
  if (input.handledStep) {
    step = *input.handledStep;
  } else if (ack->kind == rbsim::ack_t::KIND_COMMAND || input.applyAtStep == -1) {
    step = ack->effective_step - 1;
  }
  if (auto advanced = advanceTo(step, describe(*ack)); !advanced) return advanced;
  if (input.handledRevision && *input.handledRevision != m_session.worldRevision()) {
    m_report.difference = "step " + std::to_string(step) + ": the server handled " + describe(*ack) +
                          " at world revision " + std::to_string(*input.handledRevision) +
                          ", the replay is at revision " + std::to_string(m_session.worldRevision());
    return true;
  }

  const auto outcome = m_handler.handle(input.channel, input.data.data(), input.data.size(), 0);
  ++m_report.messagesApplied;
  if (!outcome || !outcome->ack.accepted || outcome->ack.effective_step != ack->effective_step) {
    m_report.difference =
        "step " + std::to_string(step) + ": the server accepted " + describe(*ack) +
        " for step " + std::to_string(ack->effective_step) + ", the replay " +
        (!outcome || !outcome->ack.accepted
             ? "rejected it: " + (outcome ? outcome->ack.reason : std::string("not a wrench or command channel"))
             : "scheduled it for step " + std::to_string(outcome->ack.effective_step));
    return true;
  }
  if (outcome->publishWorld) emitWorld(event.timestamp);
  return true;
}

Expected<bool> Replay::advanceTo(int64_t step, const std::string& why) {
  const int64_t current = m_session.world().stepCount();
  if (step < current)
    return Error{why + " belongs to step " + std::to_string(step) + ", but the replay is already at step " +
                 std::to_string(current) + " (a log out of order, or of another session)"};
  // What the log holds bounds the steps: the recorded server cannot have
  // taken more than kMaxStepsPerSecond steps a wall-clock second (one free
  // body steps in about 100 ns) between its first event and this one, so a
  // corrupt step number fails here instead of replaying practically forever.
  constexpr double kMaxStepsPerSecond = 2e7;
  constexpr double kSlackSteps = 1e6;
  const double elapsed = std::max(0.0, static_cast<double>(m_eventTimestamp - *m_firstTimestamp) * 1e-6);
  const double reachable = static_cast<double>(m_firstStep) + kSlackSteps + kMaxStepsPerSecond * elapsed;
  if (static_cast<double>(step) > reachable)
    return Error{why + " belongs to step " + std::to_string(step) + ", which no server reaches " +
                 std::to_string(elapsed) + " s after the log's first event (at most " +
                 std::to_string(static_cast<int64_t>(reachable)) +
                 "): a corrupt log, not replayed"};
  for (int64_t s = current; s < step; ++s) {
    m_sensors.beforeStep(m_session.world());
    m_session.step();
    ++m_report.stepsSimulated;
    keepSensorReadings();
  }
  return true;
}

void Replay::keepSensorReadings() {
  if (m_sensors.empty()) return;
  m_sensors.readAfterStep(m_session.world(), m_sensorReadings);
  for (const SensorReading& reading : m_sensorReadings) {
    ReplayedReading& kept = m_replayedReadings[sensorChannel(m_prefix, reading.sensor->name)];
    kept.step = reading.step;
    kept.bytes = std::visit([&](const auto& value) { return encode(sensorMessage(reading, value, 0)); },
                            reading.value);
  }
}

Expected<bool> Replay::onSensor(const LogEvent& event) {
  // Every sensor message starts with its fingerprint, then utime and step
  // (int64, big-endian), the fields every sensor type has first.
  constexpr std::size_t kHeader = 24;
  if (event.data.size() < kHeader) return Error{"a sensor message shorter than its header"};
  uint64_t stepBits = 0;
  for (std::size_t i = 16; i < kHeader; ++i) stepBits = (stepBits << 8) | event.data[i];
  const auto step = static_cast<int64_t>(stepBits);
  if (auto advanced = advanceTo(step, "the sensor reading"); !advanced) return advanced;
  const auto kept = m_replayedReadings.find(event.channel);
  const bool replayed = kept != m_replayedReadings.end() && kept->second.step == step;
  std::vector<uint8_t> bytes;
  if (replayed) {
    bytes = kept->second.bytes;
    // The recorded utime (wall clock) in place of the replay's 0.
    std::copy(event.data.begin() + 8, event.data.begin() + 16, bytes.begin() + 8);
  }
  if (m_verify) {
    ++m_report.sensorReadingsCompared;
    if (!replayed) {
      m_report.difference = "step " + std::to_string(step) + ": the log has a reading on " + event.channel +
                            ", the replay none (is the sensor in the config the replay was given?)";
      return true;
    }
    if (bytes != event.data) {
      m_report.difference = "step " + std::to_string(step) + ": the reading on " + event.channel +
                            " differs from the log's";
      return blameLostAck(step);
    }
  }
  if (m_output && replayed) m_output(event.channel, bytes, event.timestamp);
  return true;
}

Expected<bool> Replay::onState(const LogEvent& event) {
  const auto recorded = decodeWhole<rbsim::world_state_t>(event.data);
  if (!recorded) return Error{"undecodable world_state_t"};
  if (auto advanced = advanceTo(recorded->step, "the state"); !advanced) return advanced;
  // A bus log can also lose an ack: its command then waits here unanswered,
  // and the replay cannot know whether it took effect. A logged world
  // revision the replay has not reached says that it did.
  if (recorded->world_revision != m_session.worldRevision()) {
    for (const auto& [key, queue] : m_pending->byKey) {
      if (std::get<0>(key) != rbsim::ack_t::KIND_COMMAND || queue.empty()) continue;
      return Error{"step " + std::to_string(recorded->step) + ": the log is at world revision " +
                   std::to_string(recorded->world_revision) + ", the replay at " +
                   std::to_string(m_session.worldRevision()) + ", and the command of '" +
                   std::get<1>(key) + "' seq " + std::to_string(std::get<2>(key)) +
                   " has no ack (lost by the logger?): the session cannot be replayed"};
    }
  }
  m_report.lastStep = recorded->step;
  const auto pages = worldStatePages(m_session.world(), recorded->utime, m_session.worldRevision());
  const auto index = static_cast<std::size_t>(recorded->page);
  if (m_verify) {
    ++m_report.pagesCompared;
    if (recorded->page < 0 || index >= pages.size()) {
      m_report.difference = "step " + std::to_string(recorded->step) + ": the log has page " +
                            std::to_string(recorded->page) + " of " + std::to_string(recorded->num_pages) +
                            ", the replay's state has " + std::to_string(pages.size()) + " pages";
      return true;
    }
    m_report.difference = firstStateDifference(*recorded, pages[index]);
    if (m_report.difference) return blameLostAck(recorded->step);
  }
  if (m_output && recorded->page >= 0 && index < pages.size())
    m_output(event.channel, encode(pages[index]), event.timestamp);
  return true;
}

Expected<bool> Replay::blameLostAck(int64_t step) {
  // A bus log can lose the ack of a message that changes no world revision
  // (a wrench, a joint command): the message then waits here unanswered,
  // not applied, and the states part from the log's for that reason alone.
  // Then the log, not the simulation, is at fault.
  for (const auto& [key, queue] : m_pending->byKey) {
    if (queue.empty()) continue;
    return Error{"step " + std::to_string(step) + ": the states differ from the log (" + *m_report.difference +
                 ") while the message of '" + std::get<1>(key) + "' seq " + std::to_string(std::get<2>(key)) +
                 " on " + queue.front().channel +
                 " has no ack (lost by the logger?): the session cannot be replayed"};
  }
  // Or the log lost a message and its ack both: a gap in a client's numbers.
  if (const auto gap = seqGap())
    return Error{"step " + std::to_string(step) + ": the states differ from the log (" + *m_report.difference +
                 ") and the log holds no message or ack of '" + gap->first + "' seq " + std::to_string(gap->second) +
                 " (lost by the logger?): the session cannot be replayed"};
  return true;
}

Expected<bool> Replay::onJoints(const LogEvent& event) {
  const auto recorded = decodeWhole<rbsim::joints_t>(event.data);
  if (!recorded) return Error{"undecodable joints_t"};
  if (auto advanced = advanceTo(recorded->step, "the joints' state"); !advanced) return advanced;
  const auto pages = jointStatePages(m_session.world(), recorded->utime, m_session.worldRevision());
  const auto index = static_cast<std::size_t>(recorded->page);
  if (m_verify) {
    ++m_report.jointPagesCompared;
    if (recorded->page < 0 || index >= pages.size()) {
      m_report.difference = "step " + std::to_string(recorded->step) + ": the log has joints page " +
                            std::to_string(recorded->page) + " of " + std::to_string(recorded->num_pages) +
                            ", the replay's joints have " + std::to_string(pages.size()) + " pages";
      return true;
    }
    m_report.difference = firstJointsDifference(*recorded, pages[index]);
    if (m_report.difference) return blameLostAck(recorded->step);
  }
  if (m_output && recorded->page >= 0 && index < pages.size())
    m_output(event.channel, encode(pages[index]), event.timestamp);
  return true;
}

void Replay::emitWorld(int64_t timestamp) {
  if (!m_output) return;
  for (const auto& page :
       worldDescriptionPages(m_session.world(), timestamp, m_session.worldRevision(), &m_session.visuals()))
    m_output(m_prefix + "WORLD", encode(page), timestamp);
}

}  // namespace rbsim
