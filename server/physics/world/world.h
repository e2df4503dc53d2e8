#pragma once
// The world: owns the bodies and steps them by a fixed dt.
//
// Determinism: the same sequence of calls gives bit-identical states. Bodies
// are stepped in creation order (kept across removals), no unordered
// container decides an order, and no clock or random source is read here.

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "physics/body/body.h"
#include "physics/body/body_def.h"
#include "physics/body/integrator.h"
#include "physics/common/deep_copy_ptr.h"
#include "physics/common/expected.h"
#include "physics/solver/contact_solver.h"
#include "physics/world/body_id.h"
#include "physics/world/state_guard.h"
#include "physics/world/world_settings.h"

namespace rbsim {

class CollisionDetector;

class World {
 public:
  explicit World(const WorldSettings& settings = {});
  // Copies are independent worlds (the collision caches are copied too).
  World(const World& other);
  World(World&& other) noexcept;
  World& operator=(const World& other);
  World& operator=(World&& other) noexcept;
  ~World();

  // Builds a whole world; the first bad body stops it with its error.
  static Expected<World> fromDef(const WorldDef& def);

  // Computes the mass properties from the shape (mass or density), puts the
  // body frame at the centre of mass along the principal axes and places it
  // so that the shape lands at def.position / def.orientation. Errors: empty
  // or duplicate name, non-positive or non-finite mass, density or size, a
  // plane on a dynamic body, a mesh that is missing, a compound without
  // parts or with a bad part (named by its index).
  Expected<BodyId> createBody(const BodyDef& def);
  bool removeBody(BodyId id);  // false for a null or stale id

  BodyId findBody(std::string_view name) const;  // null id when absent
  bool isValid(BodyId id) const;
  const Body& body(BodyId id) const;  // asserts isValid
  Body& body(BodyId id);
  BodyId idOf(int denseIndex) const { return m_denseIds[static_cast<size_t>(denseIndex)]; }

  // Bodies in creation order; the vector's index is a body's dense index,
  // which changes when an earlier body is removed (the BodyId does not).
  const std::vector<Body>& bodies() const { return m_bodies; }
  int bodyCount() const { return static_cast<int>(m_bodies.size()); }

  // Advances the world by dt: gravity, damping and the external loads given
  // since the last step (then cleared), and contact as settings().contact
  // says. Bodies that touch nothing are integrated with the world's
  // integrator; with the impulse model, bodies in contact take the solver's
  // semi-implicit Euler step (velocities, contact impulses, then positions),
  // and colliding bodies free flight to their time of impact, the impulses
  // there, and free flight over the rest of the step (world/impacts.h).
  // Then the numerical guard checks every awake dynamic body and freezes
  // those whose state went non-finite or too fast (see state_guard.h).
  void step();

  // Bodies frozen during the last step, in body order (empty most of the time).
  const std::vector<FreezeEvent>& freezeEvents() const { return m_freezeEvents; }
  int frozenBodyCount() const { return m_frozenBodies; }
  // Freezes a dynamic body at its last good pose now (for tests and for
  // restoring a saved world); false for a null, stale, static or already
  // frozen body. Not reported in freezeEvents().
  bool freezeBody(BodyId id, FreezeReason reason = FreezeReason::Requested);
  void setStateLimits(const StateLimits& limits) { m_settings.limits = limits; }

  // The contacts of the last step (solved impulses included), sorted by
  // (serial A, serial B, piece A, piece B).
  const std::vector<SolvedManifold>& contacts() const { return m_contacts; }
  int contactPointCount() const;
  // Bodies asleep (at rest in an island that stopped being integrated).
  int sleepingBodyCount() const;
  void wakeUp(BodyId id);

  // Body serials are never reused within a world's life. A world reset to a
  // copy of its initial state continues after the serials it handed out.
  int32_t lastSerial() const { return m_lastSerial; }
  void continueSerialsAfter(int32_t serial) { m_lastSerial = std::max(m_lastSerial, serial); }

  const WorldSettings& settings() const { return m_settings; }
  void setGravity(const Vec3& gravity) { m_settings.gravity = gravity; }
  void setIntegrator(IntegratorKind kind) { m_settings.integrator = kind; }
  int64_t stepCount() const { return m_stepCount; }
  double time() const { return static_cast<double>(m_stepCount) * m_settings.dt; }  // s

  // Total linear and angular momentum (about the world origin) and kinetic
  // energy of the dynamic bodies.
  Vec3 totalLinearMomentum() const;
  Vec3 totalAngularMomentum() const;
  double totalKineticEnergy() const;

  // FNV-1a over the bit patterns of every body's (x, q, P, L) and the step
  // count: equal hashes mean bit-identical states.
  uint64_t stateHash() const;

 private:
  // Checkpoints (world_snapshot.h) save and rebuild the private state exactly.
  friend class WorldSnapshot;

  struct Slot {
    uint32_t generation = 0;
    int32_t denseIndex = -1;  // -1: free
  };

