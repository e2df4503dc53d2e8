// The impulse model's step: contacts detected at the step's start, islands
// woken, velocities after the forces, colliding contacts moved to their time
// of impact, sequential impulses (solver/contact_solver.h), positions, sleep.
#include <algorithm>
#include <iterator>
#include <memory>
#include <tuple>

#include "physics/body/body.h"
#include "physics/body/external_load.h"
#include "physics/body/integrator.h"
#include "physics/collision/collider.h"
#include "physics/math/rotation_matrix.h"
#include "physics/world/contact_detection.h"
#include "physics/solver/contact_solver.h"
#include "physics/solver/velocity_projection.h"
#include "physics/world/impacts.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

namespace rbsim {

namespace {

auto manifoldKey(const SolvedManifold& m) {
  return std::make_tuple(m.serialA, m.serialB, m.pieceA, m.pieceB);
}

bool isZero(const Vec3& v) {
  return v.x() == 0.0 && v.y() == 0.0 && v.z() == 0.0;
}

// The contacts the solver takes this step (those with an awake body) and
// the bodies it moves.
ContactStep selectContacts(const WorldData& world, const std::vector<BodyContact>& detected) {
  // Contacts with an awake body go to the solver; the others keep last
  // step's result (for reporting, and for warm starting when they wake).
  const auto awake = [&](int i) {
    const Body& b = world.bodies[static_cast<std::size_t>(i)];
    return !b.isStatic() && !b.isSleeping();
  };
  const std::size_t n = world.bodies.size();
  ContactStep step;
  step.inContact.assign(n, 0);
  const bool allActive = std::all_of(detected.begin(), detected.end(), [&](const BodyContact& c) {
    return awake(c.bodyA) || awake(c.bodyB);
  });
  if (!allActive) step.own.reserve(detected.size());
  for (const BodyContact& c : detected) {
    if (!awake(c.bodyA) && !awake(c.bodyB)) continue;
    if (!allActive) step.own.push_back(c);
    step.inContact[static_cast<std::size_t>(c.bodyA)] = 1;
    step.inContact[static_cast<std::size_t>(c.bodyB)] = 1;
  }
  step.contacts = allActive ? &detected : &step.own;
  step.solving.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    step.solving[i] = step.inContact[i] && awake(static_cast<int>(i));
  return step;
}

// The solver's bodies: velocities after the forces of h (semi-implicit
// Euler's first half); marks the fast ones. Keeps `jointed` (empty: none)
// in the step for findImpacts.
void loadSolverBodies(WorldData& world, ContactStep& step, double h, const std::vector<char>& jointed) {
  // Per body also whether any of its points may move faster than half the
  // restitution threshold (findImpacts: a pair of slower bodies cannot
  // collide). |v| + |ω| r <= sqrt(2 (|v|² + |ω|² r²)), r the collider's radius.
  const double threshold = world.settings.contact.solver.restitutionThreshold;
  const double slow2 = 0.125 * threshold * threshold;  // (threshold / 2)² / 2
  const std::size_t n = world.bodies.size();
  world.solverBodies.assign(n, SolverBody{});
  step.fast.assign(n, 0);
  step.jointed = jointed;
  forEachBody(world, [&](std::size_t i, SpeedBound&) {
    const Body& body = world.bodies[i];
    SolverBody& sb = world.solverBodies[i];
    sb.position = body.state().position;
    if (!step.solving[i]) return;
    const ForceInputs inputs = forcesOn(world, i);
    const Momenta momenta = integrateMomenta(body.state(), body.rotation(), body.dynamics(), inputs, h);
    sb.inverseMass = body.dynamics().inverseMass;
    sb.inverseInertia = body.inverseInertiaWorld();
    sb.startLinearVelocity = body.linearVelocity();
    sb.startAngularVelocity = body.angularVelocity();
    sb.linearVelocity = momenta.linear * sb.inverseMass;
    sb.angularVelocity = sb.inverseInertia * momenta.angular;
    double speed2 = sb.linearVelocity.squaredNorm();
    const double spin2 = sb.angularVelocity.squaredNorm();
    // A body without a collider (one jointed to a body in contact) is in no
    // contact: how far it turns cannot make one collide.
    if (spin2 > 0.0 && body.description().collider) {
      const double radius = colliderRadius(*body.description().collider);
      speed2 += spin2 * radius * radius;
    }
    step.fast[i] = speed2 >= slow2;
  });
  step.anyFast = std::find(step.fast.begin(), step.fast.end(), 1) != step.fast.end();
}

// A colliding contact of a jointed body, if its pair bounces: the points
// whose gap closes within the step are made touching, so that the solver
// gives them −e v_rel now rather than stopping them at the gap (which is a
// plastic collision). True when it changed the manifold.
bool speculativeBounce(const WorldData& world, BodyContact& contact) {
  const double restitution =
      combineMaterials(world.bodies[static_cast<std::size_t>(contact.bodyA)].description().material,
                       world.bodies[static_cast<std::size_t>(contact.bodyB)].description().material)
          .restitution;
  if (!(restitution > 0.0)) return false;  // plastic: the gap closes, and no further
  const double dt = world.settings.dt;
  const double threshold = world.settings.contact.solver.restitutionThreshold;
  const SolverBody& a = world.solverBodies[static_cast<std::size_t>(contact.bodyA)];
  const SolverBody& b = world.solverBodies[static_cast<std::size_t>(contact.bodyB)];
  bool changed = false;
  for (int p = 0; p < contact.manifold.pointCount; ++p) {
    ContactPoint& point = contact.manifold.points[static_cast<std::size_t>(p)];
    if (point.depth >= 0.0) continue;  // already touching
    const Vec3 x = 0.5 * (point.pointA + point.pointB);
    const Vec3 vRel = b.linearVelocity + b.angularVelocity.cross(x - b.position) -
                      a.linearVelocity - a.angularVelocity.cross(x - a.position);
    const double vn = vRel.dot(contact.manifold.normal);
    if (vn < -threshold && -point.depth + vn * dt < 0.0) {
      point.depth = 0.0;
      changed = true;
    }
  }
  return changed;
}

// Colliding contacts (world/impacts.h): each is moved to its time of
// impact, with the manifold there, and its bodies' solver data with it.
// A jointed body's flight is not free, so it has no time of impact: its
// colliding contacts bounce where they are (see speculativeBounce).
void findImpacts(WorldData& world, ContactStep& step) {
  if (!step.anyFast) return;  // a pile at rest: nothing can collide
  const double dt = world.settings.dt;
  const ContactConfig& config = world.settings.contact;
  const double threshold = config.solver.restitutionThreshold;
  ImpactSearch search;
  search.method =
      config.backtracking ? ImpactSearchMethod::Bisection : ImpactSearchMethod::RegulaFalsi;
  search.tolerance = config.solver.touchingDistance;
  search.integrator = world.settings.integrator;
  search.gravity = world.settings.gravity;
  search.detection = config.detection;

  const std::vector<BodyContact>& contacts = *step.contacts;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const BodyContact& c = contacts[k];
    if (!step.fast[static_cast<std::size_t>(c.bodyA)] && !step.fast[static_cast<std::size_t>(c.bodyB)])
      continue;
    // Cheap test first: a point approaching faster than the threshold (with
    // the velocities after the step's forces) whose gap closes within the step.
    const SolverBody& a = world.solverBodies[static_cast<std::size_t>(c.bodyA)];
    const SolverBody& b = world.solverBodies[static_cast<std::size_t>(c.bodyB)];
    bool colliding = false;
    double predictedTime = dt;  // s: when the first such gap closes at its current rate
    for (int p = 0; p < c.manifold.pointCount; ++p) {
      const ContactPoint& point = c.manifold.points[static_cast<std::size_t>(p)];
      const Vec3 x = 0.5 * (point.pointA + point.pointB);
      const Vec3 vRel = b.linearVelocity + b.angularVelocity.cross(x - b.position) -
                        a.linearVelocity - a.angularVelocity.cross(x - a.position);
      const double vn = vRel.dot(c.manifold.normal);
      if (vn < -threshold && -point.depth + vn * dt < 0.0) {
        colliding = true;
        predictedTime = std::min(predictedTime, std::max(0.0, -point.depth) / -vn);
      }
    }
    if (!colliding) continue;
    const auto isJointed = [&](int body) {
      return !step.jointed.empty() && step.jointed[static_cast<std::size_t>(body)];
    };
    if (isJointed(c.bodyA) || isJointed(c.bodyB)) {
      BodyContact bounced = c;
      if (!speculativeBounce(world, bounced)) continue;
      if (step.contacts != &step.own) {
        step.own = contacts;
        step.contacts = &step.own;
      }
      step.own[k] = bounced;
      continue;
    }
    const std::optional<Impact> impact =
        findImpact(flying(world, static_cast<std::size_t>(c.bodyA)), flying(world, static_cast<std::size_t>(c.bodyB)), c,
                   search, dt, predictedTime);
    if (!impact) continue;  // the flight curves away: a speculative contact after all
    if (step.contacts != &step.own) {
      step.own = contacts;
      step.contacts = &step.own;
    }
    if (step.impactTime.empty()) step.impactTime.assign(world.bodies.size(), -1.0);
    step.own[k].manifold = impact->manifold;
    for (const int body : {c.bodyA, c.bodyB}) {
      if (world.bodies[static_cast<std::size_t>(body)].isStatic()) continue;
      double& time = step.impactTime[static_cast<std::size_t>(body)];
      time = time < 0.0 ? impact->time : std::min(time, impact->time);
    }
  }
  if (step.impactTime.empty()) return;

