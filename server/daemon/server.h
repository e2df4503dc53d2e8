#pragma once
// rbserver's stepping loop: one thread steps the world on a real-time
// schedule, and between steps drains LCM (wrenches, commands) and signals.
// No message is handled in the middle of a step.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>
#include <rbsim/status_t.hpp>

#include "bridge/command_handler.h"
#include "config/server_settings.h"
#include "daemon/checkpoint_writer.h"
#include "daemon/instance_guard.h"
#include "daemon/running_rate.h"
#include "daemon/lateness_histogram.h"
#include "daemon/signal_events.h"
#include "daemon/step_clock.h"
#include "persist/session_checkpoint.h"
#include "rbsim/physics/world.h"
#include "replay/event_recorder.h"
#include "session/session.h"
#include "sensors/sensor_suite.h"

namespace rbsim {

class Server {
 public:
  // `initialWorld` is what RESET returns to; mesh files of spawned bodies
  // must lie under `spawnMeshDirectory`; `visuals` is how the world
  // file's robots look (published in world_t, session/session.h);
  // `sensors` publish on <prefix>SENSOR_<name> at their rates.
  Server(ServerSettings settings, World initialWorld, std::string spawnMeshDirectory, BodyVisuals visuals = {},
         RobotPublishingMap robotPublishing = {}, std::vector<SensorDef> sensors = {});

  // Connects to LCM, subscribes, opens the record file. A bad URL or an
  // unwritable record file is an error, before any stepping.
  Expected<bool> open();

  // Continues a checkpointed session (--resume) instead of the config's
  // world; call before run().
  void resumeFrom(SessionState state);

  // Runs until SIGINT/SIGTERM or the configured duration; then publishes a
  // last status and closes the record file. Returns the process exit code.
  int run(SignalEvents& signals);

 private:
  struct Counters {
    int64_t accepted = 0;
    int64_t rejected = 0;
  };
  struct StepTimes {  // wall time of World::step, over the current status window
    double sum = 0.0;
    double worst = 0.0;
    int64_t count = 0;
  };

  std::string channel(const char* suffix) const { return m_settings.channelPrefix + suffix; }
  bool shouldStep() const;
  bool durationReached() const;
  void stepOnce();
  void drainMessages();
  void checkpointIfDue();

  // A wrench or command: recorded, handed to the command handler, answered.
  void onInput(const lcm::ReceiveBuffer* buffer, const std::string& channelName);
  // Every status on our prefix (ours too): another instance's is logged.
  void onStatus(const lcm::ReceiveBuffer* buffer, const std::string& channelName,
                const rbsim::status_t* status);
  void acknowledge(rbsim::ack_t ack);

  // The world's state and joints, then (withRobots) every robot's state.
  void publishState(bool withRobots = true);
  // Robot states after a step: those published with the world state when
  // it went out (worldStatePublished), those at their own rate when due,
  // and all after the last step a STEP or robot_command_t asked for.
  void publishRobotStatesAfterStep(bool worldStatePublished, bool lastRequested);
  void publishRobotState(const std::string& robot, bool dynamics);
  void publishStatus(Nanoseconds now);
  void publishWorld();
  void publishContacts();
  // The sensors due after the step just taken.
  void publishSensors();
  template <class Message>
  void publish(const std::string& channelName, const Message& message);
  void record(const std::string& channelName, const void* data, std::size_t size, int64_t utime);

  const World& world() const { return m_session.world(); }

  ServerSettings m_settings;
  Session m_session;
  CommandHandler m_commands;
  std::unique_ptr<lcm::LCM> m_lcm;
  EventRecorder m_recorder;
  StepClock m_clock;
  CheckpointWriter m_checkpoints;
  int64_t m_checkpointEverySteps = 0;  // 0: no periodic checkpoints

  int64_t m_stateEverySteps = 1;
  int64_t m_contactsEverySteps = 0;  // 0: not published
  SensorSuite m_sensors;
  std::vector<SensorReading> m_sensorReadings;  // reused every step
  std::vector<std::string> m_sensorChannels;    // by sensor, in the suite's order
  Counters m_counters;
  StepTimes m_stepTimes;
  Nanoseconds m_lastStatus = 0;
  int64_t m_stepAtLastStatus = 0;
  Nanoseconds m_lastPausedStatePublish = 0;
  bool m_stopRequested = false;
  int64_t m_controlVersion = 0;   // bumped by commands that change the pace
  LatenessHistogram m_lateness;   // paced steps only
  double m_worstStepEver = 0.0;   // s
  std::vector<uint8_t> m_encodeBuffer;
  InstanceWatch m_instances{makeInstanceId()};
  RunningRate m_runningRate;  // for the shutdown summary
};

}  // namespace rbsim
