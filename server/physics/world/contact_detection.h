#pragma once
// Collision detection of a world's current state: the world's bodies and
// settings handed to the collision layer, which does not know World.

#include "physics/collision/collision_detector.h"
#include "rbsim/physics/world.h"
#include "rbsim/physics/world_settings.h"

namespace rbsim {

// Speculative contacts belong to the impulse model: the penalty model
// pushes on overlaps only and needs none.
inline DetectionStep detectionStep(const WorldSettings& settings) {
  return {settings.dt, settings.contact.model == ContactModel::Impulse};
}

// On the calling thread.
inline void detectContacts(CollisionDetector& detector, const World& world) {
  TaskPool caller(1);
  detector.detect(world.internalBodies(), detectionStep(world.settings()), caller);
}

// With the world's bounds on its bodies' speeds (negative: unknown), on
// the pool's threads.
inline void detectContacts(CollisionDetector& detector, const World& world, double maxSquaredSpeed,
                           double maxSquaredSpin, TaskPool& pool) {
  DetectionStep step = detectionStep(world.settings());
  step.maxSquaredSpeed = maxSquaredSpeed;
  step.maxSquaredSpin = maxSquaredSpin;
  detector.detect(world.internalBodies(), step, pool);
}

}  // namespace rbsim