  // A colliding body meets the solver as it is at its (first) time of
  // impact: position, inertia and velocities there.
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const double time = step.impactTime[i];
    if (time < 0.0) continue;
    const Body& body = world.bodies[i];
    const RigidState flight = freeFlight(flying(world, i), world.settings.integrator, world.settings.gravity, time);
    const Mat3 rotation = flight.orientation.toRotationMatrix();
    SolverBody& sb = world.solverBodies[i];
    sb.position = flight.position;
    sb.inverseInertia = rotatedDiagonal(rotation, body.dynamics().inverseInertiaBody);
    sb.linearVelocity = flight.linearMomentum * sb.inverseMass;
    sb.angularVelocity = sb.inverseInertia * flight.angularMomentum;
    sb.startLinearVelocity = sb.linearVelocity;
    sb.startAngularVelocity = sb.angularVelocity;
  }
}

// Per body: how many contacts away from a static body (shock propagation).
std::vector<int> contactLevels(const WorldData& world, const std::vector<BodyContact>& active) {
  // Levels: distance in contacts from a static body (for shock propagation),
  // by a breadth-first search over the contact graph. Bodies that no chain of
  // contacts joins to a static body share one level above all others.
  const std::size_t n = world.bodies.size();
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
    if (!world.bodies[i].isStatic()) continue;
    levels[i] = 0;
    queue.push_back(static_cast<int>(i));
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int body = queue[head];
    const int next = levels[static_cast<std::size_t>(body)] + 1;
    for (int k = start[static_cast<std::size_t>(body)];
         k < start[static_cast<std::size_t>(body) + 1]; ++k) {
      const int other = neighbours[static_cast<std::size_t>(k)];
      if (levels[static_cast<std::size_t>(other)] != kUnreached) continue;
      levels[static_cast<std::size_t>(other)] = next;
      queue.push_back(other);
    }
  }
  return levels;
}