  // Integrates the awake dynamic bodies not marked in `skip` (all when it is
  // empty) over h with the world's integrator, loads applied; judges each for
  // the guard as it goes (m_judged).
  void integrateFree(double h, const std::vector<char>& skip);
  // The numerical guard, once per step after everything else has moved.
  void guardStates();
  // Puts a frozen body back at its last good pose with zero momenta, whatever
  // a contact path did to it during the step.
  static void holdFrozen(Body& body);
  // Gravity and the body's external load, for the integrator; notes that a
  // load was seen, so that clearLoads() has something to do.
  ForceInputs forcesOn(const Body& body);
  // External loads act for one step: cleared here, once, at its end.
  void clearLoads();
  void findContacts();

  // The impulse model's step (world_impulse.cpp), in the order it runs:
  // islands → wake → integrate velocities → impacts → solve → integrate
  // positions → sleep.
  void stepImpulse();
  // Per dense index: the root of the island (bodies joined by contacts
  // between dynamic bodies) it belongs to.
  std::vector<int> findIslands(const std::vector<BodyContact>& contacts) const;
  // A sleeping body wakes when its island holds an awake or a pushed body.
  void wakeIslands(const std::vector<int>& islandOf);
  // Puts to sleep the islands whose bodies all stayed below the sleep
  // velocities, unpushed, for the sleep time.
  void updateSleep(const std::vector<int>& islandOf);
  // The contacts the solver takes this step and the bodies it moves.
  struct ContactStep {
    const std::vector<BodyContact>* contacts = nullptr;  // the detector's, or `own`
    std::vector<BodyContact> own;  // when some contacts sleep, or impacts moved a manifold
    std::vector<char> inContact;   // per dense index: in one of `contacts`
    std::vector<char> solving;     // in contact and awake: the solver moves it
    // Per dense index: the time of impact (s into the step) of the body's
    // first collision this step, or < 0 for none; empty when nothing collides.
    std::vector<double> impactTime;
  };
  ContactStep selectContacts(const std::vector<BodyContact>& detected) const;
  // The solver's bodies: velocities after the forces of h (semi-implicit Euler's first half).
  void loadSolverBodies(const std::vector<char>& solving, double h);
  // Colliding contacts (world/impacts.h): each is moved to its time of
  // impact, with the manifold there, and its bodies' solver data with it.
  void findImpacts(ContactStep& step);
  void solveContacts(const std::vector<BodyContact>& active, const ContactSolverSettings& settings,
                     double h, std::vector<SolvedManifold>& solved);
  // Per body: how many contacts away from a static body (shock propagation).
  std::vector<int> contactLevels(const std::vector<BodyContact>& active) const;
  // Momenta from the solved velocities and positions over h: semi-implicit
  // Euler's second half, with the split-impulse pseudo-velocities; free
  // flight over the rest of the step after a collision; the world's
  // integrator for a body that no impulse reached.
  void integrateSolvedBodies(const ContactStep& step, const std::vector<SolvedManifold>& solved, double h);
  // Keeps, in key order, the last results of contacts between sleeping bodies.
  void keepSleepingContacts(const std::vector<BodyContact>& detected,
                            std::vector<SolvedManifold>& solved) const;

  void stepPenalty();
  // Continuous collision for bodies flagged `continuousCollision`: a body
  // whose motion over the step (from `starts`) would pass through another
  // body is stopped at its time of impact, velocity kept, so the next step's
  // contact stops it (no tunnelling through thin geometry).
  void applyContinuousCollision(const std::vector<RigidState>& starts);

  WorldSettings m_settings;
  DeepCopyPtr<CollisionDetector> m_detector;
  ContactSolver m_solver;
  std::vector<SolvedManifold> m_contacts;
  std::vector<SolverBody> m_solverBodies;  // scratch, one per body
  std::vector<Body> m_bodies;      // dense, in creation order
  std::vector<BodyId> m_denseIds;  // parallel to m_bodies
  std::vector<Slot> m_slots;
  std::vector<int32_t> m_freeSlots;  // reused lowest-first, for determinism
  // Name lookup only; never iterated, so its order cannot leak into a step.
  std::unordered_map<std::string, BodyId> m_idByName;
  int64_t m_stepCount = 0;
  int32_t m_lastSerial = 0;
  int m_collidingBodies = 0;  // bodies with collision geometry
  int m_continuousBodies = 0; // dynamic bodies flagged for continuous collision
  int m_frozenBodies = 0;
  std::vector<FreezeEvent> m_freezeEvents;  // of the last step
  bool m_loadsSeen = false;  // some body integrated this step had an external load
  // False only when the last sleep update found every body awake (and
  // nothing since could have put one to sleep): the wake pass is skipped.
  bool m_maybeAsleep = true;
  // Per dense index, during a step: 1 when the guard has nothing left to do
  // for the body (judged and passed in integrateFree, static, asleep).
  std::vector<char> m_judged;
};

}  // namespace rbsim
