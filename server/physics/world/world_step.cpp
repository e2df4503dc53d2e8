// The step driver (World::step): the contact model's step or free flight,
// continuous collision, the loads cleared, then the numerical guard. Also
// the free integration that every path uses for the bodies touching nothing.
#include <vector>

#include "physics/body/body.h"
#include "physics/body/external_load.h"
#include "physics/body/integrator.h"
#include "physics/world/state_guard.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

namespace rbsim {

namespace {

void clearLoads(WorldData& world) {
  // Every pushed body was integrated (a push wakes a sleeping one; static
  // bodies take none; frozen ones drop theirs).
  if (!world.loadsSeen) return;
  for (ExternalLoad& load : world.loads)
    if (load.active) load.clear();
  world.loadsSeen = false;
}

void guardStates(WorldData& world) {
  if (!world.freezeEvents.empty()) world.freezeEvents.clear();
  const StateLimits& limits = world.settings.limits;
  const double maxLinear2 = limits.maxLinearSpeed * limits.maxLinearSpeed;
  const double maxAngular2 = limits.maxAngularSpeed * limits.maxAngularSpeed;
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    // Most bodies were judged by integrateFree while they were in cache; a
    // byte per body is all this pass reads of them.
    if (world.judged[i]) continue;
    Body& body = world.bodies[i];
    if (body.isStatic()) continue;
    if (body.isFrozen()) {
      // Back where it froze, whatever a contact path did to it in the step.
      body.holdAtLastGoodPose();
      world.loads[i].clear();
      continue;
    }
    if (body.isSleeping()) continue;  // it has not moved since it last passed
    if (isHealthy(body.state(), body.linearVelocity(), body.angularVelocity(), maxLinear2, maxAngular2)) {
      body.keepPoseAsGood();
      continue;
    }
    const StateVerdict verdict =
        judgeState(body.state(), body.linearVelocity(), body.angularVelocity(), limits);
    if (verdict.reason == FreezeReason::None) continue;  // a pose sum that overflowed: none does
    body.setFreezeReason(verdict.reason);
    ++world.frozenBodies;
    body.holdAtLastGoodPose();
    world.loads[i].clear();
    world.freezeEvents.push_back({world.denseIds[i], body.name(), world.stepCount, verdict, {}});
  }
  // A frozen body cannot hold a joint: its joints go (the server logs them).
  for (FreezeEvent& event : world.freezeEvents) event.droppedJoints = removeJointsOf(world, event.id);
}

}  // namespace

void stepWorld(WorldData& world) {
  world.judged.assign(world.bodies.size(), 0);
  computeGravityFeedForward(world);
  const bool anyContact = world.settings.contact.enabled && world.collidingBodies > 0;
  // The impulse model's step is also where islands at rest fall asleep, so
  // a world whose bodies all collide with nothing (BodyDef::collides) takes
  // it too: its detector finds no contact, and every body flies free as in
  // the step without contact below.
  const bool impulseStep =
      world.settings.contact.enabled && world.settings.contact.model == ContactModel::Impulse && !world.bodies.empty();
  std::vector<RigidState> starts;
  if (anyContact && world.continuousBodies > 0) {
    starts.reserve(world.bodies.size());
    for (const Body& body : world.bodies) starts.push_back(body.state());
  }
  if (impulseStep) {
    world.stepSquaredSpeed = world.stepSquaredSpin = 0.0;
    stepImpulse(world);
    // Every awake body was integrated by one of the step's paths, which
    // noted its speeds; sleeping, static and frozen bodies stand still.
    world.maxSquaredSpeed = world.stepSquaredSpeed;
    world.maxSquaredSpin = world.stepSquaredSpin;
  } else if (anyContact) {
    stepPenalty(world);
  } else {
    const std::vector<char>& jointed = findJointedBodies(world);
    integrateFree(world, world.settings.dt, jointed);
    stepJointedBodies(world, jointed, {}, {}, world.settings.dt);
    world.contacts.clear();
  }
  if (!starts.empty()) applyContinuousCollision(world, starts);
  clearLoads(world);
  ++world.stepCount;
  guardStates(world);
  ++world.revision;  // the bodies moved: the ray-cast scene follows at its next query
}

ForceInputs forcesOn(const WorldData& world, std::size_t denseIndex) {
  ForceInputs inputs;
  inputs.gravity = world.settings.gravity;
  if (const ExternalLoad& load = world.loads[denseIndex]; load.active) inputs.load = &load;
  return inputs;
}

void integrateFree(WorldData& world, double h, const std::vector<char>& skip) {
  const IntegratorKind integrator = world.settings.integrator;
  const double maxLinear2 = world.settings.limits.maxLinearSpeed * world.settings.limits.maxLinearSpeed;
  const double maxAngular2 = world.settings.limits.maxAngularSpeed * world.settings.limits.maxAngularSpeed;
  // Continuous collision may still move flagged bodies after this: those are
  // judged in guardStates, after it.
  const bool laterMoves = world.continuousBodies > 0;
  forEachBody(world, [&](std::size_t i, SpeedBound& bound) {
    Body& body = world.bodies[i];
    if (body.isStatic() || body.isSleeping()) {
      world.judged[i] = 1;  // nothing to check: it does not move this step
      return;
    }
    if (body.isFrozen()) return;
    if (!skip.empty() && skip[i]) {
      // In contact: the solver moves it later in this step, and guardStates
      // judges it then, against the pose it has now.
      body.keepPoseAsGood();
      return;
    }
    const ForceInputs inputs = forcesOn(world, i);
    const RigidState next =
        integrateStep(integrator, body.state(), body.rotation(), body.dynamics(), inputs, h);
    // The guard's check, on the new state while it is at hand. A body it
    // cannot clear (or that continuous collision may still move) is judged
    // again in guardStates, and frozen there at the pose it has now.
    // For the guard and for the next step's collision detection.
    const SpeedBounds speeds = speedBounds(next, body.dynamics().inverseMass, body.dynamics().inverseInertiaBody);
    bound.note(speeds.squaredSpeed, speeds.squaredSpin);
    const bool judgedHere = speeds.squaredSpeed <= maxLinear2 && speeds.squaredSpin <= maxAngular2 &&
                            !(laterMoves && body.description().continuousCollision);
    if (!judgedHere) body.keepPoseAsGood();
    world.judged[i] = judgedHere ? 1 : 0;
    body.moveTo(next);
  });
}

}  // namespace rbsim