std::vector<PairMaterial> materialsOf(const WorldData& world, const std::vector<BodyContact>& contacts) {
  std::vector<PairMaterial> materials;
  materials.reserve(contacts.size());
  for (const BodyContact& c : contacts)
    materials.push_back(
        combineMaterials(world.bodies[static_cast<std::size_t>(c.bodyA)].description().material,
                         world.bodies[static_cast<std::size_t>(c.bodyB)].description().material));
  return materials;
}

void solveBySequentialImpulses(WorldData& world, const std::vector<BodyContact>& active,
                               const std::vector<int32_t>& serials, const ContactSolverSettings& settings,
                               double h, std::vector<SolvedManifold>& solved,
                               const VelocityProjection* equalities) {
  world.solver->solve(active, materialsOf(world, active), world.solverBodies, serials, world.contacts, settings,
                      h, solved, taskPool(world), contactLevels(world, active), equalities);
}

// Per island root: 1 when the island had a collision in the step or has
// joints. Empty when no island has either (the usual case of a pile at
// rest): every contact is the soft step's.
std::vector<char> islandsForSequentialImpulses(const WorldData& world, const ContactStep& step,
                                               const std::vector<int>& islandOf) {
  const std::size_t n = world.bodies.size();
  std::vector<char> exactIsland;
  for (std::size_t i = 0; i < n; ++i) {
    const bool collides = !step.impactTime.empty() && step.impactTime[i] >= 0.0;
    const bool jointed = !step.jointed.empty() && step.jointed[i] && step.solving[i];
    if (!collides && !jointed) continue;
    if (exactIsland.empty()) exactIsland.assign(n, 0);
    exactIsland[static_cast<std::size_t>(islandOf[i])] = 1;
  }
  return exactIsland;
}

