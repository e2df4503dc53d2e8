// World stepping with contact: the impulse model (velocities, contact
// impulses, positions), the penalty model (spring–damper forces) and the
// seed's backtracking, plus islands and sleeping.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

#include "physics/body/integrator.h"
#include "physics/collision/collision_detector.h"
#include "physics/collision/time_of_impact.h"
#include "physics/world/world.h"

namespace rbsim {

namespace {

// Union–find over dense body indices, for islands of bodies in contact.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t count) : m_parent(count) {
    std::iota(m_parent.begin(), m_parent.end(), 0);
  }
  int find(int i) {
    while (m_parent[static_cast<std::size_t>(i)] != i) {
      m_parent[static_cast<std::size_t>(i)] = m_parent[static_cast<std::size_t>(m_parent[static_cast<std::size_t>(i)])];
      i = m_parent[static_cast<std::size_t>(i)];
    }
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) m_parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);  // deterministic root
  }

 private:
  std::vector<int> m_parent;
};

Quaternion advanceOrientation(const Quaternion& q, const Vec3& omega, double h) {
  const Quaternion w{0.0, omega.x(), omega.y(), omega.z()};
  const Quaternion rate = w * q;
  return Quaternion{q.w + 0.5 * h * rate.w, q.x + 0.5 * h * rate.x, q.y + 0.5 * h * rate.y,
                    q.z + 0.5 * h * rate.z}
      .normalized();
}

auto manifoldKey(const SolvedManifold& m) {
  return std::make_tuple(m.serialA, m.serialB, m.pieceA, m.pieceB);
}

}  // namespace

int World::contactPointCount() const {
  int count = 0;
  for (const SolvedManifold& m : m_contacts) count += m.pointCount;
  return count;
}

int World::sleepingBodyCount() const {
  return static_cast<int>(std::count_if(m_bodies.begin(), m_bodies.end(),
                                        [](const Body& b) { return b.m_sleeping; }));
}

void World::wakeUp(BodyId id) {
  if (!isValid(id)) return;
  Body& body = this->body(id);
  body.m_sleeping = false;
  body.m_restTime = 0.0;
}

void World::findContacts() { m_detector->detect(*this); }

