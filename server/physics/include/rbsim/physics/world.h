#pragma once
// The world: owns the bodies and steps them by a fixed dt. With the headers
// beside it (ids, body_definition, body_view, shapes, world_settings,
// contacts, types) this is the physics library's public API; what lives in
// the library's layer directories is internal to it.
//
// Determinism: the same sequence of calls gives bit-identical states. Bodies
// are stepped in creation order (kept across removals), no unordered
// container decides an order, and no clock or random source is read here.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "physics/common/deep_copy_ptr.h"
#include "physics/parallel/task_pool.h"
#include "rbsim/physics/body_definition.h"
#include "rbsim/physics/body_view.h"
#include "rbsim/physics/contacts.h"
#include "rbsim/physics/ids.h"
#include "rbsim/physics/joint_definition.h"
#include "rbsim/physics/types.h"
#include "rbsim/physics/world_settings.h"

namespace rbsim {

// Internal to the library: only named here.
class Body;
class ByteReader;
class ByteWriter;
class CollisionDetector;
class ContactSolver;
struct BodyContact;
struct ExternalLoad;
struct FlyingBody;
struct ForceInputs;
struct JointConstraint;
struct JointLink;
class JointSolver;
class VelocityProjection;
struct SolverBody;

// A force and a couple on a body for the coming step. The force acts at a
// point fixed in the body: during the step (and at each RK4 stage) the point
// moves and turns with the body.
struct Wrench {
  enum class Frame {
    World,             // force, couple and point in the world frame (the point where it is now)
    WorldAtBodyPoint,  // force and couple in the world frame, the point in the body frame
    Body,              // force, couple and point in the body frame: the force turns with the body
  };
  Vec3 force = Vec3::Zero();   // N
  Vec3 torque = Vec3::Zero();  // N·m
  Vec3 point = Vec3::Zero();   // m; body points are relative to the centre of mass
  Frame frame = Frame::World;
};

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
  // parts or with a bad part (named by its index). A body that does not
  // collide (def.collides false) gets no collider.
  Expected<BodyId> createBody(const BodyDef& def);
  Expected<bool> removeBody(BodyId id);  // an error for an invalid id

  BodyId findBody(std::string_view name) const;  // null id when absent
  // True for an id this world (or a copy of it) handed out whose body still
  // exists; false for a null, stale (removed) or foreign id.
  bool isValid(BodyId id) const;
  // A read-only view of the body. An invalid id is an error in every build:
  // it throws std::invalid_argument naming the id and why (null, removed, of
  // another world), rather than reading whatever body took over the slot.
  BodyView body(BodyId id) const;
  BodyId idOf(int denseIndex) const { return m_denseIds[static_cast<size_t>(denseIndex)]; }

  // Bodies in creation order; the index is a body's dense index, which
  // changes when an earlier body is removed (the BodyId does not).
  int bodyCount() const { return static_cast<int>(m_denseIds.size()); }
  BodyView bodyAt(int denseIndex) const;
  class BodyRange;
  BodyRange bodies() const;
  // The bodies themselves (an internal type, body/body.h), for the library's
  // own layers and its tests: collision detection runs on them.
  std::span<const Body> internalBodies() const;

  // Changes to one body. Each returns an error naming the body (or the id)
  // for an invalid id, and leaves the world as it was.
  //  - applyWrench: adds to the body's load for the coming step (cleared
  //    after it) and wakes its island before that step; a static body takes
  //    no load (nothing moves it). The values are not checked: a non-finite
  //    or overflowing wrench ends with the numerical guard freezing the body
  //    (world/state_guard.h); the server's limits refuse such wrenches first.
  //  - setBodyState: the whole state (quaternion normalised); it must be
  //    finite. The body wakes. A frozen body stays held where it froze.
  //  - setBodyVelocities: of the centre of mass (m/s) and about it (rad/s),
  //    world frame; finite. The body wakes.
  //  - setBodyDamping: decay rates of P and L (1/s, finite, not negative).
  Expected<bool> applyWrench(BodyId id, const Wrench& wrench);
  Expected<bool> setBodyState(BodyId id, const RigidState& state);
  Expected<bool> setBodyVelocities(BodyId id, const Vec3& linearVelocity, const Vec3& angularVelocity);
  Expected<bool> setBodyDamping(BodyId id, double linear, double angular);

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

