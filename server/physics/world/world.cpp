// World, the handle: its public functions, which check their arguments
// and forward to the stages (world/step_stages.h), and the bookkeeping of
// bodies (creation, removal, ids, changes between steps).
#include "rbsim/physics/world.h"

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
#include "rbsim/physics/byte_stream.h"
#include "physics/solver/contact_solver.h"
#include "physics/world/impacts.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

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
    Expected<MassProperties> operator()(const TriangleMeshShape& s) const {
      if (!s.mesh) return Error{where + "trimesh '" + s.file + "' was not loaded"};
      const auto valid = validateSurfaceMesh(*s.mesh, s.file);
      if (!valid) return valid.error();
      return MassProperties{};  // static only: a surface has no mass
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

WorldData::WorldData(const WorldSettings& worldSettings)
    : settings(worldSettings),
      detector(std::make_unique<CollisionDetector>(worldSettings.contact.detection)),
      tag(newWorldTag()),
      solver(std::make_unique<ContactSolver>()),
      softSolver(std::make_unique<SoftStepSolver>()),
      jointSolver(std::make_unique<JointSolver>()) {}

WorldData::WorldData(const WorldData& other) = default;
WorldData& WorldData::operator=(const WorldData& other) = default;
WorldData::~WorldData() = default;

World::World(const WorldSettings& settings) : m_data(std::make_unique<WorldData>(settings)) {}

// As the members' own copies did when they were World's: a copy is a new
// world with everything copied (the task pool aside); an assignment copies
// into the data the world has (keeping its pool).
World::World(const World& other)
    : m_data(other.m_data ? std::make_unique<WorldData>(*other.m_data) : nullptr) {}
World::World(World&& other) noexcept = default;
World& World::operator=(const World& other) {
  if (this == &other) return *this;
  if (m_data && other.m_data)
    *m_data = *other.m_data;
  else
    m_data = other.m_data ? std::make_unique<WorldData>(*other.m_data) : nullptr;
  return *this;
}
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
  for (const ExcludedPair& pair : def.excludedPairs) {
    const BodyId a = world.findBody(pair.bodyA);
    const BodyId b = world.findBody(pair.bodyB);
    const std::string which = "excluded pair ('" + pair.bodyA + "', '" + pair.bodyB + "'): ";
    if (a.isNull() || b.isNull())
      return Error{which + "no body named '" + (a.isNull() ? pair.bodyA : pair.bodyB) + "'"};
    if (auto set = world.setPairCollision(a, b, false); !set) return Error{which + set.error().message};
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
  if (isStaticOnlyShape(def.shape) && !def.isStatic)
    return Error{where + "a " + shapeTypeName(def.shape) + " can only be a static body"};
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
  const double linearDamping = def.linearDamping.value_or(m_data->settings.linearDamping);
  const double angularDamping = def.angularDamping.value_or(m_data->settings.angularDamping);
  if (!(std::isfinite(linearDamping) && linearDamping >= 0.0) ||
      !(std::isfinite(angularDamping) && angularDamping >= 0.0))
    return Error{where + "damping must be finite and not negative"};

  const auto unit = unitDensityMassProperties(def);
  if (!unit) return unit.error();

  auto description = std::make_shared<BodyDescription>();
  description->name = def.name;
  description->shape = def.shape;
  description->isStatic = def.isStatic;
  description->material = resolveMaterial(def.material, m_data->settings.contact.defaultMaterial);
  description->continuousCollision = def.continuousCollision;
  description->collides = def.collides;
  description->collisionFilter = def.collisionFilter;
  if (description->material.restitution > 1.0 || description->material.restitution < 0.0 ||
      description->material.friction < 0.0 ||
      description->material.staticCoefficient() < description->material.friction)
    return Error{where + "restitution must be in [0, 1], friction >= 0 and static friction >= friction"};

  BodyDynamics dynamics;
  dynamics.linearDamping = linearDamping;
  dynamics.angularDamping = angularDamping;
  Vec3 centerOfMass = Vec3::Zero();
  Mat3 principal = Mat3::Identity();  // columns: principal axes in the shape frame
  if (isStaticOnlyShape(def.shape)) {
    dynamics.mass = 0.0;  // a half-space or a surface has no finite mass
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
  if (!m_data->freeSlots.empty()) {
    const auto lowest = std::min_element(m_data->freeSlots.begin(), m_data->freeSlots.end());
    slot = *lowest;
    m_data->freeSlots.erase(lowest);
  } else {
    slot = static_cast<int32_t>(m_data->slots.size());
    m_data->slots.push_back({});
  }
  m_data->slots[static_cast<size_t>(slot)].denseIndex = static_cast<int32_t>(m_data->bodies.size());
  const BodyId id{slot + 1, m_data->slots[static_cast<size_t>(slot)].generation, m_data->tag};
  body.setSerial(++m_data->lastSerial);
  m_data->idByName.emplace(def.name, id);
  if (body.description().collider) ++m_data->collidingBodies;
  if (def.continuousCollision && !def.isStatic) ++m_data->continuousBodies;
  m_data->bodies.push_back(std::move(body));
  m_data->loads.emplace_back();
  m_data->maxSquaredSpeed = m_data->maxSquaredSpin = -1.0;  // its velocities are the caller's
  m_data->denseIds.push_back(id);
  ++m_data->revision;
  return id;
}

Expected<bool> World::removeBody(BodyId id) {
  if (const std::string why = invalidIdReason(*m_data, id); !why.empty()) return Error{"cannot remove: " + why};
  removeJointsOf(*m_data, id);
  dropExclusionsOf(*m_data, bodyRef(*m_data, id).serial());
  IdSlot& slot = m_data->slots[static_cast<size_t>(id.index - 1)];
  const auto dense = static_cast<size_t>(slot.denseIndex);
  m_data->idByName.erase(m_data->bodies[dense].name());
  if (m_data->bodies[dense].description().collider) --m_data->collidingBodies;
  if (m_data->bodies[dense].description().continuousCollision && !m_data->bodies[dense].isStatic())
    --m_data->continuousBodies;
  if (m_data->bodies[dense].isFrozen()) --m_data->frozenBodies;
  m_data->bodies.erase(m_data->bodies.begin() + static_cast<std::ptrdiff_t>(dense));
  m_data->loads.erase(m_data->loads.begin() + static_cast<std::ptrdiff_t>(dense));
  m_data->denseIds.erase(m_data->denseIds.begin() + static_cast<std::ptrdiff_t>(dense));
  for (size_t i = dense; i < m_data->denseIds.size(); ++i)
    m_data->slots[static_cast<size_t>(m_data->denseIds[i].index - 1)].denseIndex = static_cast<int32_t>(i);
  slot.denseIndex = -1;
  ++slot.generation;
  m_data->freeSlots.push_back(id.index - 1);
  ++m_data->revision;
  return true;
}

Expected<bool> World::setPairCollision(BodyId a, BodyId b, bool collide) {
  for (const BodyId id : {a, b})
    if (const std::string why = invalidIdReason(*m_data, id); !why.empty())
      return Error{"cannot filter the pair: " + why};
  if (a == b) return Error{"body '" + bodyRef(*m_data, a).name() + "' cannot be paired with itself"};
  setPairExcluded(*m_data, a, b, !collide);
  return true;
}

bool World::canCollide(BodyId a, BodyId b) const {
  for (const BodyId id : {a, b})
    if (const std::string why = invalidIdReason(*m_data, id); !why.empty()) throw std::invalid_argument(why);
  return a != b && filtersAllowPair(*m_data, denseIndexOf(*m_data, a), denseIndexOf(*m_data, b));
}

std::vector<std::pair<BodyId, BodyId>> World::excludedPairs() const {
  // Serials ascend along the dense order: a body's serial finds its index.
  const auto idOfSerial = [&](uint32_t serial) {
    const auto found = std::lower_bound(m_data->bodies.begin(), m_data->bodies.end(), serial,
                                        [](const Body& body, uint32_t s) { return static_cast<uint32_t>(body.serial()) < s; });
    return m_data->denseIds[static_cast<std::size_t>(found - m_data->bodies.begin())];
  };
  std::vector<std::pair<BodyId, BodyId>> pairs;
  pairs.reserve(m_data->excludedPairs.size());
  for (const uint64_t key : m_data->excludedPairs)
    pairs.emplace_back(idOfSerial(static_cast<uint32_t>(key >> 32)), idOfSerial(static_cast<uint32_t>(key)));
  return pairs;
}

BodyId findBodyByName(const WorldData& world, std::string_view name) {
  const auto found = world.idByName.find(std::string(name));
  return found == world.idByName.end() ? BodyId{} : found->second;
}

BodyId World::findBody(std::string_view name) const { return findBodyByName(*m_data, name); }

std::string invalidIdReason(const WorldData& world, BodyId id) {
  // The message is made only for an id that fails: a valid one (every body
  // lookup of every step) costs no string.
  const auto named = [&] {
    return "body id (index " + std::to_string(id.index) + ", generation " + std::to_string(id.generation) +
           ", world " + std::to_string(id.world) + ")";
  };
  if (id.isNull()) return "a null body id";
  if (id.world != world.tag) return named() + " is of another world";
  if (id.index < 1 || static_cast<size_t>(id.index) > world.slots.size()) return named() + " names no slot of this world";
  const IdSlot& slot = world.slots[static_cast<size_t>(id.index - 1)];
  if (slot.denseIndex < 0 || slot.generation != id.generation) return named() + " is stale: its body was removed";
  return {};
}

bool World::isValid(BodyId id) const { return invalidIdReason(*m_data, id).empty(); }

BodyView World::body(BodyId id) const {
  if (const std::string why = invalidIdReason(*m_data, id); !why.empty()) throw std::invalid_argument(why);
  return bodyAt(m_data->slots[static_cast<size_t>(id.index - 1)].denseIndex);
}

BodyView World::bodyAt(int denseIndex) const {
  const auto i = static_cast<size_t>(denseIndex);
  return BodyView(m_data->bodies[i], m_data->loads[i].active);
}

FlyingBody flying(const WorldData& world, std::size_t denseIndex) {
  const ExternalLoad& load = world.loads[denseIndex];
  return {world.bodies[denseIndex], load.active ? &load : nullptr};
}

Expected<bool> World::applyWrench(BodyId id, const Wrench& wrench) {
  if (const std::string why = invalidIdReason(*m_data, id); !why.empty()) return Error{"cannot push: " + why};
  const Body& target = bodyRef(*m_data, id);
  if (target.isStatic()) return true;  // nothing moves it
  ExternalLoad& load = m_data->loads[denseIndexOf(*m_data, id)];
  m_data->loadsSeen = true;
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
  if (const std::string why = invalidIdReason(*m_data, id); !why.empty()) return Error{"cannot set the state: " + why};
  Body& target = bodyRef(*m_data, id);
  if (!state.position.allFinite() || !state.orientation.isFinite() || state.orientation.norm() < 1e-9 ||
      !state.linearMomentum.allFinite() || !state.angularMomentum.allFinite())
    return Error{"body '" + target.name() + "': a state must be finite, its quaternion non-zero"};
  target.setState(state);
  target.wake();
  ++m_data->revision;
  m_data->maxSquaredSpeed = m_data->maxSquaredSpin = -1.0;
  return true;
}

Expected<bool> World::setBodyVelocities(BodyId id, const Vec3& linearVelocity, const Vec3& angularVelocity) {
  if (const std::string why = invalidIdReason(*m_data, id); !why.empty())
    return Error{"cannot set the velocities: " + why};
  Body& target = bodyRef(*m_data, id);
  if (!linearVelocity.allFinite() || !angularVelocity.allFinite())
    return Error{"body '" + target.name() + "': velocities must be finite"};
  if (target.isStatic() || target.isFrozen()) return true;  // held still either way
  target.setVelocities(linearVelocity, angularVelocity);
  target.wake();
  m_data->maxSquaredSpeed = m_data->maxSquaredSpin = -1.0;
  return true;
}

Expected<bool> World::setThreads(int threads) {
  if (threads < 0 || threads > kMaxThreads)
    return Error{"threads must be 0 (one per core) to " + std::to_string(kMaxThreads) + ", not " +
                 std::to_string(threads)};
  m_data->settings.threads = threads;
  return true;
}

Expected<bool> World::setBodyDamping(BodyId id, double linear, double angular) {
  if (const std::string why = invalidIdReason(*m_data, id); !why.empty()) return Error{"cannot set damping: " + why};
  Body& target = bodyRef(*m_data, id);
  if (!(std::isfinite(linear) && linear >= 0.0) || !(std::isfinite(angular) && angular >= 0.0))
    return Error{"body '" + target.name() + "': damping must be finite and not negative"};
  target.setDamping(linear, angular);
  return true;
}

Expected<bool> World::freezeBody(BodyId id, FreezeReason reason) {
  if (const std::string why = invalidIdReason(*m_data, id); !why.empty()) return Error{"cannot freeze: " + why};
  Body& frozen = bodyRef(*m_data, id);
  if (reason == FreezeReason::None) return Error{"body '" + frozen.name() + "': a freeze needs a reason"};
  if (frozen.isStatic()) return Error{"body '" + frozen.name() + "' is static: nothing to freeze"};
  if (frozen.isFrozen()) return Error{"body '" + frozen.name() + "' is frozen already"};
  frozen.setFreezeReason(reason);
  ++m_data->frozenBodies;
  frozen.holdAtLastGoodPose();
  ++m_data->revision;
  m_data->loads[denseIndexOf(*m_data, id)].clear();
  (void)removeJointsOf(*m_data, id);
  return true;
}

Vec3 World::totalLinearMomentum() const {
  Vec3 total = Vec3::Zero();
  for (const Body& body : m_data->bodies)
    if (!body.isStatic()) total += body.linearMomentum();
  return total;
}

Vec3 World::totalAngularMomentum() const {
  Vec3 total = Vec3::Zero();
  for (const Body& body : m_data->bodies)
    if (!body.isStatic()) total += body.angularMomentum() + body.position().cross(body.linearMomentum());
  return total;
}

double World::totalKineticEnergy() const {
  double total = 0.0;
  for (const Body& body : m_data->bodies)
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
  mix(&m_data->stepCount, sizeof m_data->stepCount);
  for (const Body& body : m_data->bodies) {
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

BodyId World::idOf(int denseIndex) const { return m_data->denseIds[static_cast<std::size_t>(denseIndex)]; }
int World::bodyCount() const { return static_cast<int>(m_data->denseIds.size()); }

void World::step() { stepWorld(*m_data); }

int World::contactPointCount() const {
  int count = 0;
  for (const SolvedManifold& m : m_data->contacts) count += m.pointCount;
  return count;
}

int World::sleepingBodyCount() const {
  return static_cast<int>(std::count_if(m_data->bodies.begin(), m_data->bodies.end(),
                                        [](const Body& b) { return b.isSleeping(); }));
}

Expected<bool> World::wakeUp(BodyId id) {
  if (const std::string why = invalidIdReason(*m_data, id); !why.empty()) return Error{"cannot wake: " + why};
  bodyRef(*m_data, id).wake();
  return true;
}

const std::vector<FreezeEvent>& World::freezeEvents() const { return m_data->freezeEvents; }
int World::frozenBodyCount() const { return m_data->frozenBodies; }
void World::setStateLimits(const StateLimits& limits) { m_data->settings.limits = limits; }
const std::vector<SolvedManifold>& World::contacts() const { return m_data->contacts; }
int32_t World::lastSerial() const { return m_data->lastSerial; }
void World::continueSerialsAfter(int32_t serial) { m_data->lastSerial = std::max(m_data->lastSerial, serial); }
const WorldSettings& World::settings() const { return m_data->settings; }
void World::setGravity(const Vec3& gravity) { m_data->settings.gravity = gravity; }
void World::setIntegrator(IntegratorKind kind) { m_data->settings.integrator = kind; }
int64_t World::stepCount() const { return m_data->stepCount; }
double World::time() const { return static_cast<double>(m_data->stepCount) * m_data->settings.dt; }

// Joints (world/joints.cpp).
Expected<JointId> World::createJoint(const JointDef& def) { return rbsim::createJoint(*m_data, def); }
Expected<bool> World::setJointMotor(JointId id, const JointMotor& motor) {
  return rbsim::setJointMotor(*m_data, id, motor);
}
Expected<bool> World::setJointDrive(JointId id, const JointDrive& drive) {
  return rbsim::setJointDrive(*m_data, id, drive);
}
Expected<bool> World::setJointEffort(JointId id, double effort) { return rbsim::setJointEffort(*m_data, id, effort); }
Expected<bool> World::removeJoint(JointId id) { return rbsim::removeJoint(*m_data, id); }
JointId World::findJoint(std::string_view name) const { return findJointByName(*m_data, name); }
bool World::isValid(JointId id) const { return invalidJointReason(*m_data, id).empty(); }
int World::jointCount() const { return static_cast<int>(m_data->joints.size()); }
JointId World::jointIdAt(int denseIndex) const { return m_data->jointIds[static_cast<std::size_t>(denseIndex)]; }

JointState World::jointState(JointId id) const {
  if (const std::string why = invalidJointReason(*m_data, id); !why.empty()) throw std::invalid_argument(why);
  return rbsim::jointStateAt(*m_data, m_data->jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex);
}

JointState World::jointStateAt(int denseIndex) const { return rbsim::jointStateAt(*m_data, denseIndex); }

const JointDef& World::jointDefinitionAt(int denseIndex) const {
  return m_data->joints[static_cast<std::size_t>(denseIndex)].def;
}

const JointDef& World::jointDefinition(JointId id) const {
  if (const std::string why = invalidJointReason(*m_data, id); !why.empty()) throw std::invalid_argument(why);
  return jointDefinitionAt(m_data->jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex);
}

// Snapshots (world/snapshot.cpp).
Expected<bool> World::writeSnapshot(ByteWriter& out) const { return rbsim::writeSnapshot(*m_data, out); }

Expected<std::vector<uint8_t>> World::encodeSnapshot() const {
  ByteWriter out;
  if (auto written = writeSnapshot(out); !written) return written.error();
  return out.take();
}

Expected<World> World::readSnapshot(ByteReader& in, const WorldSettings& settings) {
  if (auto header = readSnapshotHeader(in, settings); !header) return header.error();
  World world(settings);
  if (auto read = readSnapshotContents(*world.m_data, in); !read) return read.error();
  return world;
}

Expected<World> World::decodeSnapshot(std::span<const uint8_t> bytes, const WorldSettings& settings) {
  ByteReader in(bytes);
  auto world = readSnapshot(in, settings);
  if (world && in.remaining() != 0)
    return Error{"world snapshot: " + std::to_string(in.remaining()) + " unexpected bytes after the end"};
  return world;
}

}  // namespace rbsim