void solveContacts(WorldData& world, const ContactStep& step, const std::vector<int>& islandOf,
                   const std::vector<BodyContact>& active, const ContactSolverSettings& settings, double h,
                   std::vector<SolvedManifold>& solved, const VelocityProjection* equalities) {
  std::vector<int32_t> serials(world.bodies.size());
  for (std::size_t i = 0; i < world.bodies.size(); ++i) serials[i] = world.bodies[i].serial();
  if (settings.kind != ContactSolverKind::SoftStep) {
    solveBySequentialImpulses(world, active, serials, settings, h, solved, equalities);
    return;
  }
  // The soft step's share of the contacts: those of islands with no
  // collision in the step and no joint. The others go to sequential
  // impulses, which answer a collision at its time of impact (and a chain
  // of them pair by pair) and project joints between their sweeps. Islands
  // share no moving body, so the two solvers never touch the same one.
  const std::vector<char> exactIsland = islandsForSequentialImpulses(world, step, islandOf);
  if (exactIsland.empty()) {
    world.softSolver->solve(active, materialsOf(world, active), world.solverBodies, serials, world.contacts,
                            settings, h, solved, taskPool(world));
    return;
  }
  std::vector<BodyContact> soft, exact;
  for (const BodyContact& c : active) {
    const int moving = world.bodies[static_cast<std::size_t>(c.bodyA)].isStatic() ? c.bodyB : c.bodyA;
    const bool toExact = exactIsland[static_cast<std::size_t>(islandOf[static_cast<std::size_t>(moving)])] != 0;
    (toExact ? exact : soft).push_back(c);
  }
  std::vector<SolvedManifold> softSolved, exactSolved;
  if (!soft.empty())
    world.softSolver->solve(soft, materialsOf(world, soft), world.solverBodies, serials, world.contacts,
                            settings, h, softSolved, taskPool(world));
  if (!exact.empty()) solveBySequentialImpulses(world, exact, serials, settings, h, exactSolved, equalities);
  // Both lists keep the contacts' order, which is by key: merged, so is the result.
  solved.clear();
  solved.reserve(softSolved.size() + exactSolved.size());
  std::merge(softSolved.begin(), softSolved.end(), exactSolved.begin(), exactSolved.end(),
             std::back_inserter(solved), [](const SolvedManifold& x, const SolvedManifold& y) {
               return manifoldKey(x) < manifoldKey(y);
             });
}

// Momenta from the solved velocities and positions over h: semi-implicit
// Euler's second half, with the split-impulse pseudo-velocities; free
// flight over the rest of the step after a collision; the world's
// integrator for a body that no impulse reached. Jointed bodies are left
// to stepJointedBodies.
void integrateSolvedBodies(WorldData& world, const ContactStep& step, const std::vector<SolvedManifold>& solved,
                           double h, const std::vector<char>& jointed) {
  const IntegratorKind integrator = world.settings.integrator;
  // Bodies that some contact pushed: a contact ending the solve with no
  // impulse at all pushed nothing (its warm start was taken back).
  std::vector<char> pushed(world.bodies.size(), 0);
  for (const SolvedManifold& m : solved) {
    bool any = !isZero(m.frictionImpulse) || m.twistImpulse != 0.0;
    for (int p = 0; p < m.pointCount && !any; ++p) any = m.points[p].normalImpulse != 0.0;
    if (!any) continue;
    pushed[static_cast<std::size_t>(m.bodyA)] = 1;
    pushed[static_cast<std::size_t>(m.bodyB)] = 1;
  }
  forEachBody(world, [&](std::size_t i, SpeedBound& bound) {
    if (!step.solving[i] || (!jointed.empty() && jointed[i])) return;  // jointed: stepJointedBodies
    Body& body = world.bodies[i];
    const SolverBody& sb = world.solverBodies[i];
    const ForceInputs inputs = forcesOn(world, i);
    const bool pseudo = !isZero(sb.pseudoLinear) || !isZero(sb.pseudoAngular);
    const double impactTime = step.impactTime.empty() ? -1.0 : step.impactTime[i];
    if (impactTime >= 0.0) {
      // Free flight to the time of impact, the impulses there (momenta from
      // the solved velocities with the inertia of that moment), free flight
      // over the rest of the step.
      RigidState state = freeFlight(flying(world, i), integrator, world.settings.gravity, impactTime);
      const Mat3 rotation = state.orientation.toRotationMatrix();
      state.linearMomentum = body.dynamics().mass * sb.linearVelocity;
      state.angularMomentum =
          rotatedDiagonal(rotation, body.dynamics().inertiaBody) * sb.angularVelocity;
      if (h > impactTime)
        state = integrateStep(integrator, state, rotation, body.dynamics(), inputs, h - impactTime);
      if (pseudo)
        integratePose(state.position, state.orientation, sb.pseudoLinear, sb.pseudoAngular, h);
      body.moveTo(state);
    } else if (!pseudo && !pushed[i]) {
      // No impulse reached it (a gap that stayed open): it flew free.
      body.moveTo(integrateStep(integrator, body.state(), body.rotation(), body.dynamics(), inputs, h));
    } else {
      // The solver worked with the inertia of the step start: L = I(t0) ω.
      RigidState state = body.state();
      state.linearMomentum = body.dynamics().mass * sb.linearVelocity;
      state.angularMomentum = body.inertiaWorld() * sb.angularVelocity;
      integratePose(state.position, state.orientation, sb.linearVelocity + sb.pseudoLinear,
                    sb.angularVelocity + sb.pseudoAngular, h);
      body.moveTo(state);
    }
    bound.note(body.linearVelocity().squaredNorm(), body.angularVelocity().squaredNorm());
  });
}

