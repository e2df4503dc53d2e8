#pragma once
// The step's stages, free functions on a WorldData (world/world_data.h),
// one file per stage:
//   world_step.cpp            the step driver, free integration, the guard
//   islands.cpp               islands, waking and sleeping
//   impulse_step.cpp          the impulse model's step (contacts, impacts, solve)
//   joint_step.cpp            the joint step of jointed bodies
//   joints.cpp                joints made, changed, removed and reported
//   penalty_step.cpp          the penalty model's step
//   continuous_collision.cpp  no tunnelling for flagged fast bodies
//   collision_filtering.cpp   which pairs of bodies never collide
//   snapshot.cpp              the world as bytes and back
//   ray_queries.cpp           ray casts between steps (query/ray_scene.h)
// World (world.cpp) forwards its public functions to them.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "physics/world/world_data.h"

namespace rbsim {

class ByteReader;
class ByteWriter;
class VelocityProjection;
struct BodyContact;

// --- world_step.cpp
// Advances the world by settings.dt (World::step says what happens).
void stepWorld(WorldData& world);
// Integrates the awake dynamic bodies not marked in `skip` (all when it is
// empty) over h with the world's integrator, loads applied; judges each for
// the guard as it goes (world.judged).
void integrateFree(WorldData& world, double h, const std::vector<char>& skip);

// --- islands.cpp
// Per dense index: the root of the island (bodies joined by contacts or
// joints between dynamic bodies) it belongs to.
std::vector<int> findIslands(const WorldData& world, const std::vector<BodyContact>& contacts);
// A sleeping body wakes when its island holds an awake or a pushed body.
void wakeIslands(WorldData& world, const std::vector<int>& islandOf);
// Puts to sleep the islands whose bodies all stayed below the sleep
// velocities, unpushed, for the sleep time.
void updateSleep(WorldData& world, const std::vector<int>& islandOf);

// --- impulse_step.cpp
// Collision detection of the bodies as they are now, on the step's threads.
void findContacts(WorldData& world);
// The impulse model's step, in the order it runs: islands → wake →
// integrate velocities → impacts → solve → integrate positions → sleep.
void stepImpulse(WorldData& world);
// The contacts the solver takes this step and the bodies it moves.
struct ContactStep {
  const std::vector<BodyContact>* contacts = nullptr;  // the detector's, or `own`
  std::vector<BodyContact> own;  // when some contacts sleep, or impacts moved a manifold
  std::vector<char> inContact;   // per dense index: in one of `contacts`
  std::vector<char> solving;     // in contact and awake: the solver moves it
  std::vector<char> fast;        // solving, and fast enough to collide (loadSolverBodies)
  std::vector<char> jointed;     // per dense index: moved by its joints (empty: no joints)
  bool anyFast = false;
  // Per dense index: the time of impact (s into the step) of the body's
  // first collision this step, or < 0 for none; empty when nothing collides.
  std::vector<double> impactTime;
};

// --- joint_step.cpp
// Per dense index: 1 for an awake dynamic body with an enforced joint
// (empty when there is none): the joint step moves it instead of the free
// integration and the contact path.
// (Kept in world.jointScratch, as the joint step's other lists: valid
// until the next call.)
const std::vector<char>& findJointedBodies(WorldData& world);
// Per dense index: 1 for a body that an actuator still moves (a motor with
// a target rate, a drive whose joint still moves), which must not fall
// asleep however slowly it goes; empty when no joint acts so.
const std::vector<char>& findActuatedBodies(WorldData& world);
// Puts every jointed body of an island that touches something into
// step.solving (the contact path's kick and solve) and returns the joints'
// velocity rows for the contact solve (null when no such island), which
// the world keeps (world.jointScratch) until the next step makes them again.
const VelocityProjection* addJointedIslandsInContact(WorldData& world, ContactStep& step,
                                                     const std::vector<char>& jointed,
                                                     const std::vector<int>& islandOf);
// For the jointed islands that addJointedIslandsInContact put into the
// contact solve: their axes' motors, drives, damping and friction and the
// joints' direct efforts over the whole step h, into world.solverBodies'
// velocities (after the forces' kick), so that the contacts answer them;
// stepJointedBodies reports them and leaves them out.
void actuateJointedIslandsInContact(WorldData& world, const ContactStep& step, const std::vector<char>& jointed,
                                    double h);
// The joint step of the jointed bodies over h (joint/joint_solver.h). An
// island (`islandOf`) that touches nothing takes RATTLE: half kick, drift
// and projection, half kick, velocity projection. An island in contact
// takes the contact path's semi-implicit step around the same projection:
// the whole kick and the contact impulses of world.solverBodies (for the
// `solving` bodies) before the drift, and no kick after it, so that a body
// resting on the ground leaves the step at rest.
void stepJointedBodies(WorldData& world, const std::vector<char>& jointed, const std::vector<char>& solving,
                       const std::vector<int>& islandOf, double h);

// --- joints.cpp
// Where a joint's side is: the body's pose.
JointSidePose jointSidePose(const Body& body);
bool jointIsEnforced(const WorldData& world, const JointConstraint& joint);
JointId findJointByName(const WorldData& world, std::string_view name);  // null id when absent
JointState jointStateAt(const WorldData& world, int denseIndex);
// Each joint's gravityFeedForward for the step: the effort that holds what
// it carries against gravity, for an enabled drive with gravity
// compensation, else 0.
void computeGravityFeedForward(WorldData& world);
// A follower's leader (def.mimic.leader, by name) into follower.mimicLeader:
// an existing revolute or prismatic joint.
Expected<bool> resolveMimicLeader(const WorldData& world, JointConstraint& follower);
// The dense index of a follower's leader, -1 when it has none or the
// leader is not enforced (a frozen body): the coupling is then not held.
int enforcedLeaderOf(const WorldData& world, const JointConstraint& follower);
// Removes the joints of a body (about to be removed or frozen); returns
// their names, in creation order.
std::vector<std::string> removeJointsOf(WorldData& world, BodyId body);
Expected<JointId> createJoint(WorldData& world, const JointDef& def);
Expected<bool> removeJoint(WorldData& world, JointId id);
Expected<bool> setJointMotor(WorldData& world, JointId id, const JointMotor& motor);
Expected<bool> setJointDrive(WorldData& world, JointId id, const JointDrive& drive);
Expected<bool> setJointEffort(WorldData& world, JointId id, double effort);

// --- penalty_step.cpp
void stepPenalty(WorldData& world);

// --- collision_filtering.cpp
// The pairs the broad phase leaves out now (DetectionStep::excludedPairs):
// world.excludedPairs and the pairs of bodies a joint joins unless it has
// collideConnected, as serialPairKey keys, ascending (gathered in
// world.pairsLeftOut when joints add some). A function of the bodies'
// serials, the joints and the exclusions, never of the past.
std::span<const uint64_t> pairsLeftOut(WorldData& world);
// Whether the filters (groups and masks, joints, exclusions) let the bodies
// at these dense indices collide.
bool filtersAllowPair(const WorldData& world, std::size_t a, std::size_t b);
// Adds (collide false) or drops the exclusion of the pair of two distinct
// valid bodies.
void setPairExcluded(WorldData& world, BodyId a, BodyId b, bool excluded);
// Drops the exclusions of a body about to be removed.
void dropExclusionsOf(WorldData& world, int32_t serial);

// --- continuous_collision.cpp
// Continuous collision for bodies flagged `continuousCollision`: a body
// whose motion over the step (from `starts`) would pass through another
// body is stopped at its time of impact, velocity kept, so the next step's
// contact stops it (no tunnelling through thin geometry).
void applyContinuousCollision(WorldData& world, const std::vector<RigidState>& starts);

// --- snapshot.cpp (the format is described there)
Expected<bool> writeSnapshot(const WorldData& world, ByteWriter& out);
// Reads a snapshot's magic, version and recorded settings, which must be
// `settings`; then readSnapshotContents reads the rest into a new world made
// with them. Errors name the field and byte offset.
Expected<bool> readSnapshotHeader(ByteReader& in, const WorldSettings& settings);
Expected<bool> readSnapshotContents(WorldData& world, ByteReader& in);

}  // namespace rbsim