  // Joints (rbsim/physics/joint_definition.h, docs/joints_design.md). A
  // jointed body takes the joint step (RATTLE, position-level) whatever the
  // world's integrator; bodies without joints keep the world's integrator.
  //  - createJoint: errors name the joint: an empty or duplicate name, an
  //    invalid body id, a body joined to itself, two sides of which neither
  //    moves, a bad anchor, axis or length (joint/joint_constraint.h), and a
  //    world on the penalty contact model (joints are impulse rows). The
  //    bodies wake.
  //  - removeJoint: an error for an invalid id; its bodies wake.
  //  - removeBody also removes the body's joints.
  // A body frozen by the numerical guard (or freezeBody) loses its joints:
  // they are removed, and the freeze event names them.
  Expected<JointId> createJoint(const JointDef& def);
  // A joint's actuation, changed between steps (as commands do): the motor
  // or the drive (off: enabled false; enabling one turns the other off) and
  // the direct effort. Errors name the joint; the joint's bodies wake.
  Expected<bool> setJointMotor(JointId id, const JointMotor& motor);
  Expected<bool> setJointDrive(JointId id, const JointDrive& drive);
  Expected<bool> setJointEffort(JointId id, double effort);
  Expected<bool> removeJoint(JointId id);
  JointId findJoint(std::string_view name) const;  // null id when absent
  bool isValid(JointId id) const;
  int jointCount() const;
  JointId jointIdAt(int denseIndex) const;  // joints in creation order
  // What the joint is doing now (its coordinate, error, last reaction); an
  // invalid id throws std::invalid_argument, as body() does.
  JointState jointState(JointId id) const;
  JointState jointStateAt(int denseIndex) const;
  // The joint as defined (its limits, motor, drive and effort in force), with
  // the points and directions of its creation; denseIndex < jointCount().
  const JointDef& jointDefinitionAt(int denseIndex) const;
  // The same by id; an invalid id throws std::invalid_argument.
  const JointDef& jointDefinition(JointId id) const;

  // Bodies frozen during the last step, in body order (empty most of the
  // time), each with the joints it lost.
  const std::vector<FreezeEvent>& freezeEvents() const { return m_freezeEvents; }
  int frozenBodyCount() const { return m_frozenBodies; }
  // Freezes a dynamic body at its last good pose now (for tests and for
  // restoring a saved world); false for a null, stale, static or already
  // frozen body. Not reported in freezeEvents(); its joints are removed.
  Expected<bool> freezeBody(BodyId id, FreezeReason reason = FreezeReason::Requested);
  void setStateLimits(const StateLimits& limits) { m_settings.limits = limits; }

  // The contacts of the last step (solved impulses included), sorted by
  // (serial A, serial B, piece A, piece B).
  const std::vector<SolvedManifold>& contacts() const { return m_contacts; }
  int contactPointCount() const;
  // Bodies asleep (at rest in an island that stopped being integrated).
  int sleepingBodyCount() const;
  Expected<bool> wakeUp(BodyId id);  // wakes the body's island for the coming step

  // Body serials are never reused within a world's life. A world reset to a
  // copy of its initial state continues after the serials it handed out.
  int32_t lastSerial() const { return m_lastSerial; }
  void continueSerialsAfter(int32_t serial) { m_lastSerial = std::max(m_lastSerial, serial); }

  const WorldSettings& settings() const { return m_settings; }
  void setGravity(const Vec3& gravity) { m_settings.gravity = gravity; }
  void setIntegrator(IntegratorKind kind) { m_settings.integrator = kind; }
  // The step's threads (WorldSettings::threads; 0: one per core). Every
  // count gives the same bits, so it may change between any two steps.
  Expected<bool> setThreads(int threads);
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

