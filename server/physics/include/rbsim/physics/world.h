#pragma once
// The world: owns the bodies and steps them by a fixed dt. With the headers
// beside it in include/rbsim/physics/ (the definitions, views and ids, and
// the value types they use; types.h gathers the latter) this is the physics
// library's public API: these headers include one another only, and what
// lives in the library's layer directories is internal to it (checked by
// tests/layering). World is a handle: its data and the step's stages are
// in world/.
//
// Determinism: the same sequence of calls gives bit-identical states. Bodies
// are stepped in creation order (kept across removals), no unordered
// container decides an order, and no clock or random source is read here.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rbsim/physics/body_definition.h"
#include "rbsim/physics/body_view.h"
#include "rbsim/physics/contacts.h"
#include "rbsim/physics/ids.h"
#include "rbsim/physics/joint_definition.h"
#include "rbsim/physics/ray_cast.h"
#include "rbsim/physics/shape_cast.h"
#include "rbsim/physics/types.h"
#include "rbsim/physics/world_settings.h"

namespace rbsim {

class ByteReader;
class ByteWriter;
// Internal to the library (world/world_data.h): only named here.
struct WorldData;

// A force and a couple on a body for the coming step. The force acts at a
// point fixed in the body: during the step (and at each RK4 stage) the point
// moves and turns with the body.
struct Wrench {
  enum class Frame {
    World,             // force, couple and point in the world frame (the point where it is now)
    WorldAtBodyPoint,  // force and couple in the world frame, the point in the body frame
    // Force, couple and point in the body frame (origin at the centre of
    // mass, axes along the principal axes: BodyView::rotation): the force
    // turns with the body. The server's shape-frame wrenches are converted.
    Body,
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
  BodyId idOf(int denseIndex) const;

  // Bodies in creation order; the index is a body's dense index, which
  // changes when an earlier body is removed (the BodyId does not).
  int bodyCount() const;
  BodyView bodyAt(int denseIndex) const;
  class BodyRange;
  BodyRange bodies() const;

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
  const std::vector<FreezeEvent>& freezeEvents() const;
  int frozenBodyCount() const;
  // Freezes a dynamic body at its last good pose now (for tests and for
  // restoring a saved world); false for a null, stale, static or already
  // frozen body. Not reported in freezeEvents(); its joints are removed.
  Expected<bool> freezeBody(BodyId id, FreezeReason reason = FreezeReason::Requested);
  void setStateLimits(const StateLimits& limits);

  // Collision filtering (rbsim/physics/collision_filter.h). Two bodies are
  // handed to the narrow phase only when their groups and masks allow it,
  // no joint joins them (unless the joint has collideConnected), and their
  // pair is not excluded here; what is filtered out is never tested, so it
  // costs nothing past the broad phase.
  //  - setPairCollision: excludes the pair of two distinct bodies (collide
  //    false) or takes the exclusion back (true); the groups, masks and
  //    joints still apply. Errors name an invalid id or a body paired with
  //    itself. Removing a body drops its exclusions.
  //  - canCollide: whether the filters let the two bodies collide now (all
  //    three rules); an invalid id throws std::invalid_argument, as body().
  //  - excludedPairs: the exclusions of setPairCollision, ordered by the
  //    bodies' creation (lower first in a pair, pairs by their first then
  //    their second body).
  Expected<bool> setPairCollision(BodyId a, BodyId b, bool collide);
  bool canCollide(BodyId a, BodyId b) const;
  std::vector<std::pair<BodyId, BodyId>> excludedPairs() const;

  // Ray casts against the bodies as they are now (rbsim/physics/ray_cast.h
  // says what a ray hits and what a hit reports; docs/queries.md). Between
  // steps only, never during one; any number of threads may cast at once.
  // The first cast after a change (a step, a body added, removed, placed
  // or frozen) brings the world's ray-cast tree up to date. An invalid
  // (non-null) filter.excluded throws std::invalid_argument, as body().
  //  - castRay: the nearest hit, ties going to the body created first and
  //    then to its lower piece.
  //  - castRayAll: every body the ray hits, once each (where it first
  //    enters the body), nearest first, ties as for castRay.
  //  - castRayAny: whether the ray hits anything; stops at the first hit
  //    found (an occlusion test).
  //  - castRays: castRay of every ray, hits[i] for rays[i] (hits.size()
  //    must equal rays.size(), or std::invalid_argument), shared among the
  //    world's threads (settings().threads). Each answer is bit for bit
  //    castRay's, on any number of threads.
  std::optional<RayHit> castRay(const Ray& ray, const RayFilter& filter = {}) const;
  std::vector<RayHit> castRayAll(const Ray& ray, const RayFilter& filter = {}) const;
  bool castRayAny(const Ray& ray, const RayFilter& filter = {}) const;
  void castRays(std::span<const Ray> rays, std::span<std::optional<RayHit>> hits,
                const RayFilter& filter = {}) const;