void World::stepImpulse() {
  const double dt = m_settings.dt;
  const ContactConfig& config = m_settings.contact;
  findContacts();
  const std::vector<BodyContact>& detected = m_detector->contacts();
  const std::size_t n = m_bodies.size();

  if (detected.empty()) {
    // Nothing touches: every body flies free, each its own island.
    for (Body& body : m_bodies) {
      if (body.m_sleeping && body.m_load.active) {
        body.m_sleeping = false;
        body.m_restTime = 0.0;
      }
    }
    integrateFree(dt, {});
    m_contacts.clear();
    if (config.sleeping) {
      std::vector<int> islandOf(n);
      std::iota(islandOf.begin(), islandOf.end(), 0);
      updateSleep(islandOf);
    }
    return;
  }

  // Islands: dynamic bodies joined by contacts. A pushed body, or one that
  // touches an awake body, wakes its whole island.
  DisjointSets islands(n);
  for (const BodyContact& c : detected) {
    if (!m_bodies[static_cast<std::size_t>(c.bodyA)].isStatic() &&
        !m_bodies[static_cast<std::size_t>(c.bodyB)].isStatic())
      islands.unite(c.bodyA, c.bodyB);
  }
  std::vector<char> islandAwake(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Body& body = m_bodies[i];
    if (!body.isStatic() && (!body.m_sleeping || body.m_load.active || !config.sleeping))
      islandAwake[static_cast<std::size_t>(islands.find(static_cast<int>(i)))] = 1;
  }
  for (std::size_t i = 0; i < n; ++i) {
    Body& body = m_bodies[i];
    if (body.m_sleeping && islandAwake[static_cast<std::size_t>(islands.find(static_cast<int>(i)))]) {
      body.m_sleeping = false;
      body.m_restTime = 0.0;
    }
  }

  // Contacts between awake bodies go to the solver; the others keep last
  // step's result (for reporting and for warm starting when they wake).
  const auto awake = [&](int i) {
    const Body& b = m_bodies[static_cast<std::size_t>(i)];
    return !b.isStatic() && !b.m_sleeping;
  };
  std::vector<BodyContact> someActive;  // filled only when some contacts sleep
  std::vector<char> inContact(n, 0);
  const bool allActive = std::all_of(detected.begin(), detected.end(), [&](const BodyContact& c) {
    return awake(c.bodyA) || awake(c.bodyB);
  });
  if (!allActive) someActive.reserve(detected.size());
  for (const BodyContact& c : detected) {
    if (!awake(c.bodyA) && !awake(c.bodyB)) continue;
    if (!allActive) someActive.push_back(c);
    inContact[static_cast<std::size_t>(c.bodyA)] = 1;
    inContact[static_cast<std::size_t>(c.bodyB)] = 1;
  }
  const std::vector<BodyContact>& active = allActive ? detected : someActive;

  // Bodies touching nothing: the world's integrator.
  integrateFree(dt, inContact);

  // Bodies in contact: forces to velocities (semi-implicit Euler), contact
  // impulses, then positions with the solved velocities plus the
  // split-impulse pseudo-velocities (which move positions only).
  std::vector<char> solving(n, 0);
  for (std::size_t i = 0; i < n; ++i) solving[i] = inContact[i] && awake(static_cast<int>(i));
  loadSolverBodies(solving, dt);
  std::vector<SolvedManifold> solved;
  solveContacts(active, config.solver, dt, solved);
  storeSolverVelocities(solving);
  advanceSolverPositions(solving, dt, true);
  for (std::size_t i = 0; i < n; ++i)
    if (solving[i] && m_bodies[i].m_load.active) m_bodies[i].m_load.clear();

  // Keep the sleeping pairs' last results, in key order.
  std::vector<SolvedManifold> kept;
  for (const BodyContact& c : detected) {
    if (awake(c.bodyA) || awake(c.bodyB)) continue;
    const auto key = std::make_tuple(m_bodies[static_cast<std::size_t>(c.bodyA)].m_serial,
                                     m_bodies[static_cast<std::size_t>(c.bodyB)].m_serial, c.pieceA, c.pieceB);
    const auto found = std::lower_bound(m_contacts.begin(), m_contacts.end(), key,
                                        [](const SolvedManifold& m, const auto& k) { return manifoldKey(m) < k; });
    if (found != m_contacts.end() && manifoldKey(*found) == key) {
      SolvedManifold copy = *found;
      copy.bodyA = c.bodyA;
      copy.bodyB = c.bodyB;
      kept.push_back(copy);
    }
  }
  if (!kept.empty()) {
    solved.insert(solved.end(), kept.begin(), kept.end());
    std::sort(solved.begin(), solved.end(),
              [](const SolvedManifold& x, const SolvedManifold& y) { return manifoldKey(x) < manifoldKey(y); });
  }
  m_contacts = std::move(solved);

  if (config.sleeping) {
    std::vector<int> islandOf(n);
    for (std::size_t i = 0; i < n; ++i) islandOf[i] = islands.find(static_cast<int>(i));
    updateSleep(islandOf);
  }
}

