// Continuous collision for fast bodies flagged for it: no tunnelling.
#include <algorithm>
#include <utility>

#include "physics/body/body.h"
#include "physics/collision/broad_phase.h"
#include "physics/collision/collision_detector.h"
#include "physics/collision/time_of_impact.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

namespace rbsim {

void applyContinuousCollision(WorldData& world, const std::vector<RigidState>& starts) {
  const std::size_t n = world.bodies.size();
  // Swept boxes: the collider's box at the start and at the end of the step.
  const auto sweptBox = [&](std::size_t i) {
    const Body& body = world.bodies[i];
    const Aabb bounds = body.description().collider->bounds;
    const Aabb atStart =
        transformedAabb(bounds, Transform::fromPose(starts[i].position, starts[i].orientation));
    const Aabb atEnd = transformedAabb(bounds, Transform{body.rotation(), body.state().position});
    return atStart.merged(atEnd).fattened(world.settings.contact.detection.margin);
  };
  // Pairs the step's contacts already held (within the margin, or the
  // reach of a fast body, at its start) were answered by the contact model:
  // stopping them again here would hold a resting body in place while its
  // velocity grows. Continuous collision is for the pairs those missed.
  std::vector<std::pair<int32_t, int32_t>> inContact;
  if (world.detector) {
    inContact.reserve(world.detector->contacts().size());
    for (const BodyContact& c : world.detector->contacts())
      inContact.emplace_back(world.bodies[static_cast<std::size_t>(c.bodyA)].serial(),
                             world.bodies[static_cast<std::size_t>(c.bodyB)].serial());
  }
  // Pairs the collision filters rule out never collide, swept or not.
  const std::span<const uint64_t> leftOut = pairsLeftOut(world);
  const auto filteredOut = [&](const Body& a, const Body& b) {
    return !a.description().collisionFilter.allows(b.description().collisionFilter) ||
           std::binary_search(leftOut.begin(), leftOut.end(), serialPairKey(a.serial(), b.serial()));
  };
  const auto touched = [&](const Body& a, const Body& b) {
    // By value: minmax of two values returns references to them.
    const int32_t low = std::min(a.serial(), b.serial());
    const int32_t high = std::max(a.serial(), b.serial());
    return std::binary_search(inContact.begin(), inContact.end(), std::make_pair(low, high));
  };
  for (std::size_t i = 0; i < n; ++i) {
    Body& body = world.bodies[i];
    if (!body.description().continuousCollision || body.isStatic() || body.isSleeping() ||
        body.isFrozen() || !body.description().collider)
      continue;
    const Aabb sweptI = sweptBox(i);
    Body startI = body;
    startI.setState(starts[i]);
    double earliest = 1.0;
    for (std::size_t j = 0; j < n; ++j) {
      // A frozen body is out of the simulation: nothing collides with it.
      if (j == i || !world.bodies[j].description().collider || world.bodies[j].isFrozen()) continue;
      if (touched(body, world.bodies[j]) || filteredOut(body, world.bodies[j])) continue;
      const Collider& other = *world.bodies[j].description().collider;
      if (!other.plane && !sweptI.overlaps(sweptBox(j))) continue;
      Body startJ = world.bodies[j];
      startJ.setState(starts[j]);
      const TimeOfImpact impact =
          continuousTimeOfImpact(startI, body.state(), startJ, world.bodies[j].state());
      if (impact.status == ImpactStatus::Hit && impact.fraction < earliest)
        earliest = impact.fraction;
    }
    if (earliest < 1.0) {
      // Back to the pose at the time of impact; the momenta stay, so the
      // contact found there next step takes the approach out.
      const Transform pose = SweptMotion::between(starts[i], body.state()).poseAt(earliest);
      RigidState state = body.state();
      state.position = pose.translation;
      state.orientation = Quaternion::fromRotationMatrix(pose.rotation);
      body.moveTo(state);
    }
  }
}

}  // namespace rbsim
