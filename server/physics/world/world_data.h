#pragma once
// What a World is: its bodies, their loads, its joints, the solvers and
// their caches, the step's scratch and the settings, in one struct. World
// (rbsim/physics/world.h) is a handle that holds one of these; the step's
// stages are free functions that take it (world/step_stages.h), one file per
// stage, so the data a stage reads and writes is in its arguments.
//
// Copying a WorldData copies everything (the collision and warm-start caches
// too) except the task pool, which a copy makes anew when it first steps.

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "physics/body/body.h"
#include "physics/body/external_load.h"
#include "physics/common/deep_copy_ptr.h"
#include "physics/joint/joint_constraint.h"
#include "physics/joint/joint_solver.h"
#include "physics/world/joint_step_scratch.h"
#include "physics/parallel/task_pool.h"
#include "physics/query/ray_scene.h"
#include "physics/solver/contact_solver.h"
#include "physics/solver/soft_step_solver.h"
#include "rbsim/physics/world.h"

namespace rbsim {

class CollisionDetector;
class JointSolver;
struct FlyingBody;
struct ForceInputs;

// The generation and dense index behind an id's slot (ids.h).
struct IdSlot {
  uint32_t generation = 0;
  int32_t denseIndex = -1;  // -1: free
};

// The largest squared speeds one chunk of a parallel loop over the bodies saw.
struct SpeedBound {
  double squaredSpeed = 0.0;
  double squaredSpin = 0.0;
  void note(double speed2, double spin2) {
    squaredSpeed = std::max(squaredSpeed, speed2);
    squaredSpin = std::max(squaredSpin, spin2);
  }
};

struct WorldData {
  explicit WorldData(const WorldSettings& worldSettings);
  WorldData(const WorldData& other);
  WorldData& operator=(const WorldData& other);
  ~WorldData();