void World::loadSolverBodies(const std::vector<char>& solving, double h) {
  const std::size_t n = m_bodies.size();
  m_solverBodies.assign(n, SolverBody{});
  for (std::size_t i = 0; i < n; ++i) {
    const Body& body = m_bodies[i];
    SolverBody& sb = m_solverBodies[i];
    sb.position = body.m_state.position;
    if (!solving[i]) continue;
    ForceInputs inputs;
    inputs.gravity = m_settings.gravity;
    inputs.load = body.m_load.active ? &body.m_load : nullptr;
    const Wrench wrench = evaluateWrench(body.m_state, body.m_rotation, body.m_dynamics, inputs, false);
    Vec3 p = body.m_state.linearMomentum + h * wrench.force;
    Vec3 l = body.m_state.angularMomentum + h * wrench.torque;
    // Implicit damping, as in the semi-implicit integrator.
    if (body.m_dynamics.linearDamping != 0.0) p /= 1.0 + h * body.m_dynamics.linearDamping;
    if (body.m_dynamics.angularDamping != 0.0) l /= 1.0 + h * body.m_dynamics.angularDamping;
    sb.inverseMass = body.m_dynamics.inverseMass;
    sb.inverseInertia = body.m_invInertiaWorld;
    sb.startLinearVelocity = body.m_linearVelocity;
    sb.startAngularVelocity = body.m_angularVelocity;
    sb.linearVelocity = p * sb.inverseMass;
    sb.angularVelocity = sb.inverseInertia * l;
  }
}

void World::solveContacts(const std::vector<BodyContact>& active, const ContactSolverSettings& settings,
                          double h, std::vector<SolvedManifold>& solved) {
  std::vector<int32_t> serials(m_bodies.size());
  for (std::size_t i = 0; i < m_bodies.size(); ++i) serials[i] = m_bodies[i].m_serial;
  std::vector<PairMaterial> materials;
  materials.reserve(active.size());
  for (const BodyContact& c : active)
    materials.push_back(combineMaterials(m_bodies[static_cast<std::size_t>(c.bodyA)].description().material,
                                         m_bodies[static_cast<std::size_t>(c.bodyB)].description().material));
  m_solver.solve(active, materials, m_solverBodies, serials, m_contacts, settings, h, solved,
                 contactLevels(active));
}