// Keeps, in key order, the last results of contacts between sleeping bodies.
void keepSleepingContacts(const WorldData& world, const std::vector<BodyContact>& detected,
                          std::vector<SolvedManifold>& solved) {
  const auto asleep = [&](int i) {
    const Body& b = world.bodies[static_cast<std::size_t>(i)];
    return b.isStatic() || b.isSleeping();
  };
  std::vector<SolvedManifold> kept;
  for (const BodyContact& c : detected) {
    if (!asleep(c.bodyA) || !asleep(c.bodyB)) continue;
    const auto key =
        std::make_tuple(world.bodies[static_cast<std::size_t>(c.bodyA)].serial(),
                        world.bodies[static_cast<std::size_t>(c.bodyB)].serial(), c.pieceA, c.pieceB);
    const auto found =
        std::lower_bound(world.contacts.begin(), world.contacts.end(), key,
                         [](const SolvedManifold& m, const auto& k) { return manifoldKey(m) < k; });
    if (found != world.contacts.end() && manifoldKey(*found) == key) {
      SolvedManifold copy = *found;
      copy.bodyA = c.bodyA;
      copy.bodyB = c.bodyB;
      kept.push_back(copy);
    }
  }
  if (kept.empty()) return;
  solved.insert(solved.end(), kept.begin(), kept.end());
  std::sort(solved.begin(), solved.end(), [](const SolvedManifold& x, const SolvedManifold& y) {
    return manifoldKey(x) < manifoldKey(y);
  });
}

}  // namespace

void findContacts(WorldData& world) {
  detectContacts(*world.detector, world.bodies, world.settings, world.maxSquaredSpeed, world.maxSquaredSpin,
                 pairsLeftOut(world), taskPool(world));
}

void stepImpulse(WorldData& world) {
  const double dt = world.settings.dt;
  findContacts(world);
  // Joined and excluded pairs never reach the narrow phase (collision_filtering.cpp).
  const std::vector<BodyContact>& detected = world.detector->contacts();
  const std::vector<int> islandOf = findIslands(world, detected);
  wakeIslands(world, islandOf);
  const std::vector<char>& jointed = findJointedBodies(world);  // empty: no joint to enforce
  if (detected.empty()) {
    integrateFree(world, dt, jointed);  // nothing touches: every unjointed body flies free
    stepJointedBodies(world, jointed, {}, {}, dt);
    world.contacts.clear();
  } else {
    ContactStep step = selectContacts(world, detected);
    // A jointed island that touches something is solved with the contacts:
    // all its bodies go to the solver, and its joints' velocity rows are
    // projected between the contact sweeps.
    const VelocityProjection* jointRows = nullptr;
    if (!jointed.empty()) jointRows = addJointedIslandsInContact(world, step, jointed, islandOf);
    if (jointed.empty()) {
      integrateFree(world, dt, step.inContact);  // bodies touching nothing
    } else {
      std::vector<char> skip = step.inContact;
      for (std::size_t i = 0; i < skip.size(); ++i) skip[i] = skip[i] || jointed[i];
      integrateFree(world, dt, skip);
    }
    loadSolverBodies(world, step, dt, jointed);
    if (jointRows) actuateJointedIslandsInContact(world, step, jointed, dt);
    findImpacts(world, step);
    std::vector<SolvedManifold> solved;
    solveContacts(world, step, islandOf, *step.contacts, world.settings.contact.solver, dt, solved, jointRows);
    integrateSolvedBodies(world, step, solved, dt, jointed);
    stepJointedBodies(world, jointed, step.solving, islandOf, dt);
    keepSleepingContacts(world, detected, solved);
    world.contacts = std::move(solved);
  }
  if (world.settings.contact.sleeping) updateSleep(world, islandOf);
}

}  // namespace rbsim
