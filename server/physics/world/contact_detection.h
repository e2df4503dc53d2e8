#pragma once
// Collision detection of a world's bodies as they are now: the bodies and
// the world's settings handed to the collision layer, which knows neither
// World nor WorldData.

#include <cstdint>
#include <span>

#include "physics/body/body.h"
#include "physics/collision/collision_detector.h"
#include "physics/parallel/task_pool.h"
#include "rbsim/physics/world_settings.h"

namespace rbsim {

// Speculative contacts belong to the impulse model: the penalty model
// pushes on overlaps only and needs none.
inline DetectionStep detectionStep(const WorldSettings& settings) {
  DetectionStep step;
  step.dt = settings.dt;
  step.speculative = settings.contact.model == ContactModel::Impulse;
  return step;
}

// On the calling thread, without bounds on the bodies' speeds.
inline void detectContacts(CollisionDetector& detector, std::span<const Body> bodies, const WorldSettings& settings) {
  TaskPool caller(1);
  detector.detect(bodies, detectionStep(settings), caller);
}

// With the world's bounds on its bodies' speeds (negative: unknown) and
// the pairs it leaves out (DetectionStep::excludedPairs), on the pool's
// threads.
inline void detectContacts(CollisionDetector& detector, std::span<const Body> bodies, const WorldSettings& settings,
                           double maxSquaredSpeed, double maxSquaredSpin, std::span<const uint64_t> excludedPairs,
                           TaskPool& pool) {
  DetectionStep step = detectionStep(settings);
  step.maxSquaredSpeed = maxSquaredSpeed;
  step.maxSquaredSpin = maxSquaredSpin;
  step.excludedPairs = excludedPairs;
  detector.detect(bodies, step, pool);
}

}  // namespace rbsim