std::vector<int> World::contactLevels(const std::vector<BodyContact>& active) const {
  // Levels: distance in contacts from a static body (for shock propagation),
  // by a breadth-first search over the contact graph. Bodies that no chain of
  // contacts joins to a static body share one level above all others.
  const std::size_t n = m_bodies.size();
  constexpr int kUnreached = 1 << 20;
  std::vector<int> levels(n, kUnreached);
  std::vector<int> start(n + 1, 0);  // adjacency in compressed rows
  for (const BodyContact& c : active) {
    ++start[static_cast<std::size_t>(c.bodyA) + 1];
    ++start[static_cast<std::size_t>(c.bodyB) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<int> neighbours(static_cast<std::size_t>(start[n]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const BodyContact& c : active) {
    neighbours[static_cast<std::size_t>(fill[static_cast<std::size_t>(c.bodyA)]++)] = c.bodyB;
    neighbours[static_cast<std::size_t>(fill[static_cast<std::size_t>(c.bodyB)]++)] = c.bodyA;
  }
  std::vector<int> queue;
  queue.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!m_bodies[i].isStatic()) continue;
    levels[i] = 0;
    queue.push_back(static_cast<int>(i));
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int body = queue[head];
    const int next = levels[static_cast<std::size_t>(body)] + 1;
    for (int k = start[static_cast<std::size_t>(body)]; k < start[static_cast<std::size_t>(body) + 1]; ++k) {
      const int other = neighbours[static_cast<std::size_t>(k)];
      if (levels[static_cast<std::size_t>(other)] != kUnreached) continue;
      levels[static_cast<std::size_t>(other)] = next;
      queue.push_back(other);
    }
  }
  return levels;
}

void World::storeSolverVelocities(const std::vector<char>& solving) {
  for (std::size_t i = 0; i < m_bodies.size(); ++i) {
    if (!solving[i]) continue;
    Body& body = m_bodies[i];
    const SolverBody& sb = m_solverBodies[i];
    // The solver worked with the inertia of the step start: L = I(t0) ω.
    body.m_state.linearMomentum = body.m_dynamics.mass * sb.linearVelocity;
    body.m_state.angularMomentum = body.inertiaWorld() * sb.angularVelocity;
  }
}

void World::advanceSolverPositions(const std::vector<char>& solving, double h, bool withPseudo) {
  for (std::size_t i = 0; i < m_bodies.size(); ++i) {
    if (!solving[i]) continue;
    Body& body = m_bodies[i];
    const SolverBody& sb = m_solverBodies[i];
    const Vec3 v = withPseudo ? Vec3(sb.linearVelocity + sb.pseudoLinear) : sb.linearVelocity;
    const Vec3 w = withPseudo ? Vec3(sb.angularVelocity + sb.pseudoAngular) : sb.angularVelocity;
    body.m_state.position += h * v;
    body.m_state.orientation = advanceOrientation(body.m_state.orientation, w, h);
    body.updateDerived();
  }
}

void World::updateSleep(const std::vector<int>& islandOf) {
  const double dt = m_settings.dt;
  const ContactConfig& config = m_settings.contact;
  const std::size_t n = m_bodies.size();
  // An island's rest time is its least restful body's.
  std::vector<double> islandRest(n, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i) {
    Body& body = m_bodies[i];
    if (body.isStatic() || body.m_sleeping) continue;
    const bool still = body.m_linearVelocity.squaredNorm() <
                           config.sleepLinearVelocity * config.sleepLinearVelocity &&
                       body.m_angularVelocity.squaredNorm() <
                           config.sleepAngularVelocity * config.sleepAngularVelocity &&
                       !body.m_load.active;
    body.m_restTime = still ? body.m_restTime + dt : 0.0;
    double& rest = islandRest[static_cast<std::size_t>(islandOf[i])];
    rest = std::min(rest, body.m_restTime);
  }
  for (std::size_t i = 0; i < n; ++i) {
    Body& body = m_bodies[i];
    if (body.isStatic() || body.m_sleeping) continue;
    if (islandRest[static_cast<std::size_t>(islandOf[i])] >= config.sleepTime) {
      body.m_sleeping = true;
      body.m_state.linearMomentum.setZero();
      body.m_state.angularMomentum.setZero();
      body.updateDerived();
    }
  }
}

}  // namespace rbsim

