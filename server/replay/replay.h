#pragma once
// `rbserver --replay LOG`: re-simulates a recorded session as fast as
// possible. The log is an rbserver --record file or an lcm-logger log of the
// bus. The session starts from the config's world (or the checkpoint the
// recorded server resumed from); each wrench, joint command or command the
// server accepted and that changed the world (wrenches, joint commands,
// SPAWN, REMOVE, RESET) goes through the same CommandHandler at the step the
// server handled it, and the world is stepped to every recorded state. With `verify`, every recorded state page
// is compared bit for bit with the replayed one.
//
// Where a message was handled: a --record file says so exactly (a handled_t
// after each received message). An lcm-logger log has only the acks: a
// message acts from ack.effective_step, so it was handled after step
// effective_step - 1; a wrench scheduled ahead with apply_at_step is handled
// where the replay stands (the same order, possibly a few steps early,
// which changes nothing unless it was at the edge of a limit).
//
// Messages the server rejected, and those that only pace the server (PAUSE,
// RESUME, STEP, SET_REAL_TIME_FACTOR, PUBLISH_WORLD, SAVE_CHECKPOINT), are
// skipped: they do not change the simulated states.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bridge/command_handler.h"
#include "rbsim/physics/types.h"
#include "replay/lcm_log_reader.h"
#include "sensors/sensor_suite.h"
#include "session/session.h"

namespace rbsim {

struct ReplayReport {
  int64_t eventsRead = 0;
  int64_t messagesApplied = 0;  // accepted wrenches and commands re-applied
  int64_t stepsSimulated = 0;
  int64_t pagesCompared = 0;       // world_state_t pages
  int64_t jointPagesCompared = 0;  // joints_t pages
  int64_t sensorReadingsCompared = 0;  // messages on <prefix>SENSOR_<name>
  int64_t lastStep = 0;         // of the last recorded state
  // The first difference (verify), or the first decision the replay took
  // differently from the recorded server; nullopt: identical.
  std::optional<std::string> difference;
};

class Replay {
 public:
  // Receives every message the replay produces: state and joints pages (at
  // the steps the log has them) and world descriptions (at start and at
  // every change),
  // already encoded, with the recorded event's timestamp.
  using Output = std::function<void(const std::string& channel, const std::vector<uint8_t>& data,
                                    int64_t timestamp)>;

  // `handler` must act on `session` and be configured like the recorded
  // server (channel prefix, limits), without read-only mode or rate limits:
  // the log says which messages were accepted.
  // `sensors` are the config's (the recorded server's): they read after
  // every replayed step, and each reading the log holds is compared (with
  // `verify`) and re-emitted with the recorded one's utime.
  Replay(Session& session, CommandHandler& handler, std::string channelPrefix, bool verify,
         Output output, std::vector<SensorDef> sensors = {});
  ~Replay();

  // Errors: an unreadable or corrupt log, or a log the replay cannot follow
  // (a state or a message for a step the replay has already passed, an
  // accepted message missing from the log).
  Expected<ReplayReport> run(const std::string& logPath);

 private:
  struct Input;
  Expected<bool> onInput(const LogEvent& event);
  Expected<bool> onHandled(const LogEvent& event);
  Expected<bool> onAck(const LogEvent& event);
  Expected<bool> onState(const LogEvent& event);
  Expected<bool> onJoints(const LogEvent& event);
  Expected<bool> onSensor(const LogEvent& event);
  // After a difference: an error (the log lost an ack) if a message still
  // waits for its ack, else true with the difference reported.
  Expected<bool> blameLostAck(int64_t step);
  // The first number missing from a client's messages and acks seen so far
  // (client, seq): a message the log lost with its ack.
  std::optional<std::pair<std::string, int64_t>> seqGap() const;  // compared and re-emitted as the states are
  Expected<bool> advanceTo(int64_t step, const std::string& why);
  void emitWorld(int64_t timestamp);
  // The sensors' readings after the step just replayed, encoded, by channel.
  void keepSensorReadings();

  Session& m_session;
  CommandHandler& m_handler;
  std::string m_prefix;
  bool m_verify;
  Output m_output;
  ReplayReport m_report;
  struct Pending;
  std::unique_ptr<Pending> m_pending;
  // The log's first event (its timestamp, the step the replay started at)
  // and the current event's timestamp, µs: they bound the steps a log can ask for.
  std::optional<int64_t> m_firstTimestamp;
  int64_t m_firstStep = 0;
  int64_t m_eventTimestamp = 0;
  SensorSuite m_sensors;
  std::vector<SensorReading> m_sensorReadings;
  struct ReplayedReading {
    int64_t step = -1;
    std::vector<uint8_t> bytes;  // encoded with utime 0
  };
  std::map<std::string, ReplayedReading> m_replayedReadings;  // by channel
};

}  // namespace rbsim
