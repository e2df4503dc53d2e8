#pragma once
// What a running simulation is, apart from any network or clock: the world,
// the world it started from (for RESET), the wrenches clients asked for, and
// whether it is paused. The server steps it on a real-time schedule, a
// replay steps it as fast as it can, a fuzzer pokes it with messages; all
// through the same code, so what a recorded session did can be done again.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "rbsim/physics/world.h"
#include "robot/robot_publishing.h"
#include "robot/visual.h"
#include "session/joint_command_scheduler.h"
#include "session/wrench_scheduler.h"

namespace rbsim {

class Session {
 public:
  // `initialWorld` is what RESET returns to; the session starts from it.
  explicit Session(World initialWorld, bool startPaused = false);

  const World& world() const { return m_world; }
  World& world() { return m_world; }
  const World& initialWorld() const { return m_initialWorld; }
  const WrenchScheduler& wrenches() const { return m_wrenches; }
  WrenchScheduler& wrenches() { return m_wrenches; }
  // Joint commands scheduled ahead (apply_at_step); RESET and a new world drop them.
  const JointCommandScheduler& jointCommands() const { return m_jointCommands; }
  JointCommandScheduler& jointCommands() { return m_jointCommands; }

  // One step of the world with the joint commands and wrenches due in it
  // (numbered as on the wire: the step taken from stepCount() s is step s + 1).
  void step();

  bool paused() const { return m_paused; }
  // STEP while paused: how many steps are still to be taken.
  int64_t stepsRequested() const { return m_stepsRequested; }
  void pause();
  void resume();
  void requestSteps(int64_t count) { m_stepsRequested += count; }
  // True (and one fewer pending) if the next step is one that STEP asked for.
  bool takeRequestedStep();

  // Back to the initial world. Serials handed out stay taken (body ids are
  // never reused), wrenches are dropped, the pause state is kept.
  void resetToInitialWorld();
  // Replaces world and wrenches (a checkpoint), with the same rules for serials.
  void replaceWorld(World world, WrenchScheduler wrenches);

  // Continues a checkpointed session: its world, wrenches, pause state and
  // revision (serials continue after both worlds').
  void resumeFrom(World world, WrenchScheduler wrenches, int64_t worldRevision, bool paused,
                  int64_t stepsRequested, std::vector<JointCommandRequest> jointCommands = {});

  // How bodies look (robot/visual.h), by body name: the world file's
  // robots' and those of every SPAWN since. Kept by name beside the world,
  // not in it (drawing is no physics): RESET, a checkpoint restored and
  // REMOVE leave it as it is, and a body is drawn with the visuals of its
  // name, if any; a spawn replaces those of the names it creates.
  const BodyVisuals& visuals() const { return m_visuals; }
  void setVisuals(BodyVisuals visuals) { m_visuals = std::move(visuals); }
  void addSpawnedVisuals(const std::vector<std::string>& bodyNames, BodyVisuals visuals) {
    for (const std::string& name : bodyNames) m_visuals.erase(name);
    m_visuals.merge(visuals);
  }

  // How each robot's state goes out (robot/robot_publishing.h), by robot
  // name: the world file's and the spawns' robots, changed by
  // robot_command_t. Kept beside the world as the visuals are: RESET and a
  // checkpoint leave it; a robot without an entry publishes with the world
  // state, without dynamics.
  const RobotPublishingMap& robotPublishing() const { return m_robotPublishing; }
  RobotPublishing& robotPublishing(const std::string& robot) { return m_robotPublishing[robot]; }
  void addRobotPublishing(const RobotPublishingMap& publishing) {
    for (const auto& [robot, settings] : publishing) m_robotPublishing[robot] = settings;
  }

  // world_t revision: bumped at every change of the set of bodies.
  int64_t worldRevision() const { return m_worldRevision; }
  void noteWorldChanged() { ++m_worldRevision; }

 private:
  World m_initialWorld;
  World m_world;
  WrenchScheduler m_wrenches;
  JointCommandScheduler m_jointCommands;
  bool m_paused = false;
  int64_t m_stepsRequested = 0;
  int64_t m_worldRevision = 1;
  BodyVisuals m_visuals;
  RobotPublishingMap m_robotPublishing;
};

}  // namespace rbsim