namespace rbsim {

double World::deepestPenetration() {
  findContacts();
  double deepest = -std::numeric_limits<double>::infinity();
  for (const BodyContact& c : m_detector->contacts())
    for (int p = 0; p < c.manifold.pointCount; ++p)
      deepest = std::max(deepest, c.manifold.points[static_cast<std::size_t>(p)].depth);
  return deepest;
}

void World::stepBacktracking() {
  // The seed's backtracking: velocities first (forces, then the impulses of
  // the contacts that touch now), then a trial move over the rest of the
  // step; if it makes bodies overlap, bisect for the time of collision (the
  // moment the closest distance is in (0, tolerance]), move there, answer the
  // collision with impulses, and go on with the rest of the step. Every body
  // takes the semi-implicit Euler step in this mode, and none sleeps.
  const double dt = m_settings.dt;
  const ContactConfig& config = m_settings.contact;
  const double tolerance = std::max(config.solver.linearSlop, 1e-6);
  constexpr double kOverlap = 1e-9;     // m: deeper than this is an overlap
  constexpr int kMaxCollisionsPerStep = 8;
  constexpr int kMaxBisections = 50;

  const std::size_t n = m_bodies.size();
  std::vector<char> dynamic(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    m_bodies[i].m_sleeping = false;
    dynamic[i] = !m_bodies[i].isStatic();
  }
  ContactSolverSettings settings = config.solver;
  settings.positionIterations = 0;          // positions are never corrected: they never overlap
  settings.speculativeDistance = tolerance;  // farther contacts are the bisection's business

  loadSolverBodies(dynamic, dt);
  for (Body& body : m_bodies) body.m_load.clear();
  std::vector<RigidState> saved(n);
  double remaining = dt;
  for (int collision = 0; collision <= kMaxCollisionsPerStep && remaining > 0.0; ++collision) {
    findContacts();
    std::vector<SolvedManifold> solved;
    solveContacts(m_detector->contacts(), settings, remaining, solved);
    m_contacts = std::move(solved);
    storeSolverVelocities(dynamic);

    for (std::size_t i = 0; i < n; ++i) saved[i] = m_bodies[i].m_state;
    const auto moveBy = [&](double h) {
      for (std::size_t i = 0; i < n; ++i)
        if (dynamic[i]) m_bodies[i].setState(saved[i]);
      advanceSolverPositions(dynamic, h, false);
    };
    moveBy(remaining);
    if (deepestPenetration() <= kOverlap || collision == kMaxCollisionsPerStep) break;

    // Bisection over [0, remaining] for the time of collision.
    double low = 0.0, high = remaining, found = 0.0;
    for (int i = 0; i < kMaxBisections; ++i) {
      const double mid = 0.5 * (low + high);
      moveBy(mid);
      const double deepest = deepestPenetration();
      if (deepest > kOverlap) {
        high = mid;
      } else {
        found = low = mid;
        if (deepest > -tolerance) break;  // the gap is in (0, tolerance]: close enough
      }
    }
    moveBy(found);
    remaining -= found;
    if (found == 0.0) {
      // Already touching and still closing after the impulses (e.g. a
      // contact outside the solver's reach): take the rest of the step.
      moveBy(remaining);
      break;
    }
  }
  if (!m_contacts.empty()) findContacts();
}

}  // namespace rbsim

namespace rbsim {

void World::applyContinuousCollision(const std::vector<RigidState>& starts) {
  const std::size_t n = m_bodies.size();
  // Swept boxes: the collider's box at the start and at the end of the step.
  const auto sweptBox = [&](std::size_t i) {
    const Body& body = m_bodies[i];
    const Aabb bounds = body.description().collider->bounds;
    const Aabb atStart =
        transformedAabb(bounds, Transform::fromPose(starts[i].position, starts[i].orientation));
    const Aabb atEnd = transformedAabb(bounds, Transform{body.m_rotation, body.m_state.position});
    return atStart.merged(atEnd).fattened(m_settings.contact.detection.margin);
  };
  for (std::size_t i = 0; i < n; ++i) {
    Body& body = m_bodies[i];
    if (!body.description().continuousCollision || body.isStatic() || body.m_sleeping ||
        body.isFrozen() || !body.description().collider)
      continue;
    const Aabb sweptI = sweptBox(i);
    Body startI = body;
    startI.setState(starts[i]);
    double earliest = 1.0;
    for (std::size_t j = 0; j < n; ++j) {
      // A frozen body is out of the simulation: nothing collides with it.
      if (j == i || !m_bodies[j].description().collider || m_bodies[j].isFrozen()) continue;
      const Collider& other = *m_bodies[j].description().collider;
      if (!other.plane && !sweptI.overlaps(sweptBox(j))) continue;
      Body startJ = m_bodies[j];
      startJ.setState(starts[j]);
      const TimeOfImpact impact =
          continuousTimeOfImpact(startI, body.m_state, startJ, m_bodies[j].m_state);
      if (impact.status == ImpactStatus::Hit && impact.fraction < earliest) earliest = impact.fraction;
    }
    if (earliest < 1.0) {
      // Back to the pose at the time of impact; the momenta stay, so the
      // contact found there next step takes the approach out.
      const Transform pose = SweptMotion::between(starts[i], body.m_state).poseAt(earliest);
      body.m_state.position = pose.translation;
      body.m_state.orientation = Quaternion::fromRotationMatrix(pose.rotation);
      body.updateDerived();
    }
  }
}

}  // namespace rbsim
