// Islands and sleeping: bodies joined by contacts or joints move as one island, wake
// together and fall asleep together.
#include <algorithm>
#include <limits>
#include <numeric>

#include "physics/body/body.h"
#include "physics/body/external_load.h"
#include "physics/collision/body_contact.h"
#include "physics/joint/joint_constraint.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

namespace rbsim {

namespace {

// Union–find over dense body indices.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t count) : m_parent(count) {
    std::iota(m_parent.begin(), m_parent.end(), 0);
  }
  int find(int i) {
    while (parent(i) != i) {
      parent(i) = parent(parent(i));  // path halving
      i = parent(i);
    }
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent(std::max(a, b)) = std::min(a, b);  // deterministic root: the lowest index
  }

 private:
  int& parent(int i) { return m_parent[static_cast<std::size_t>(i)]; }
  std::vector<int> m_parent;
};

}  // namespace

std::vector<int> findIslands(const WorldData& world, const std::vector<BodyContact>& contacts) {
  const std::size_t n = world.bodies.size();
  std::vector<int> islandOf(n);
  if (contacts.empty() && world.joints.empty()) {  // every body its own island
    std::iota(islandOf.begin(), islandOf.end(), 0);
    return islandOf;
  }
  // A static body joins nothing: two piles on one floor are two islands.
  DisjointSets islands(n);
  for (const BodyContact& c : contacts) {
    if (!world.bodies[static_cast<std::size_t>(c.bodyA)].isStatic() &&
        !world.bodies[static_cast<std::size_t>(c.bodyB)].isStatic())
      islands.unite(c.bodyA, c.bodyB);
  }
  for (const JointConstraint& joint : world.joints) {
    const BodyId a = joint.def.bodyA, b = joint.def.bodyB;
    if (a.isNull() || b.isNull()) continue;
    const std::size_t ia = denseIndexOf(world, a), ib = denseIndexOf(world, b);
    if (!world.bodies[ia].isStatic() && !world.bodies[ib].isStatic())
      islands.unite(static_cast<int>(ia), static_cast<int>(ib));
  }
  // A mimic coupling joins the follower's bodies to the leader's.
  for (const JointConstraint& follower : world.joints) {
    if (!follower.def.mimic.enabled || !invalidJointReason(world, follower.mimicLeader).empty()) continue;
    const JointConstraint& leader = world.joints[static_cast<std::size_t>(
        world.jointSlots[static_cast<std::size_t>(follower.mimicLeader.index - 1)].denseIndex)];
    int first = -1;
    for (const BodyId id : {follower.def.bodyA, follower.def.bodyB, leader.def.bodyA, leader.def.bodyB}) {
      if (id.isNull()) continue;
      const std::size_t i = denseIndexOf(world, id);
      if (world.bodies[i].isStatic()) continue;
      if (first < 0) first = static_cast<int>(i);
      else islands.unite(first, static_cast<int>(i));
    }
  }
  for (std::size_t i = 0; i < n; ++i) islandOf[i] = islands.find(static_cast<int>(i));
  return islandOf;
}

void wakeIslands(WorldData& world, const std::vector<int>& islandOf) {
  if (!world.maybeAsleep) return;
  const bool sleeping = world.settings.contact.sleeping;
  const std::size_t n = world.bodies.size();
  std::vector<char> islandAwake;
  for (std::size_t i = 0; i < n; ++i) {
    // Only a sleeping body has anything to wake; most steps find none.
    if (!world.bodies[i].isSleeping()) continue;
    if (islandAwake.empty()) {
      // An island is awake when it holds an awake or a pushed body (a push
      // wakes it before the step in which the push first acts). Static
      // bodies are islands of their own and never asleep: harmless here.
      islandAwake.assign(n, 0);
      for (std::size_t k = 0; k < n; ++k) {
        const Body& body = world.bodies[k];
        if (!body.isSleeping() || world.loads[k].active || !sleeping)
          islandAwake[static_cast<std::size_t>(islandOf[k])] = 1;
      }
    }
    Body& body = world.bodies[i];
    if (islandAwake[static_cast<std::size_t>(islandOf[i])]) body.wake();
  }
}

void updateSleep(WorldData& world, const std::vector<int>& islandOf) {
  const double dt = world.settings.dt;
  const ContactConfig& config = world.settings.contact;
  const std::size_t n = world.bodies.size();
  // An island's rest time is its least restful body's. A body pushed during
  // this step is not at rest, however slowly it moves yet: it must not fall
  // asleep under the force, and falling asleep must not throw away the
  // momentum the push gave it.
  std::vector<double> islandRest(n, std::numeric_limits<double>::infinity());
  static const std::vector<char> kNone;
  const std::vector<char>& actuated = world.joints.empty() ? kNone : findActuatedBodies(world);
  for (std::size_t i = 0; i < n; ++i) {
    Body& body = world.bodies[i];
    if (body.isStatic() || body.isSleeping()) continue;
    const bool still = !world.loads[i].active && (actuated.empty() || !actuated[i]) &&
                       body.linearVelocity().squaredNorm() <
                           config.sleepLinearVelocity * config.sleepLinearVelocity &&
                       body.angularVelocity().squaredNorm() <
                           config.sleepAngularVelocity * config.sleepAngularVelocity;
    body.setRestTime(still ? body.restTime() + dt : 0.0);
    double& rest = islandRest[static_cast<std::size_t>(islandOf[i])];
    rest = std::min(rest, body.restTime());
  }
  bool anyAsleep = false;
  for (std::size_t i = 0; i < n; ++i) {
    Body& body = world.bodies[i];
    anyAsleep = anyAsleep || body.isSleeping();
    if (body.isStatic() || body.isSleeping()) continue;
    if (islandRest[static_cast<std::size_t>(islandOf[i])] >= config.sleepTime) {
      anyAsleep = true;
      body.setSleeping(true);
      body.setMomenta(Vec3::Zero(), Vec3::Zero());
    }
  }
  world.maybeAsleep = anyAsleep;
}

}  // namespace rbsim