  WorldSettings settings;
  // The step's threads (settings.threads): the pool is made at the first
  // step, a copy of the world makes its own.
  OwnTaskPool pool;
  DeepCopyPtr<CollisionDetector> detector;
  uint32_t tag;  // stamped on the ids it hands out (ids.h); copies keep it
  DeepCopyPtr<ContactSolver> solver;
  DeepCopyPtr<SoftStepSolver> softSolver;  // when settings.contact.solver.kind is SoftStep
  // The joint step's solver: it keeps the symbolic factorisation of the
  // joints' system while their pattern stays (joint/joint_solver.h).
  DeepCopyPtr<JointSolver> jointSolver;
  std::vector<SolvedManifold> contacts;  // of the last step, sorted by key
  std::vector<SolverBody> solverBodies;  // scratch, one per body
  // Scratch of a step, by joint: what the axes of jointed islands in
  // contact did before the contact solve (actuateJointedIslandsInContact),
  // reported with the joint step's impulses (empty: nothing).
  std::vector<JointLinkResult> contactActuation;
  // The joint step's lists, kept so that a steady step allocates nothing.
  JointStepScratch jointScratch;
  std::vector<Body> bodies;              // dense, in creation order
  // Parallel to `bodies`: the external loads for the coming step, kept here
  // rather than in the bodies (most bodies are pushed by nothing, and the
  // stepping loops read every body).
  std::vector<ExternalLoad> loads;
  std::vector<BodyId> denseIds;  // parallel to `bodies`
  std::vector<IdSlot> slots;
  std::vector<int32_t> freeSlots;  // reused lowest-first, for determinism
  // Joints, dense in creation order, with their ids and slots (as bodies).
  std::vector<JointConstraint> joints;
  std::vector<JointId> jointIds;
  std::vector<IdSlot> jointSlots;
  std::vector<int32_t> freeJointSlots;
  // Pairs of bodies that never collide (World::setPairCollision), as
  // serialPairKey keys (collision/broad_phase.h), ascending.
  std::vector<uint64_t> excludedPairs;
  // Scratch of the step: those and the pairs joints join, for the broad
  // phase (collision_filtering.cpp).
  std::vector<uint64_t> pairsLeftOut;
  // Name lookup only; never iterated, so its order cannot leak into a step.
  std::unordered_map<std::string, BodyId> idByName;
  int64_t stepCount = 0;
  // Bumped by every change of a body's pose or of the set of bodies that
  // rays may hit: each step, createBody, removeBody, setBodyState and
  // freezeBody. The ray-cast scene is refreshed when it has changed.
  uint64_t revision = 0;
  // The bodies as ray casts see them, refreshed lazily (query/ray_scene.h);
  // a copy starts empty.
  RayScene rayScene;
  int32_t lastSerial = 0;
  int collidingBodies = 0;   // bodies with collision geometry
  int continuousBodies = 0;  // dynamic bodies flagged for continuous collision
  int frozenBodies = 0;
  std::vector<FreezeEvent> freezeEvents;  // of the last step
  bool loadsSeen = false;  // some body may hold an external load (set where loads are added)
  // Bounds on every awake body's squared speeds after the last step, for
  // the detector (collision/collision_detector.h: DetectionStep); negative
  // when a change from outside (a new body, new velocities) made them
  // unknown. The step's integrations gather the next ones.
  double maxSquaredSpeed = -1.0;  // m²/s²
  double maxSquaredSpin = -1.0;   // 1/s²
  double stepSquaredSpeed = 0.0;
  double stepSquaredSpin = 0.0;
  std::vector<SpeedBound> chunkSpeeds;  // scratch of forEachBody
  // False only when the last sleep update found every body awake (and
  // nothing since could have put one to sleep): the wake pass is skipped.
  bool maybeAsleep = true;
  // Per dense index, during a step: 1 when the guard has nothing left to do
  // for the body (judged and passed in integrateFree, static, asleep).
  std::vector<char> judged;
};

// Why `id` names no body of this world ("" when it does). The message is
// made only for an id that fails.
std::string invalidIdReason(const WorldData& world, BodyId id);
// The same for joint ids.
std::string invalidJointReason(const WorldData& world, JointId id);
// The dense index of a valid id, and its body.
inline std::size_t denseIndexOf(const WorldData& world, BodyId id) {
  return static_cast<std::size_t>(world.slots[static_cast<std::size_t>(id.index - 1)].denseIndex);
}
inline Body& bodyRef(WorldData& world, BodyId id) { return world.bodies[denseIndexOf(world, id)]; }
inline const Body& bodyRef(const WorldData& world, BodyId id) { return world.bodies[denseIndexOf(world, id)]; }
BodyId findBodyByName(const WorldData& world, std::string_view name);  // null id when absent

// Gravity and the body's external load, for the integrator. Reads only,
// so the step's threads may ask for different bodies at once.
ForceInputs forcesOn(const WorldData& world, std::size_t denseIndex);
// A body with its load, for free flight to a time of impact.
FlyingBody flying(const WorldData& world, std::size_t denseIndex);

inline TaskPool& taskPool(WorldData& world) { return world.pool.get(world.settings.threads); }

inline void noteSpeeds(WorldData& world, double squaredSpeed, double squaredSpin) {
  world.stepSquaredSpeed = std::max(world.stepSquaredSpeed, squaredSpeed);
  world.stepSquaredSpin = std::max(world.stepSquaredSpin, squaredSpin);
}

// Calls visit(i, bound) for every dense index i on the step's threads, in
// chunks of a fixed size; visit may change body i and its own entries of
// per-body arrays, nothing else, and notes the body's speeds in `bound`
// (its chunk's). The chunks' bounds then go to noteSpeeds in chunk order:
// a maximum is exact, so the result is the serial loop's.
template <class Visit>
void forEachBody(WorldData& world, Visit&& visit) {
  constexpr std::size_t kBodiesPerChunk = 128;
  const std::size_t chunks = chunkCount(world.bodies.size(), kBodiesPerChunk);
  world.chunkSpeeds.assign(chunks, SpeedBound{});
  forEachChunk(taskPool(world), world.bodies.size(), kBodiesPerChunk,
               [&](std::size_t chunk, std::size_t begin, std::size_t end) {
                 // Kept on this thread's stack and stored once: the chunks'
                 // bounds share cache lines, which two threads writing at
                 // every body would pass between their cores.
                 SpeedBound bound;
                 for (std::size_t i = begin; i < end; ++i) visit(i, bound);
                 world.chunkSpeeds[chunk] = bound;
               });
  for (const SpeedBound& bound : world.chunkSpeeds) noteSpeeds(world, bound.squaredSpeed, bound.squaredSpin);
}

}  // namespace rbsim