  // Shape casts against the bodies as they are now (rbsim/physics/
  // shape_cast.h; docs/queries.md): a sphere, box, capsule or cylinder
  // swept along a segment without turning, filtered as rays are, under the
  // same rules (between steps, any number of threads at once).
  //  - castShape: the first body the shape touches, ties as for castRay.
  //  - castShapeAll: every body it touches, once each (where it first
  //    touches it), nearest first.
  // A sweep with from == to reports what the shape touches where it
  // stands (an overlap test); one with a non-finite end or orientation
  // touches nothing. A shape of a bad size (not finite, or not positive:
  // a radius, a half extent or a half length of 0 or less; a capsule's
  // half length may be 0) throws std::invalid_argument, naming it.
  std::optional<ShapeCastHit> castShape(const ShapeCast& cast, const RayFilter& filter = {}) const;
  std::vector<ShapeCastHit> castShapeAll(const ShapeCast& cast, const RayFilter& filter = {}) const;

  // The contacts of the last step (solved impulses included), sorted by
  // (serial A, serial B, piece A, piece B).
  const std::vector<SolvedManifold>& contacts() const;
  int contactPointCount() const;
  // Bodies asleep (at rest in an island that stopped being integrated).
  int sleepingBodyCount() const;
  Expected<bool> wakeUp(BodyId id);  // wakes the body's island for the coming step

  // Body serials are never reused within a world's life. A world reset to a
  // copy of its initial state continues after the serials it handed out.
  int32_t lastSerial() const;
  void continueSerialsAfter(int32_t serial);

  const WorldSettings& settings() const;
  void setGravity(const Vec3& gravity);
  void setIntegrator(IntegratorKind kind);
  // The step's threads (WorldSettings::threads; 0: one per core). Every
  // count gives the same bits, so it may change between any two steps.
  Expected<bool> setThreads(int threads);
  int64_t stepCount() const;
  double time() const;  // s: stepCount() dt

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
  // (world/snapshot.cpp says what it holds and the format). Encoding fails
  // only for a shape the format cannot hold. Decoding takes the config's
  // settings, which must match those the snapshot recorded; errors name the
  // field and byte offset of truncated, corrupt or inconsistent data.
  static constexpr uint32_t kSnapshotMagic = 0x53574252u;  // "RBWS" in file order
  // 2: a body's freeze reason (numerical guard); 3: loads at points fixed in
  // the body, and whether a body's mass properties were given as data; 4:
  // joints; 5: a joint's coordinate at creation (JointDef::position); 6:
  // whether a body collides at all (BodyDef::collides); 7: a joint's
  // actuator limits (JointDef::actuatorLimits); 8: a body's collision
  // group and mask (BodyDef::collisionFilter) and the excluded pairs
  // (setPairCollision); 9: a joint's mimic (JointDef::mimic) and its
  // coupling's error; 10: a drive's gravity compensation; 11: a drive's
  // target rate; 12: the joint solver's factors' inputs (a factor kept
  // across steps, JointSolverSettings::keepRatio).
  static constexpr uint32_t kSnapshotVersion = 12;
  Expected<bool> writeSnapshot(ByteWriter& out) const;
  Expected<std::vector<uint8_t>> encodeSnapshot() const;
  static Expected<World> readSnapshot(ByteReader& in, const WorldSettings& settings);
  static Expected<World> decodeSnapshot(std::span<const uint8_t> bytes, const WorldSettings& settings);

 private:
  // Everything the world is (world/world_data.h); never null but in a
  // moved-from world. Copies copy it whole.
  std::unique_ptr<WorldData> m_data;
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