  // The complete state as bytes, for checkpoints: a world decoded from its
  // snapshot steps on bit-identically to the world it was taken from
  // (world_snapshot.cpp says what it holds and the format). Encoding fails
  // only for a shape the format cannot hold. Decoding takes the config's
  // settings, which must match those the snapshot recorded; errors name the
  // field and byte offset of truncated, corrupt or inconsistent data.
  static constexpr uint32_t kSnapshotMagic = 0x53574252u;  // "RBWS" in file order
  // 2: a body's freeze reason (numerical guard); 3: loads at points fixed in
  // the body, and whether a body's mass properties were given as data; 4:
  // joints; 5: a joint's coordinate at creation (JointDef::position); 6:
  // whether a body collides at all (BodyDef::collides); 7: a joint's
  // actuator limits (JointDef::actuatorLimits).
  static constexpr uint32_t kSnapshotVersion = 7;
  Expected<bool> writeSnapshot(ByteWriter& out) const;
  Expected<std::vector<uint8_t>> encodeSnapshot() const;
  static Expected<World> readSnapshot(ByteReader& in, const WorldSettings& settings);
  static Expected<World> decodeSnapshot(std::span<const uint8_t> bytes, const WorldSettings& settings);

 private:

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
  // The body behind a valid id, and its dense index.
  Body& bodyRef(BodyId id);
  std::size_t denseIndexOf(BodyId id) const;
  // A body with its load, for free flight to a time of impact.
  FlyingBody flying(std::size_t denseIndex) const;
  // Why `id` names no body of this world ("" when it does).
  std::string invalidIdReason(BodyId id) const;
  // The joints of a snapshot, after its bodies (world_snapshot.cpp).
  Expected<bool> readJointsSnapshot(ByteReader& in);
  // Gravity and the body's external load, for the integrator. Reads only,
  // so the step's threads may ask for different bodies at once.
  ForceInputs forcesOn(std::size_t denseIndex) const;
  // External loads act for one step: cleared here, once, at its end.
  void clearLoads();
  void findContacts();

