// Which pairs of bodies never collide: the world's part of collision
// filtering (rbsim/physics/collision_filter.h). Groups and masks travel with
// the bodies' descriptions to the broad phase; the pairs left out by joints
// and by World::setPairCollision are gathered here, as one sorted list of
// keys the broad phase walks beside its own sorted pairs. Both happen before
// the narrow phase, so a filtered pair costs no contact generation at all
// (before this, joined bodies' contacts were generated and then dropped).
#include <algorithm>

#include "physics/body/body.h"
#include "physics/collision/broad_phase.h"
#include "physics/joint/joint_constraint.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

namespace rbsim {

namespace {

bool isJoinedPair(const JointDef& def) {
  return !def.collideConnected && !def.bodyA.isNull() && !def.bodyB.isNull();
}

}  // namespace

std::span<const uint64_t> pairsLeftOut(WorldData& world) {
  std::vector<uint64_t>& out = world.pairsLeftOut;
  out.clear();
  for (const JointConstraint& joint : world.joints) {
    if (!isJoinedPair(joint.def)) continue;
    out.push_back(serialPairKey(bodyRef(world, joint.def.bodyA).serial(), bodyRef(world, joint.def.bodyB).serial()));
  }
  if (out.empty()) return world.excludedPairs;
  const auto joined = static_cast<std::ptrdiff_t>(out.size());
  std::sort(out.begin(), out.end());
  out.insert(out.end(), world.excludedPairs.begin(), world.excludedPairs.end());
  std::inplace_merge(out.begin(), out.begin() + joined, out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool filtersAllowPair(const WorldData& world, std::size_t a, std::size_t b) {
  const Body& bodyA = world.bodies[a];
  const Body& bodyB = world.bodies[b];
  if (!bodyA.description().collisionFilter.allows(bodyB.description().collisionFilter)) return false;
  const uint64_t key = serialPairKey(bodyA.serial(), bodyB.serial());
  if (std::binary_search(world.excludedPairs.begin(), world.excludedPairs.end(), key)) return false;
  return std::none_of(world.joints.begin(), world.joints.end(), [&](const JointConstraint& joint) {
    return isJoinedPair(joint.def) &&
           serialPairKey(bodyRef(world, joint.def.bodyA).serial(), bodyRef(world, joint.def.bodyB).serial()) == key;
  });
}

void setPairExcluded(WorldData& world, BodyId a, BodyId b, bool excluded) {
  const uint64_t key = serialPairKey(bodyRef(world, a).serial(), bodyRef(world, b).serial());
  std::vector<uint64_t>& keys = world.excludedPairs;
  const auto at = std::lower_bound(keys.begin(), keys.end(), key);
  const bool present = at != keys.end() && *at == key;
  if (excluded && !present) keys.insert(at, key);
  if (!excluded && present) keys.erase(at);
}

void dropExclusionsOf(WorldData& world, int32_t serial) {
  const auto low = static_cast<uint32_t>(serial);
  std::erase_if(world.excludedPairs, [&](uint64_t key) {
    return static_cast<uint32_t>(key >> 32) == low || static_cast<uint32_t>(key) == low;
  });
}

}  // namespace rbsim
