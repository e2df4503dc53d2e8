#include "rbsim/physics/world.h"
#include "physics/world/for_each_body.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "physics/body/body.h"
#include "physics/body/external_load.h"
#include "physics/body/integrator.h"
#include "physics/collision/collision_detector.h"
#include "physics/joint/joint_constraint.h"
#include "physics/joint/joint_solver.h"
#include "physics/solver/contact_solver.h"
#include "physics/world/impacts.h"

namespace rbsim {

namespace {

bool isPositiveFinite(double value) { return std::isfinite(value) && value > 0.0; }
bool isFiniteVec(const Vec3& v) { return v.allFinite(); }
// A quaternion that normalises to a rotation: finite entries whose norm is
// neither (nearly) zero nor beyond double range (entries of 1e200 are finite,
// their squares are not).
bool isRotationQuaternion(const Quaternion& q) {
  const double norm = q.norm();
  return q.isFinite() && std::isfinite(norm) && norm >= 1e-9;
}

MassProperties scaled(const MassProperties& unit, double density);

// Mass properties of the shape at unit density, or an error for a bad size.
// A compound's parts of their own density weigh density / bodyDensity
// (kg/m³ over kg/m³), so that scaling by the body's density gives each part
// its own.
Expected<MassProperties> unitDensityMassProperties(const BodyDef& def) {
  const std::string where = "body '" + def.name + "': ";
  struct Visitor {
    const std::string& where;
    double bodyDensity;  // kg/m³
    Expected<MassProperties> operator()(const SphereShape& s) const {
      if (!isPositiveFinite(s.radius)) return Error{where + "sphere radius must be positive"};
      return sphereMassProperties(s.radius, 1.0);
    }
    Expected<MassProperties> operator()(const BoxShape& s) const {
      if (!isPositiveFinite(s.halfExtents.minCoeff()) || !s.halfExtents.allFinite())
        return Error{where + "box half_extents must be positive"};
      return boxMassProperties(s.halfExtents, 1.0);
    }
    Expected<MassProperties> operator()(const CylinderShape& s) const {
      if (!isPositiveFinite(s.radius) || !isPositiveFinite(s.halfLength))
        return Error{where + "cylinder radius and half_length must be positive"};
      return cylinderMassProperties(s.radius, s.halfLength, 1.0);
    }
    Expected<MassProperties> operator()(const CapsuleShape& s) const {
      // A capsule of zero cylindrical length is a sphere: allowed.
      if (!isPositiveFinite(s.radius) || !(std::isfinite(s.halfLength) && s.halfLength >= 0.0))
        return Error{where + "capsule radius must be positive and half_length not negative"};
      return capsuleMassProperties(s.radius, s.halfLength, 1.0);
    }
    Expected<MassProperties> operator()(const MeshShape& s) const {
      if (!s.mesh) return Error{where + "mesh '" + s.file + "' was not loaded"};
      const auto valid = validateClosedMesh(*s.mesh, s.file);
      if (!valid) return valid.error();
      return polyhedronMassProperties(*s.mesh, 1.0);
    }
    Expected<MassProperties> operator()(const PlaneShape& s) const {
      if (!s.normal.allFinite() || s.normal.norm() < 1e-12 || !std::isfinite(s.offset))
        return Error{where + "plane normal must be a finite non-zero vector"};
      return MassProperties{};  // a half-space has no finite mass
    }
    Expected<MassProperties> operator()(const CompoundShape& s) const {
      if (s.parts.empty()) return Error{where + "a compound needs at least one part"};
      std::vector<PlacedMassProperties> parts;
      parts.reserve(s.parts.size());
      for (std::size_t i = 0; i < s.parts.size(); ++i) {
        const CompoundPart& part = s.parts[i];
        const std::string partWhere = where + "compound part " + std::to_string(i) + ": ";
        if (!isFiniteVec(part.position) || !isRotationQuaternion(part.orientation))
          return Error{partWhere +
                       "position and orientation must be finite, the quaternion non-zero"};
        if (part.density && !isPositiveFinite(*part.density))
          return Error{partWhere + "density must be positive"};
        const auto unit = std::visit(Visitor{partWhere, bodyDensity}, part.shape);
        if (!unit) return unit.error();
        const double weight = part.density ? *part.density / bodyDensity : 1.0;
        parts.push_back({scaled(*unit, weight),
                         Transform::fromPose(part.position, part.orientation.normalized())});
      }
      return combinedMassProperties(parts);
    }
  };
  return std::visit(Visitor{where, def.density.value_or(BodyDef::kDefaultDensity)}, def.shape);
}

// Tags for the ids of worlds built anew; copies keep theirs. Only an id's
// validity depends on it, never a step, so its global order cannot leak
// into a simulation.
uint32_t newWorldTag() {
  static std::atomic<uint32_t> last{0};
  return ++last;
}

MassProperties scaled(const MassProperties& unit, double density) {
  MassProperties result = unit;
  result.mass = unit.mass * density;
  result.inertia = unit.inertia * density;
  return result;
}

}  // namespace

World::World(const WorldSettings& settings)
    : m_settings(settings),
      m_detector(std::make_unique<CollisionDetector>(settings.contact.detection)),
      m_tag(newWorldTag()),
      m_solver(std::make_unique<ContactSolver>()),
      m_jointSolver(std::make_unique<JointSolver>()) {}

World::World(const World& other) = default;
World::World(World&& other) noexcept = default;
World& World::operator=(const World& other) = default;
World& World::operator=(World&& other) noexcept = default;
World::~World() = default;

Expected<World> World::fromDef(const WorldDef& def) {
  World world(def.settings);
  for (const BodyDef& body : def.bodies) {
    const auto id = world.createBody(body);
    if (!id) return id.error();
  }
  for (const NamedJointDef& named : def.joints) {
    JointDef joint = named.def;
    const std::string where = named.source.empty() ? "" : named.source + ": ";
    for (const bool sideB : {false, true}) {
      const std::string& name = sideB ? named.bodyB : named.bodyA;
      if (name == "world") continue;
      const BodyId id = world.findBody(name);
      if (id.isNull()) return Error{where + (sideB ? "body_b" : "body_a") + ": no body named '" + name + "'"};
      (sideB ? joint.bodyB : joint.bodyA) = id;
    }
    const auto id = world.createJoint(joint);
    if (!id) return Error{where + id.error().message};
  }
  return world;
}

Expected<BodyId> World::createBody(const BodyDef& def) {
  if (def.name.empty()) return Error{"a body needs a non-empty name"};
  if (!findBody(def.name).isNull()) return Error{"a body named '" + def.name + "' already exists"};
  const std::string where = "body '" + def.name + "': ";
  if (!isFiniteVec(def.position) || !isFiniteVec(def.linearVelocity) ||
      !isFiniteVec(def.angularVelocity) || !def.orientation.isFinite())
    return Error{where + "position, orientation and velocities must be finite"};
  if (!isRotationQuaternion(def.orientation))
    return Error{where + "the orientation quaternion must be non-zero and of finite norm"};
  const bool isPlane = std::holds_alternative<PlaneShape>(def.shape);
  if (isPlane && !def.isStatic) return Error{where + "a plane can only be a static body"};
  if (def.mass && def.density) return Error{where + "give mass or density, not both"};
  if (def.mass && !isPositiveFinite(*def.mass)) return Error{where + "mass must be positive"};
  if (def.density && !isPositiveFinite(*def.density))
    return Error{where + "density must be positive"};
  if (def.centerOfMass && !def.inertia)
    return Error{where + "a centre of mass needs an inertia tensor (and a mass) with it"};
  if (def.inertia) {
    if (def.isStatic)
      return Error{where +
                   "a static body has no mass properties; remove mass, inertia and centre of mass"};
    if (!def.mass)
      return Error{where + "an inertia tensor needs the body's mass with it (not a density)"};
    if (def.centerOfMass && !isFiniteVec(*def.centerOfMass))
      return Error{where + "the centre of mass must be finite"};
    if (const auto problem = inertiaTensorProblem(*def.inertia)) return Error{where + *problem};
  }
  const double linearDamping = def.linearDamping.value_or(m_settings.linearDamping);
  const double angularDamping = def.angularDamping.value_or(m_settings.angularDamping);
  if (!(std::isfinite(linearDamping) && linearDamping >= 0.0) ||
      !(std::isfinite(angularDamping) && angularDamping >= 0.0))
    return Error{where + "damping must be finite and not negative"};

  const auto unit = unitDensityMassProperties(def);
  if (!unit) return unit.error();

  auto description = std::make_shared<BodyDescription>();
  description->name = def.name;
  description->shape = def.shape;
  description->isStatic = def.isStatic;
  description->material = resolveMaterial(def.material, m_settings.contact.defaultMaterial);
  description->continuousCollision = def.continuousCollision;
  description->collides = def.collides;
  if (description->material.restitution > 1.0 || description->material.restitution < 0.0 ||
      description->material.friction < 0.0 ||
      description->material.staticCoefficient() < description->material.friction)
    return Error{where + "restitution must be in [0, 1], friction >= 0 and static friction >= friction"};

  BodyDynamics dynamics;
  dynamics.linearDamping = linearDamping;
  dynamics.angularDamping = angularDamping;
  Vec3 centerOfMass = Vec3::Zero();
  Mat3 principal = Mat3::Identity();  // columns: principal axes in the shape frame
  if (isPlane) {
    dynamics.mass = 0.0;  // a half-space has no finite mass
    dynamics.inertiaBody = Vec3::Zero();
  } else {
    // unit->mass is the volume, except for a compound whose parts have
    // densities of their own (then it weighs them).
    const double density = def.mass ? *def.mass / unit->mass
                                    : def.density.value_or(BodyDef::kDefaultDensity);
    if (def.inertia) {
      // Given as data: the shape keeps only its volume (and its collider).
      // The mean of the two triangles keeps a given symmetric tensor as it
      // is and splits round-off evenly.
      description->massPropertiesGiven = true;
      description->massProperties.mass = *def.mass;
      description->massProperties.volume = unit->volume;
      description->massProperties.centerOfMass = def.centerOfMass.value_or(Vec3::Zero());
      description->massProperties.inertia = 0.5 * (*def.inertia + def.inertia->transpose());
    } else {
      description->massProperties = scaled(*unit, density);
      if (def.mass) description->massProperties.mass = *def.mass;  // exactly as given
    }
    const PrincipalAxes axes = principalAxes(description->massProperties.inertia);
    centerOfMass = description->massProperties.centerOfMass;
    principal = axes.axes;
    if (!isPositiveFinite(description->massProperties.mass) || !isPositiveFinite(axes.moments.minCoeff()))
      return Error{where + "mass properties are degenerate (zero mass or moment)"};
    dynamics.mass = description->massProperties.mass;
    dynamics.inertiaBody = axes.moments;
  }
  if (def.isStatic) {
    dynamics.inverseMass = 0.0;
    dynamics.inverseInertiaBody = Vec3::Zero();
  } else {
    dynamics.inverseMass = 1.0 / dynamics.mass;
    dynamics.inverseInertiaBody = dynamics.inertiaBody.cwiseInverse();
  }

  // Body space: origin at the centre of mass, axes along the principal axes.
  // p_shape = c + A p_body, so p_body = Aᵀ (p_shape − c).
  description->shapeRotation = principal.transpose();
  description->shapeTranslation = -(principal.transpose() * centerOfMass);
  if (const auto* mesh = std::get_if<MeshShape>(&def.shape)) {
    description->bodySpaceMesh = std::make_shared<TriangleMesh>(
        transformed(*mesh->mesh, description->shapeRotation, description->shapeTranslation));
  }
  // A body that collides with nothing has no collider: detection and the
  // sweeps skip a body without one (and its mesh parts need no hulls).
  if (def.collides) {
    auto collider = buildCollider(def.shape, Transform{description->shapeRotation, description->shapeTranslation},
                                  "body '" + def.name + "'");
    if (!collider) return collider.error();
    description->collider = std::make_shared<const Collider>(std::move(collider).value());
  }

  const Quaternion shapeOrientation = def.orientation.normalized();
  RigidState state;
  state.position = def.position + shapeOrientation.rotate(centerOfMass);
  state.orientation = (shapeOrientation * Quaternion::fromRotationMatrix(principal)).normalized();
  Body body(std::move(description), dynamics, state);
  if (!def.isStatic) body.setVelocities(def.linearVelocity, def.angularVelocity);

  int32_t slot;
  if (!m_freeSlots.empty()) {
    const auto lowest = std::min_element(m_freeSlots.begin(), m_freeSlots.end());
    slot = *lowest;
    m_freeSlots.erase(lowest);
  } else {
    slot = static_cast<int32_t>(m_slots.size());
    m_slots.push_back({});
  }
  m_slots[static_cast<size_t>(slot)].denseIndex = static_cast<int32_t>(m_bodies.size());
  const BodyId id{slot + 1, m_slots[static_cast<size_t>(slot)].generation, m_tag};
  body.setSerial(++m_lastSerial);
  m_idByName.emplace(def.name, id);
  if (body.description().collider) ++m_collidingBodies;
  if (def.continuousCollision && !def.isStatic) ++m_continuousBodies;
  m_bodies.push_back(std::move(body));
  m_loads.emplace_back();
  m_maxSquaredSpeed = m_maxSquaredSpin = -1.0;  // its velocities are the caller's
  m_denseIds.push_back(id);
  return id;
}

Expected<bool> World::removeBody(BodyId id) {
  if (const std::string why = invalidIdReason(id); !why.empty()) return Error{"cannot remove: " + why};
  removeJointsOf(id);
  Slot& slot = m_slots[static_cast<size_t>(id.index - 1)];
  const auto dense = static_cast<size_t>(slot.denseIndex);
  m_idByName.erase(m_bodies[dense].name());
  if (m_bodies[dense].description().collider) --m_collidingBodies;
  if (m_bodies[dense].description().continuousCollision && !m_bodies[dense].isStatic())
    --m_continuousBodies;
  if (m_bodies[dense].isFrozen()) --m_frozenBodies;
  m_bodies.erase(m_bodies.begin() + static_cast<std::ptrdiff_t>(dense));
  m_loads.erase(m_loads.begin() + static_cast<std::ptrdiff_t>(dense));
  m_denseIds.erase(m_denseIds.begin() + static_cast<std::ptrdiff_t>(dense));
  for (size_t i = dense; i < m_denseIds.size(); ++i)
    m_slots[static_cast<size_t>(m_denseIds[i].index - 1)].denseIndex = static_cast<int32_t>(i);
  slot.denseIndex = -1;
  ++slot.generation;
  m_freeSlots.push_back(id.index - 1);
  return true;
}

BodyId World::findBody(std::string_view name) const {
  const auto found = m_idByName.find(std::string(name));
  return found == m_idByName.end() ? BodyId{} : found->second;
}

bool World::isValid(BodyId id) const { return invalidIdReason(id).empty(); }

std::string World::invalidIdReason(BodyId id) const {
  // The message is made only for an id that fails: a valid one (every body
  // lookup of every step) costs no string.
  const auto named = [&] {
    return "body id (index " + std::to_string(id.index) + ", generation " + std::to_string(id.generation) +
           ", world " + std::to_string(id.world) + ")";
  };
  if (id.isNull()) return "a null body id";
  if (id.world != m_tag) return named() + " is of another world";
  if (id.index < 1 || static_cast<size_t>(id.index) > m_slots.size()) return named() + " names no slot of this world";
  const Slot& slot = m_slots[static_cast<size_t>(id.index - 1)];
  if (slot.denseIndex < 0 || slot.generation != id.generation) return named() + " is stale: its body was removed";
  return {};
}

BodyView World::body(BodyId id) const {
  if (const std::string why = invalidIdReason(id); !why.empty()) throw std::invalid_argument(why);
  return bodyAt(m_slots[static_cast<size_t>(id.index - 1)].denseIndex);
}

BodyView World::bodyAt(int denseIndex) const {
  const auto i = static_cast<size_t>(denseIndex);
  return BodyView(m_bodies[i], m_loads[i].active);
}

FlyingBody World::flying(std::size_t denseIndex) const {
  const ExternalLoad& load = m_loads[denseIndex];
  return {m_bodies[denseIndex], load.active ? &load : nullptr};
}

std::span<const Body> World::internalBodies() const { return m_bodies; }

std::size_t World::denseIndexOf(BodyId id) const {
  return static_cast<size_t>(m_slots[static_cast<size_t>(id.index - 1)].denseIndex);
}

Body& World::bodyRef(BodyId id) { return m_bodies[denseIndexOf(id)]; }

Expected<bool> World::applyWrench(BodyId id, const Wrench& wrench) {
  if (const std::string why = invalidIdReason(id); !why.empty()) return Error{"cannot push: " + why};
  const Body& target = bodyRef(id);
  if (target.isStatic()) return true;  // nothing moves it
  ExternalLoad& load = m_loads[denseIndexOf(id)];
  m_loadsSeen = true;
  switch (wrench.frame) {
    case Wrench::Frame::World:
      load.addWorldWrench(wrench.force, wrench.torque, target.worldToBody(wrench.point));
      break;
    case Wrench::Frame::WorldAtBodyPoint:
      load.addWorldWrench(wrench.force, wrench.torque, wrench.point);
      break;
    case Wrench::Frame::Body:
      load.addBodyWrench(wrench.force, wrench.torque, wrench.point);
      break;
  }
  return true;
}

Expected<bool> World::setBodyState(BodyId id, const RigidState& state) {
  if (const std::string why = invalidIdReason(id); !why.empty()) return Error{"cannot set the state: " + why};
  Body& target = bodyRef(id);
  if (!state.position.allFinite() || !state.orientation.isFinite() || state.orientation.norm() < 1e-9 ||
      !state.linearMomentum.allFinite() || !state.angularMomentum.allFinite())
    return Error{"body '" + target.name() + "': a state must be finite, its quaternion non-zero"};
  target.setState(state);
  target.wake();
  m_maxSquaredSpeed = m_maxSquaredSpin = -1.0;
  return true;
}

Expected<bool> World::setBodyVelocities(BodyId id, const Vec3& linearVelocity, const Vec3& angularVelocity) {
  if (const std::string why = invalidIdReason(id); !why.empty())
    return Error{"cannot set the velocities: " + why};
  Body& target = bodyRef(id);
  if (!linearVelocity.allFinite() || !angularVelocity.allFinite())
    return Error{"body '" + target.name() + "': velocities must be finite"};
  if (target.isStatic() || target.isFrozen()) return true;  // held still either way
  target.setVelocities(linearVelocity, angularVelocity);
  target.wake();
  m_maxSquaredSpeed = m_maxSquaredSpin = -1.0;
  return true;
}

Expected<bool> World::setThreads(int threads) {
  if (threads < 0 || threads > kMaxThreads)
    return Error{"threads must be 0 (one per core) to " + std::to_string(kMaxThreads) + ", not " +
                 std::to_string(threads)};
  m_settings.threads = threads;
  return true;
}

Expected<bool> World::setBodyDamping(BodyId id, double linear, double angular) {
  if (const std::string why = invalidIdReason(id); !why.empty()) return Error{"cannot set damping: " + why};
  Body& target = bodyRef(id);
  if (!(std::isfinite(linear) && linear >= 0.0) || !(std::isfinite(angular) && angular >= 0.0))
    return Error{"body '" + target.name() + "': damping must be finite and not negative"};
  target.setDamping(linear, angular);
  return true;
}

void World::step() {
  m_judged.assign(m_bodies.size(), 0);
  const bool anyContact = m_settings.contact.enabled && m_collidingBodies > 0;
  // The impulse model's step is also where islands at rest fall asleep, so
  // a world whose bodies all collide with nothing (BodyDef::collides) takes
  // it too: its detector finds no contact, and every body flies free as in
  // the step without contact below.
  const bool impulseStep =
      m_settings.contact.enabled && m_settings.contact.model == ContactModel::Impulse && !m_bodies.empty();
  std::vector<RigidState> starts;
  if (anyContact && m_continuousBodies > 0) {
    starts.reserve(m_bodies.size());
    for (const Body& body : m_bodies) starts.push_back(body.state());
  }
  if (impulseStep) {
    m_stepSquaredSpeed = m_stepSquaredSpin = 0.0;
    stepImpulse();
    // Every awake body was integrated by one of the step's paths, which
    // noted its speeds; sleeping, static and frozen bodies stand still.
    m_maxSquaredSpeed = m_stepSquaredSpeed;
    m_maxSquaredSpin = m_stepSquaredSpin;
  } else if (anyContact) {
    stepPenalty();
  } else {
    const std::vector<char> jointed = findJointedBodies();
    integrateFree(m_settings.dt, jointed);
    stepJointedBodies(jointed, {}, {}, m_settings.dt);
    m_contacts.clear();
  }
  if (!starts.empty()) applyContinuousCollision(starts);
  clearLoads();
  ++m_stepCount;
  guardStates();
}

ForceInputs World::forcesOn(std::size_t denseIndex) const {
  ForceInputs inputs;
  inputs.gravity = m_settings.gravity;
  if (const ExternalLoad& load = m_loads[denseIndex]; load.active) inputs.load = &load;
  return inputs;
}

void World::clearLoads() {
  // Every pushed body was integrated (a push wakes a sleeping one; static
  // bodies take none; frozen ones drop theirs).
  if (!m_loadsSeen) return;
  for (ExternalLoad& load : m_loads)
    if (load.active) load.clear();
  m_loadsSeen = false;
}

void World::guardStates() {
  if (!m_freezeEvents.empty()) m_freezeEvents.clear();
  const StateLimits& limits = m_settings.limits;
  const double maxLinear2 = limits.maxLinearSpeed * limits.maxLinearSpeed;
  const double maxAngular2 = limits.maxAngularSpeed * limits.maxAngularSpeed;
  for (std::size_t i = 0; i < m_bodies.size(); ++i) {
    // Most bodies were judged by integrateFree while they were in cache; a
    // byte per body is all this pass reads of them.
    if (m_judged[i]) continue;
    Body& body = m_bodies[i];
    if (body.isStatic()) continue;
    if (body.isFrozen()) {
      // Back where it froze, whatever a contact path did to it in the step.
      body.holdAtLastGoodPose();
      m_loads[i].clear();
      continue;
    }
    if (body.isSleeping()) continue;  // it has not moved since it last passed
    if (isHealthy(body.state(), body.linearVelocity(), body.angularVelocity(), maxLinear2, maxAngular2)) {
      body.keepPoseAsGood();
      continue;
    }
    const StateVerdict verdict =
        judgeState(body.state(), body.linearVelocity(), body.angularVelocity(), limits);
    if (verdict.reason == FreezeReason::None) continue;  // a pose sum that overflowed: none does
    body.setFreezeReason(verdict.reason);
    ++m_frozenBodies;
    body.holdAtLastGoodPose();
    m_loads[i].clear();
    m_freezeEvents.push_back({m_denseIds[i], body.name(), m_stepCount, verdict, {}});
  }
  // A frozen body cannot hold a joint: its joints go (the server logs them).
  for (FreezeEvent& event : m_freezeEvents) event.droppedJoints = removeJointsOf(event.id);
}

Expected<bool> World::freezeBody(BodyId id, FreezeReason reason) {
  if (const std::string why = invalidIdReason(id); !why.empty()) return Error{"cannot freeze: " + why};
  Body& frozen = bodyRef(id);
  if (reason == FreezeReason::None) return Error{"body '" + frozen.name() + "': a freeze needs a reason"};
  if (frozen.isStatic()) return Error{"body '" + frozen.name() + "' is static: nothing to freeze"};
  if (frozen.isFrozen()) return Error{"body '" + frozen.name() + "' is frozen already"};
  frozen.setFreezeReason(reason);
  ++m_frozenBodies;
  frozen.holdAtLastGoodPose();
  m_loads[denseIndexOf(id)].clear();
  (void)removeJointsOf(id);
  return true;
}

void World::integrateFree(double h, const std::vector<char>& skip) {
  const IntegratorKind integrator = m_settings.integrator;
  const double maxLinear2 = m_settings.limits.maxLinearSpeed * m_settings.limits.maxLinearSpeed;
  const double maxAngular2 = m_settings.limits.maxAngularSpeed * m_settings.limits.maxAngularSpeed;
  // Continuous collision may still move flagged bodies after this: those are
  // judged in guardStates, after it.
  const bool laterMoves = m_continuousBodies > 0;
  forEachBody([&](std::size_t i, SpeedBound& bound) {
    Body& body = m_bodies[i];
    if (body.isStatic() || body.isSleeping()) {
      m_judged[i] = 1;  // nothing to check: it does not move this step
      return;
    }
    if (body.isFrozen()) return;
    if (!skip.empty() && skip[i]) {
      // In contact: the solver moves it later in this step, and guardStates
      // judges it then, against the pose it has now.
      body.keepPoseAsGood();
      return;
    }
    const ForceInputs inputs = forcesOn(i);
    const RigidState next =
        integrateStep(integrator, body.state(), body.rotation(), body.dynamics(), inputs, h);
    // The guard's check, on the new state while it is at hand. A body it
    // cannot clear (or that continuous collision may still move) is judged
    // again in guardStates, and frozen there at the pose it has now.
    // For the guard and for the next step's collision detection.
    const SpeedBounds speeds = speedBounds(next, body.dynamics().inverseMass, body.dynamics().inverseInertiaBody);
    bound.note(speeds.squaredSpeed, speeds.squaredSpin);
    const bool judgedHere = speeds.squaredSpeed <= maxLinear2 && speeds.squaredSpin <= maxAngular2 &&
                            !(laterMoves && body.description().continuousCollision);
    if (!judgedHere) body.keepPoseAsGood();
    m_judged[i] = judgedHere ? 1 : 0;
    body.moveTo(next);
  });
}

Vec3 World::totalLinearMomentum() const {
  Vec3 total = Vec3::Zero();
  for (const Body& body : m_bodies)
    if (!body.isStatic()) total += body.linearMomentum();
  return total;
}

Vec3 World::totalAngularMomentum() const {
  Vec3 total = Vec3::Zero();
  for (const Body& body : m_bodies)
    if (!body.isStatic()) total += body.angularMomentum() + body.position().cross(body.linearMomentum());
  return total;
}

double World::totalKineticEnergy() const {
  double total = 0.0;
  for (const Body& body : m_bodies)
    if (!body.isStatic()) total += body.kineticEnergy();
  return total;
}

uint64_t World::stateHash() const {
  uint64_t hash = 14695981039346656037ull;
  const auto mix = [&hash](const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
      hash ^= bytes[i];
      hash *= 1099511628211ull;
    }
  };
  mix(&m_stepCount, sizeof m_stepCount);
  for (const Body& body : m_bodies) {
    const RigidState& s = body.state();
    const double values[13] = {s.position.x(),       s.position.y(),       s.position.z(),
                               s.orientation.w,      s.orientation.x,      s.orientation.y,
                               s.orientation.z,      s.linearMomentum.x(), s.linearMomentum.y(),
                               s.linearMomentum.z(), s.angularMomentum.x(), s.angularMomentum.y(),
                               s.angularMomentum.z()};
    mix(values, sizeof values);
  }
  return hash;
}

}  // namespace rbsim