  // The impulse model's step (world_impulse.cpp), in the order it runs:
  // islands → wake → integrate velocities → impacts → solve → integrate
  // positions → sleep.
  void stepImpulse();
  // Per dense index: the root of the island (bodies joined by contacts or
  // joints between dynamic bodies) it belongs to.
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
    std::vector<char> fast;        // solving, and fast enough to collide (loadSolverBodies)
    std::vector<char> jointed;     // per dense index: moved by its joints (empty: no joints)
    bool anyFast = false;
    // Per dense index: the time of impact (s into the step) of the body's
    // first collision this step, or < 0 for none; empty when nothing collides.
    std::vector<double> impactTime;
  };
  ContactStep selectContacts(const std::vector<BodyContact>& detected) const;
  // The solver's bodies: velocities after the forces of h (semi-implicit
  // Euler's first half); marks the fast ones.
  // Keeps `jointed` (empty: none) in the step for findImpacts.
  void loadSolverBodies(ContactStep& step, double h, const std::vector<char>& jointed);
  // Colliding contacts (world/impacts.h): each is moved to its time of
  // impact, with the manifold there, and its bodies' solver data with it.
  // A jointed body's flight is not free, so it has no time of impact: its
  // colliding contacts bounce where they are (see speculativeBounce).
  void findImpacts(ContactStep& step);
  // A colliding contact of a jointed body, if its pair bounces: the points
  // whose gap closes within the step are made touching, so that the solver
  // gives them −e v_rel now rather than stopping them at the gap (which is
  // a plastic collision). True when it changed the manifold.
  bool speculativeBounce(BodyContact& contact) const;
  void solveContacts(const std::vector<BodyContact>& active, const ContactSolverSettings& settings,
                     double h, std::vector<SolvedManifold>& solved, const VelocityProjection* equalities);
  // Puts every jointed body of an island that touches something into
  // step.solving (the contact path's kick and solve) and returns the joints'
  // velocity rows for the contact solve (null when no such island).
  std::unique_ptr<VelocityProjection> addJointedIslandsInContact(ContactStep& step, const std::vector<char>& jointed,
                                                                 const std::vector<int>& islandOf) const;
  // The enforced joints with a moving side as the joint solver takes them:
  // sides by `local` index (-1: a fixed pose), with the joint's index.
  void collectJointLinks(const std::vector<int>& local, std::vector<JointLink>& links,
                         std::vector<std::size_t>& linkJoint) const;
  // Per body: how many contacts away from a static body (shock propagation).
  std::vector<int> contactLevels(const std::vector<BodyContact>& active) const;
  // Momenta from the solved velocities and positions over h: semi-implicit
  // Euler's second half, with the split-impulse pseudo-velocities; free
  // flight over the rest of the step after a collision; the world's
  // integrator for a body that no impulse reached.
  // Jointed bodies are left to stepJointedBodies.
  void integrateSolvedBodies(const ContactStep& step, const std::vector<SolvedManifold>& solved, double h,
                             const std::vector<char>& jointed);
  // Keeps, in key order, the last results of contacts between sleeping bodies.
  void keepSleepingContacts(const std::vector<BodyContact>& detected,
                            std::vector<SolvedManifold>& solved) const;

  // Joints (world_joints.cpp). Per dense index: 1 for an awake dynamic body
  // with an enforced joint (empty when there is none): the joint step moves
  // it instead of the free integration and the contact path.
  std::vector<char> findJointedBodies() const;
  // Per dense index: 1 for a body that an actuator still moves (a motor
  // with a target rate, a drive whose joint still moves), which must not
  // fall asleep however slowly it goes; empty when no joint acts so.
  std::vector<char> findActuatedBodies() const;
  // The joint step of the jointed bodies over h (joint/joint_solver.h). An
  // island (`islandOf`) that touches nothing takes RATTLE: half kick, drift
  // and projection, half kick, velocity projection. An island in contact
  // takes the contact path's semi-implicit step around the same projection:
  // the whole kick and the contact impulses of m_solverBodies (for the
  // `solving` bodies) before the drift, and no kick after it, so that a
  // body resting on the ground leaves the step at rest.
  void stepJointedBodies(const std::vector<char>& jointed, const std::vector<char>& solving,
                         const std::vector<int>& islandOf, double h);
  std::string invalidJointReason(JointId id) const;
  // `detected` without the contacts of bodies that a joint joins (unless it
  // lets them collide): `detected` itself when no joint filters, else
  // `storage` filled.
  const std::vector<BodyContact>& contactsBetweenUnjoinedBodies(const std::vector<BodyContact>& detected,
                                                                std::vector<BodyContact>& storage) const;
  // Removes the joints of a body about to be removed (its dense index).
  std::vector<std::string> removeJointsOf(BodyId body);  // their names, in creation order
  bool jointIsEnforced(const JointConstraint& joint) const;
  void wakeJointBodies(const JointDef& def);

  void stepPenalty();
  // Continuous collision for bodies flagged `continuousCollision`: a body
  // whose motion over the step (from `starts`) would pass through another
  // body is stopped at its time of impact, velocity kept, so the next step's
  // contact stops it (no tunnelling through thin geometry).
  void applyContinuousCollision(const std::vector<RigidState>& starts);

  // The step's threads (settings.threads): the pool is made at the first
  // step, a copy of the world makes its own.
  TaskPool& taskPool() { return m_pool.get(m_settings.threads); }

  WorldSettings m_settings;
  OwnTaskPool m_pool;
  DeepCopyPtr<CollisionDetector> m_detector;
  uint32_t m_tag;  // stamped on the ids it hands out (ids.h); copies keep it
  DeepCopyPtr<ContactSolver> m_solver;
  // The joint step's solver: it keeps the symbolic factorisation of the
  // joints' system while their pattern stays (joint/joint_solver.h).
  DeepCopyPtr<JointSolver> m_jointSolver;
  std::vector<SolvedManifold> m_contacts;
  std::vector<SolverBody> m_solverBodies;  // scratch, one per body
  std::vector<Body> m_bodies;      // dense, in creation order
  // Parallel to m_bodies: the external loads for the coming step, kept here
  // rather than in the bodies (most bodies are pushed by nothing, and the
  // stepping loops read every body).
  std::vector<ExternalLoad> m_loads;
  std::vector<BodyId> m_denseIds;  // parallel to m_bodies
  std::vector<Slot> m_slots;
  std::vector<int32_t> m_freeSlots;  // reused lowest-first, for determinism
  // Joints, dense in creation order, with their ids and slots (as bodies).
  std::vector<JointConstraint> m_joints;
  std::vector<JointId> m_jointIds;
  std::vector<Slot> m_jointSlots;
  std::vector<int32_t> m_freeJointSlots;
  // Name lookup only; never iterated, so its order cannot leak into a step.
  std::unordered_map<std::string, BodyId> m_idByName;
  int64_t m_stepCount = 0;
  int32_t m_lastSerial = 0;
  int m_collidingBodies = 0;  // bodies with collision geometry
  int m_continuousBodies = 0; // dynamic bodies flagged for continuous collision
  int m_frozenBodies = 0;
  std::vector<FreezeEvent> m_freezeEvents;  // of the last step
  bool m_loadsSeen = false;  // some body may hold an external load (set where loads are added)
  // Bounds on every awake body's squared speeds after the last step, for
  // the detector (collision/collision_detector.h: DetectionStep); negative
  // when a change from outside (a new body, new velocities) made them
  // unknown. The step's integrations gather the next ones.
  double m_maxSquaredSpeed = -1.0;  // m²/s²
  double m_maxSquaredSpin = -1.0;   // 1/s²
  double m_stepSquaredSpeed = 0.0;
  double m_stepSquaredSpin = 0.0;
  void noteSpeeds(double squaredSpeed, double squaredSpin) {
    m_stepSquaredSpeed = std::max(m_stepSquaredSpeed, squaredSpeed);
    m_stepSquaredSpin = std::max(m_stepSquaredSpin, squaredSpin);
  }
  // The largest squared speeds one chunk of a parallel loop over the bodies saw.
  struct SpeedBound {
    double squaredSpeed = 0.0;
    double squaredSpin = 0.0;
    void note(double speed2, double spin2) {
      squaredSpeed = std::max(squaredSpeed, speed2);
      squaredSpin = std::max(squaredSpin, spin2);
    }
  };
  std::vector<SpeedBound> m_chunkSpeeds;  // scratch of forEachBody
  // Calls visit(i, bound) for every dense index i on the step's threads, in
  // chunks of a fixed size; visit may change body i and its own entries of
  // per-body arrays, nothing else, and notes the body's speeds in `bound`
  // (its chunk's). The chunks' bounds then go to noteSpeeds in chunk order:
  // a maximum is exact, so the result is the serial loop's.
  // (Defined in world/for_each_body.h, where Body is complete.)
  template <class Visit>
  void forEachBody(Visit&& visit);
  // False only when the last sleep update found every body awake (and
  // nothing since could have put one to sleep): the wake pass is skipped.
  bool m_maybeAsleep = true;
  // Per dense index, during a step: 1 when the guard has nothing left to do
  // for the body (judged and passed in integrateFree, static, asleep).
  std::vector<char> m_judged;
};

// The bodies in creation order, as views: for (BodyView b : world.bodies()).
class World::BodyRange {
 public:
  class Iterator {
   public:
    Iterator(const World* world, int index) : m_world(world), m_index(index) {}
    BodyView operator*() const { return m_world->bodyAt(m_index); }
    Iterator& operator++() {
      ++m_index;
      return *this;
    }
    bool operator!=(const Iterator& other) const { return m_index != other.m_index; }

   private:
    const World* m_world;
    int m_index;
  };
  explicit BodyRange(const World* world) : m_world(world) {}
  Iterator begin() const { return {m_world, 0}; }
  Iterator end() const { return {m_world, m_world->bodyCount()}; }
  int size() const { return m_world->bodyCount(); }
  BodyView operator[](std::size_t denseIndex) const { return m_world->bodyAt(static_cast<int>(denseIndex)); }

 private:
  const World* m_world;
};

inline World::BodyRange World::bodies() const { return BodyRange(this); }

}  // namespace rbsim
