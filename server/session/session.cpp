#include "session/session.h"

#include <utility>

namespace rbsim {

Session::Session(World initialWorld, bool startPaused)
    : m_initialWorld(initialWorld), m_world(std::move(initialWorld)), m_paused(startPaused) {}

void Session::step() {
  const int64_t stepNumber = m_world.stepCount() + 1;
  m_jointCommands.applyForStep(m_world, stepNumber);
  m_wrenches.applyForStep(m_world, stepNumber);
  m_world.step();
  m_wrenches.finishStep(stepNumber);
}

void Session::pause() {
  m_paused = true;
  m_stepsRequested = 0;
}

void Session::resume() {
  m_paused = false;
  m_stepsRequested = 0;
}

bool Session::takeRequestedStep() {
  if (m_stepsRequested <= 0) return false;
  --m_stepsRequested;
  return true;
}

void Session::resetToInitialWorld() {
  replaceWorld(m_initialWorld, WrenchScheduler{});
}

void Session::replaceWorld(World world, WrenchScheduler wrenches) {
  const int32_t lastSerial = m_world.lastSerial();
  m_world = std::move(world);
  m_world.continueSerialsAfter(lastSerial);
  m_wrenches = std::move(wrenches);
  m_jointCommands.clearAll();
  m_stepsRequested = 0;
  ++m_worldRevision;
}

void Session::resumeFrom(World world, WrenchScheduler wrenches, int64_t worldRevision, bool paused,
                         int64_t stepsRequested, std::vector<JointCommandRequest> jointCommands) {
  replaceWorld(std::move(world), std::move(wrenches));
  for (JointCommandRequest& request : jointCommands) m_jointCommands.add(std::move(request));
  m_worldRevision = worldRevision;
  m_paused = paused;
  m_stepsRequested = stepsRequested;
}

}  // namespace rbsim
