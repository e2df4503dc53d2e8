#include "physics/solver/soft_step_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include "physics/solver/previous_manifold.h"
#include "physics/solver/tangent_basis.h"

namespace rbsim {

Softness softness(double hertz, double dampingRatio, double h) {
  if (hertz <= 0.0) return Softness{};
  const double omega = 2.0 * std::numbers::pi * hertz;
  const double a1 = 2.0 * dampingRatio + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return Softness{omega / a1, a2 * a3, a3};
}

namespace {

double inverseOrZero(double k) { return k > 0.0 ? 1.0 / k : 0.0; }

// An impulse along a row (VelocityRow::apply, lane by lane). A body that
// does not move has no inverse mass and no response, so its lanes keep
// their velocities (and scatter() does not write them).
inline void applyRow(LaneVec3& vA, LaneVec3& wA, LaneVec3& vB, LaneVec3& wB, const Lanes& inverseMassA,
                     const Lanes& inverseMassB, const LaneVec3& linear, const LaneVec3& responseA,
                     const LaneVec3& responseB, const Lanes& impulse) {
  addScaled(vA, -(impulse * inverseMassA), linear);
  addScaled(wA, -impulse, responseA);
  addScaled(vB, impulse * inverseMassB, linear);
  addScaled(wB, impulse, responseB);
}

}  // namespace

void SoftStepSolver::solve(const std::vector<BodyContact>& contacts,
                           const std::vector<PairMaterial>& materials,
                           std::vector<SolverBody>& bodies, const std::vector<int32_t>& serials,
                           const std::vector<SolvedManifold>& previous,
                           const ContactSolverSettings& settings, double dt,
                           std::vector<SolvedManifold>& result, TaskPool& pool) {
  const int substeps = std::max(1, settings.substeps);
  const double h = dt / substeps;
  const double inverseH = 1.0 / h;
  // Stiffer than an eighth of the sub-step rate and a tall stack's
  // one-sweep-per-sub-step Gauss–Seidel starts to ring (a 20-box tower at
  // a quarter of the rate, Box2D's cap, keeps 0.02 J of jitter; at an
  // eighth it comes to rest). Against a static body only one side moves,
  // so it may be twice as stiff (as Box2D v3 does).
  const double hertz = std::min(settings.contactHertz, 0.125 * inverseH);
  const Softness soft = softness(hertz, settings.contactDampingRatio, h);
  const Softness staticSoft = softness(2.0 * hertz, settings.contactDampingRatio, h);

  // Last step's manifold of each contact (both lists sorted by key).
  m_previousOf.resize(contacts.size());
  std::size_t cursor = 0;
  for (std::size_t m = 0; m < contacts.size(); ++m) {
    const BodyContact& contact = contacts[m];
    const ManifoldKey key{serials[static_cast<std::size_t>(contact.bodyA)],
                          serials[static_cast<std::size_t>(contact.bodyB)], contact.pieceA,
                          contact.pieceB};
    m_previousOf[m] = previousManifold(previous, key, cursor);
  }
  m_manifolds.resize(contacts.size());
  constexpr std::size_t kContactsPerChunk = 32;
  forEachChunk(pool, contacts.size(), kContactsPerChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t m = begin; m < end; ++m)
      prepareOne(m, contacts[m], materials[m], bodies, m_previousOf[m], settings, soft, staticSoft);
  });

  // The moving bodies, and the sweeps' batches.
  m_moves.assign(bodies.size(), 0);
  m_pushed.assign(bodies.size(), 0);
  m_constraintBodies.resize(m_manifolds.size());
  for (std::size_t m = 0; m < m_manifolds.size(); ++m) {
    const Manifold& c = m_manifolds[m];
    m_constraintBodies[m] = {c.bodyA, c.bodyB};
    if (c.inverseMassA > 0.0) m_moves[static_cast<std::size_t>(c.bodyA)] = 1;
    if (c.inverseMassB > 0.0) m_moves[static_cast<std::size_t>(c.bodyB)] = 1;
  }
  m_moving.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (m_moves[i]) m_moving.push_back(static_cast<int>(i));
  m_batcher.build(m_constraintBodies, m_moves, {}, m_sweep);
  packGroups();

  // Each body starts from its velocity at the step's start and gains the
  // forces' share at every sub-step.
  m_motion.resize(bodies.size());
  constexpr std::size_t kBodiesPerChunk = 256;
  const auto forEachMoving = [&](auto&& body) {
    forEachChunk(pool, m_moving.size(), kBodiesPerChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        const std::size_t i = static_cast<std::size_t>(m_moving[k]);
        body(i, bodies[i], m_motion[i]);
      }
    });
  };
  const double share = 1.0 / substeps;
  forEachMoving([&](std::size_t, SolverBody& b, Motion& motion) {
    motion.linear.setZero();
    motion.angular.setZero();
    motion.forceLinear = share * (b.linearVelocity - b.startLinearVelocity);
    motion.forceAngular = share * (b.angularVelocity - b.startAngularVelocity);
    b.linearVelocity = b.startLinearVelocity;
    b.angularVelocity = b.startAngularVelocity;
  });

  const double maxPush = settings.maxCorrectionVelocity;
  for (int s = 0; s < substeps; ++s) {
    forEachMoving([&](std::size_t, SolverBody& b, Motion& motion) {
      b.linearVelocity += motion.forceLinear;
      b.angularVelocity += motion.forceAngular;
    });
    if (settings.warmStarting) sweepGroups(pool, [&](Group& g) { warmStartGroup(g, bodies); });
    sweepGroups(pool, [&](Group& g) { solveGroup(g, bodies, true, inverseH, maxPush); });
    forEachMoving([&](std::size_t, SolverBody& b, Motion& motion) {
      motion.linear += h * b.linearVelocity;
      motion.angular += h * b.angularVelocity;
    });
    sweepGroups(pool, [&](Group& g) { solveGroup(g, bodies, false, inverseH, maxPush); });
  }
  unpackGroups();
  // Integrating the pose with velocity + pseudo over dt gives the mean
  // velocity's motion: the sub-steps' position. A body that no contact
  // pushed in any sub-step flew free; the world's integrator moves it then
  // (exactly, for RK4 under gravity), so it gets no pseudo-velocity.
  for (const Manifold& c : m_manifolds) {
    bool pushed = c.tangentTotal[0] != 0.0 || c.tangentTotal[1] != 0.0 || c.twistTotal != 0.0;
    for (int p = 0; p < c.pointCount && !pushed; ++p) pushed = c.points[p].total != 0.0;
    if (!pushed) continue;
    m_pushed[static_cast<std::size_t>(c.bodyA)] = 1;
    m_pushed[static_cast<std::size_t>(c.bodyB)] = 1;
  }
  const double inverseDt = 1.0 / dt;
  forEachMoving([&](std::size_t i, SolverBody& b, Motion& motion) {
    if (!m_pushed[i]) return;
    b.pseudoLinear = inverseDt * motion.linear - b.linearVelocity;
    b.pseudoAngular = inverseDt * motion.angular - b.angularVelocity;
  });

  result.resize(m_manifolds.size());
  constexpr std::size_t kResultsPerChunk = 64;
  forEachChunk(pool, m_manifolds.size(), kResultsPerChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t m = begin; m < end; ++m) result[m] = resultOf(m, contacts[m], bodies, serials, settings);
  });
}

void SoftStepSolver::prepareOne(std::size_t m, const BodyContact& contact, const PairMaterial& material,
                                const std::vector<SolverBody>& bodies, const SolvedManifold* old,
                                const ContactSolverSettings& settings, const Softness& soft,
                                const Softness& staticSoft) {
  Manifold& c = m_manifolds[m];
  const SolverBody& a = bodies[static_cast<std::size_t>(contact.bodyA)];
  const SolverBody& b = bodies[static_cast<std::size_t>(contact.bodyB)];
  c.bodyA = contact.bodyA;
  c.bodyB = contact.bodyB;
  c.inverseMassA = a.inverseMass;
  c.inverseMassB = b.inverseMass;
  c.normal = contact.manifold.normal;
  tangentBasis(c.normal, c.tangent1, c.tangent2);
  c.pointCount = contact.manifold.pointCount;
  c.soft = (a.inverseMass == 0.0 || b.inverseMass == 0.0) ? staticSoft : soft;
  // Warm starting: last step's impulses were summed over its sub-steps; a
  // sub-step's share is where this one starts.
  const double perSubstep = 1.0 / std::max(1, settings.substeps);
  const bool warm = settings.warmStarting && old != nullptr;

  Vec3 centroid = Vec3::Zero();
  bool matched[4] = {false, false, false, false};
  for (int p = 0; p < c.pointCount; ++p) {
    const ContactPoint& raw = contact.manifold.points[static_cast<std::size_t>(p)];
    Point& pc = c.points[p];
    const Vec3 x = 0.5 * (raw.pointA + raw.pointB);
    centroid += x;
    pc.armA = (x - a.position).cross(c.normal);
    pc.armB = (x - b.position).cross(c.normal);
    pc.responseA = a.inverseInertia * pc.armA;
    pc.responseB = b.inverseInertia * pc.armB;
    pc.normalMass = inverseOrZero(a.inverseMass + b.inverseMass + pc.armA.dot(pc.responseA) +
                                  pc.armB.dot(pc.responseB));
    pc.depth = raw.depth;
    pc.baseSeparation = -raw.depth;
    pc.featureId = raw.featureId;
    pc.relativeNormalVelocity = c.normal.dot(b.startLinearVelocity - a.startLinearVelocity) +
                                pc.armB.dot(b.startAngularVelocity) -
                                pc.armA.dot(a.startAngularVelocity);
    pc.impulse = 0.0;
    pc.total = 0.0;
    if (warm) {
      // A bounce's impulse (the sequential-impulse solver's, at a time of
      // impact) is no load: the collision is over.
      for (int q = 0; q < old->pointCount; ++q) {
        if (old->points[q].featureId != raw.featureId) continue;
        const bool bounced = material.restitution > 0.0 &&
                             old->points[q].relativeNormalVelocity < -settings.restitutionThreshold;
        if (!bounced) pc.impulse = perSubstep * old->points[q].normalImpulse;
        matched[p] = true;
        break;
      }
    }
  }
  if (warm) shareUnmatchedLoad(c, *old, matched, perSubstep, material, settings);
  centroid /= std::max(1, c.pointCount);
  c.twistRadius = 0.0;
  for (int p = 0; p < c.pointCount; ++p) {
    const ContactPoint& raw = contact.manifold.points[static_cast<std::size_t>(p)];
    c.twistRadius += (0.5 * (raw.pointA + raw.pointB) - centroid).norm();
  }
  c.twistRadius /= std::max(1, c.pointCount);

  const Vec3 rA = centroid - a.position;
  const Vec3 rB = centroid - b.position;
  c.tangentRows[0].set(c.tangent1, rA.cross(c.tangent1), rB.cross(c.tangent1), a.inverseInertia,
                       b.inverseInertia);
  c.tangentRows[1].set(c.tangent2, rA.cross(c.tangent2), rB.cross(c.tangent2), a.inverseInertia,
                       b.inverseInertia);
  c.twistRow.set(Vec3::Zero(), c.normal, c.normal, a.inverseInertia, b.inverseInertia);
  for (int k = 0; k < 2; ++k)
    c.tangentMass[k] = inverseOrZero(
        c.tangentRows[k].coupling(c.tangentRows[k], a.inverseMass, b.inverseMass, true, true));
  c.twistMass =
      inverseOrZero(c.twistRow.coupling(c.twistRow, a.inverseMass, b.inverseMass, true, true));
  c.tangentImpulse[0] = c.tangentImpulse[1] = c.twistImpulse = 0.0;
  c.tangentTotal[0] = c.tangentTotal[1] = c.twistTotal = 0.0;
  c.friction = material.friction;
  if (old != nullptr) {
    if (warm) {
      c.tangentImpulse[0] = perSubstep * old->frictionImpulse.dot(c.tangent1);
      c.tangentImpulse[1] = perSubstep * old->frictionImpulse.dot(c.tangent2);
      c.twistImpulse = c.twistRadius > 0.0 ? perSubstep * old->twistImpulse : 0.0;
    }
    if (old->sticking) c.friction = material.staticFriction;
  }
}

// A manifold's points are the clipped contact polygon cut down to four, and
// which four may change from one step to the next as the bodies settle by
// micrometres (two boxes turned against each other touch along an octagon).
// A point that starts cold there drops its share of the load for a sub-step,
// and a tall stack rocks. So the load last step's manifold carried at points
// that are gone is shared among this step's new points: the manifold starts
// from the whole load it carried.
void SoftStepSolver::shareUnmatchedLoad(Manifold& c, const SolvedManifold& old, const bool matched[4],
                                        double perSubstep, const PairMaterial& material,
                                        const ContactSolverSettings& settings) {
  double left = 0.0;  // N·s of last step's load at points that are gone
  for (int q = 0; q < old.pointCount; ++q) {
    const SolvedContactPoint& point = old.points[q];
    const bool bounced = material.restitution > 0.0 && point.relativeNormalVelocity < -settings.restitutionThreshold;
    if (bounced) return;  // a collision's impulse is no load
    bool kept = false;
    for (int p = 0; p < c.pointCount && !kept; ++p) kept = matched[p] && c.points[p].featureId == point.featureId;
    if (!kept) left += point.normalImpulse;
  }
  int unmatched = 0;
  for (int p = 0; p < c.pointCount; ++p) unmatched += matched[p] ? 0 : 1;
  if (unmatched == 0 || !(left > 0.0)) return;
  const double share = perSubstep * left / unmatched;
  for (int p = 0; p < c.pointCount; ++p)
    if (!matched[p]) c.points[p].impulse = share;
}

void SoftStepSolver::packGroups() {
  m_groups.clear();
  m_batchGroups.assign(1, 0);
  for (int b = 0; b < m_sweep.batchCount(); ++b) {
    const std::span<const int> batch = m_sweep.batch(b);
    // Manifolds of the overflow batch share bodies: one per group, in order.
    const int perGroup = m_sweep.inOrder[static_cast<std::size_t>(b)] ? 1 : kLanes;
    for (std::size_t k = 0; k < batch.size(); k += static_cast<std::size_t>(perGroup)) {
      Group& g = m_groups.emplace_back();
      g.count = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(perGroup), batch.size() - k));
      for (int lane = 0; lane < g.count; ++lane) {
        g.manifold[lane] = batch[k + static_cast<std::size_t>(lane)];
        storeLane(g, lane, m_manifolds[static_cast<std::size_t>(g.manifold[lane])]);
      }
      // Unused lanes point at the first lane's bodies: read, never written.
      for (int lane = g.count; lane < kLanes; ++lane) {
        g.bodyA[lane] = g.bodyA[0];
        g.bodyB[lane] = g.bodyB[0];
      }
    }
    m_batchGroups.push_back(static_cast<int>(m_groups.size()));
  }
}

void SoftStepSolver::storeLane(Group& g, int lane, const Manifold& c) {
  g.bodyA[lane] = c.bodyA;
  g.bodyB[lane] = c.bodyB;
  g.movesA[lane] = c.inverseMassA != 0.0;
  g.movesB[lane] = c.inverseMassB != 0.0;
  g.inverseMassA[lane] = c.inverseMassA;
  g.inverseMassB[lane] = c.inverseMassB;
  g.normal.set(lane, c.normal);
  for (int p = 0; p < c.pointCount; ++p) {
    const Point& point = c.points[p];
    PointLanes& lanes = g.points[p];
    lanes.armA.set(lane, point.armA);
    lanes.armB.set(lane, point.armB);
    lanes.responseA.set(lane, point.responseA);
    lanes.responseB.set(lane, point.responseB);
    lanes.normalMass[lane] = point.normalMass;
    lanes.baseSeparation[lane] = point.baseSeparation;
    lanes.impulse[lane] = point.impulse;
    lanes.total[lane] = 0.0;
  }
  for (int p = c.pointCount; p < 4; ++p) {  // no point: no mass, no impulse
    PointLanes& lanes = g.points[p];
    for (LaneVec3* v : {&lanes.armA, &lanes.armB, &lanes.responseA, &lanes.responseB}) v->set(lane, Vec3::Zero());
    lanes.normalMass[lane] = lanes.baseSeparation[lane] = lanes.impulse[lane] = lanes.total[lane] = 0.0;
  }
  for (int k = 0; k < 2; ++k) {
    const VelocityRow& row = c.tangentRows[k];
    g.tangent[k].set(lane, row.linear);
    g.tangentArmA[k].set(lane, row.armA);
    g.tangentArmB[k].set(lane, row.armB);
    g.tangentResponseA[k].set(lane, row.responseA);
    g.tangentResponseB[k].set(lane, row.responseB);
    g.tangentMass[k][lane] = c.tangentMass[k];
    g.tangentImpulse[k][lane] = c.tangentImpulse[k];
    g.tangentTotal[k][lane] = 0.0;
  }
  g.twistResponseA.set(lane, c.twistRow.responseA);
  g.twistResponseB.set(lane, c.twistRow.responseB);
  g.twistMass[lane] = c.twistMass;
  g.twistImpulse[lane] = c.twistImpulse;
  g.twistTotal[lane] = 0.0;
  g.friction[lane] = c.friction;
  g.twistRadius[lane] = c.twistRadius;
  g.biasRate[lane] = c.soft.biasRate;
  g.massScale[lane] = c.soft.massScale;
  g.impulseScale[lane] = c.soft.impulseScale;
}

void SoftStepSolver::unpackGroups() {
  for (const Group& g : m_groups) {
    for (int lane = 0; lane < g.count; ++lane) {
      Manifold& c = m_manifolds[static_cast<std::size_t>(g.manifold[lane])];
      for (int p = 0; p < c.pointCount; ++p) {
        c.points[p].impulse = g.points[p].impulse[lane];
        c.points[p].total = g.points[p].total[lane];
      }
      for (int k = 0; k < 2; ++k) {
        c.tangentImpulse[k] = g.tangentImpulse[k][lane];
        c.tangentTotal[k] = g.tangentTotal[k][lane];
      }
      c.twistImpulse = g.twistImpulse[lane];
      c.twistTotal = g.twistTotal[lane];
    }
  }
}

template <class Solve>
void SoftStepSolver::sweepGroups(TaskPool& pool, Solve&& solve) {
  // A batch of fewer groups than this is solved on the calling thread:
  // sharing it would cost more than it saves.
  constexpr int kSmallestShared = 12;
  constexpr std::size_t kGroupsPerTask = 4;
  for (int b = 0; b + 1 < static_cast<int>(m_batchGroups.size()); ++b) {
    const int begin = m_batchGroups[static_cast<std::size_t>(b)];
    const int end = m_batchGroups[static_cast<std::size_t>(b) + 1];
    if (m_sweep.inOrder[static_cast<std::size_t>(b)] || end - begin < kSmallestShared || pool.threadCount() == 1) {
      for (int g = begin; g < end; ++g) solve(m_groups[static_cast<std::size_t>(g)]);
      continue;
    }
    forEachChunk(pool, static_cast<std::size_t>(end - begin), kGroupsPerTask,
                 [&](std::size_t, std::size_t first, std::size_t last) {
                   for (std::size_t g = first; g < last; ++g) solve(m_groups[static_cast<std::size_t>(begin) + g]);
                 });
  }
}

SoftStepSolver::GroupVelocities SoftStepSolver::gather(const Group& g, const std::vector<SolverBody>& bodies) const {
  GroupVelocities v;
  for (int lane = 0; lane < kLanes; ++lane) {
    const SolverBody& a = bodies[static_cast<std::size_t>(g.bodyA[lane])];
    const SolverBody& b = bodies[static_cast<std::size_t>(g.bodyB[lane])];
    v.vA.set(lane, a.linearVelocity);
    v.wA.set(lane, a.angularVelocity);
    v.vB.set(lane, b.linearVelocity);
    v.wB.set(lane, b.angularVelocity);
  }
  return v;
}

// Only the used lanes' moving bodies are written: a static body (or one
// asleep) may be read by other threads at the same time.
void SoftStepSolver::scatter(const Group& g, const GroupVelocities& v, std::vector<SolverBody>& bodies) {
  for (int lane = 0; lane < g.count; ++lane) {
    if (g.movesA[lane]) {
      SolverBody& a = bodies[static_cast<std::size_t>(g.bodyA[lane])];
      a.linearVelocity = v.vA.get(lane);
      a.angularVelocity = v.wA.get(lane);
    }
    if (g.movesB[lane]) {
      SolverBody& b = bodies[static_cast<std::size_t>(g.bodyB[lane])];
      b.linearVelocity = v.vB.get(lane);
      b.angularVelocity = v.wB.get(lane);
    }
  }
}

void SoftStepSolver::warmStartGroup(Group& g, std::vector<SolverBody>& bodies) const {
  GroupVelocities v = gather(g, bodies);
  for (const PointLanes& point : g.points) applyRow(v.vA, v.wA, v.vB, v.wB, g.inverseMassA, g.inverseMassB, g.normal, point.responseA, point.responseB, point.impulse);
  for (int k = 0; k < 2; ++k)
    applyRow(v.vA, v.wA, v.vB, v.wB, g.inverseMassA, g.inverseMassB, g.tangent[k], g.tangentResponseA[k], g.tangentResponseB[k], g.tangentImpulse[k]);
  addScaled(v.wA, -g.twistImpulse, g.twistResponseA);
  addScaled(v.wB, g.twistImpulse, g.twistResponseB);
  scatter(g, v, bodies);
}

void SoftStepSolver::solveGroup(Group& g, std::vector<SolverBody>& bodies, bool useBias, double inverseH,
                                double maxPush) const {
  GroupVelocities v = gather(g, bodies);

  // Friction first, bounded by the normal impulses so far in this sub-step
  // (non-penetration has the last word): the patch's two tangential
  // impulses stay in the disc of radius μ Σλn.
  const Lanes totalNormal = g.points[0].impulse + g.points[1].impulse + g.points[2].impulse + g.points[3].impulse;
  Lanes tangential[2];
  for (int k = 0; k < 2; ++k) {
    const Lanes slip = dot(g.tangent[k], v.vB - v.vA) + dot(g.tangentArmB[k], v.wB) - dot(g.tangentArmA[k], v.wA);
    tangential[k] = g.tangentImpulse[k] - g.tangentMass[k] * slip;
  }
  const Lanes limit = g.friction * totalNormal;
  const Lanes magnitude = (tangential[0] * tangential[0] + tangential[1] * tangential[1]).sqrt();
  // magnitude > limit >= 0 where the clamp acts, so the quotient is finite there.
  const Lanes scale =
      (magnitude > limit).select(limit / magnitude.max(std::numeric_limits<double>::min()), Lanes::Ones());
  for (int k = 0; k < 2; ++k) {
    tangential[k] *= scale;
    const Lanes delta = tangential[k] - g.tangentImpulse[k];
    g.tangentImpulse[k] = tangential[k];
    applyRow(v.vA, v.wA, v.vB, v.wB, g.inverseMassA, g.inverseMassB, g.tangent[k], g.tangentResponseA[k], g.tangentResponseB[k], delta);
  }
  // Torsion: the patch resists spinning about the normal up to μ r Σλn
  // (nothing for a single point, r = 0).
  {
    const Lanes spin = dot(g.normal, v.wB) - dot(g.normal, v.wA);
    const Lanes twistLimit = g.friction * g.twistRadius * totalNormal;
    const Lanes twisted = (g.twistImpulse - g.twistMass * spin).max(-twistLimit).min(twistLimit);
    const auto twisting = g.twistRadius > 0.0;
    const Lanes delta = twisting.select(twisted - g.twistImpulse, Lanes::Zero());
    g.twistImpulse = twisting.select(twisted, g.twistImpulse);
    addScaled(v.wA, -delta, g.twistResponseA);
    addScaled(v.wB, delta, g.twistResponseB);
  }

  // The bodies' motion since the step's start moves the points' separation.
  LaneVec3 linearA, angularA, linearB, angularB;
  for (int lane = 0; lane < kLanes; ++lane) {
    if (g.movesA[lane]) {
      const Motion& motion = m_motion[static_cast<std::size_t>(g.bodyA[lane])];
      linearA.set(lane, motion.linear);
      angularA.set(lane, motion.angular);
    }
    if (g.movesB[lane]) {
      const Motion& motion = m_motion[static_cast<std::size_t>(g.bodyB[lane])];
      linearB.set(lane, motion.linear);
      angularB.set(lane, motion.angular);
    }
  }
  const Lanes approach = dot(g.normal, linearB - linearA);
  for (PointLanes& point : g.points) {
    const Lanes separation = point.baseSeparation + approach + dot(point.armB, angularB) - dot(point.armA, angularA);
    const auto speculative = separation > 0.0;
    Lanes bias = Lanes::Zero(), massScale = Lanes::Ones(), impulseScale = Lanes::Zero();
    if (useBias) {
      // Speculative: the gap may close in this sub-step, no further.
      // Penetrating: the soft spring's push-out, capped.
      bias = speculative.select(separation * inverseH, (g.biasRate * separation).max(-maxPush));
      massScale = speculative.select(Lanes::Ones(), g.massScale);
      impulseScale = speculative.select(Lanes::Zero(), g.impulseScale);
    }
    const Lanes vn = dot(g.normal, v.vB - v.vA) + dot(point.armB, v.wB) - dot(point.armA, v.wA);
    const Lanes delta = -point.normalMass * massScale * (vn + bias) - impulseScale * point.impulse;
    Lanes accumulated = (point.impulse + delta).max(0.0);
    // The relax sweep comes after the positions moved: held to a gap there
    // it would look one sub-step ahead, past the step's end in the last
    // one, and stop a body short of a collision that the next step answers
    // at its time of impact. It has no bias of a gap to take back, so it
    // leaves speculative points alone.
    if (!useBias) accumulated = speculative.select(point.impulse, accumulated);
    const Lanes applied = accumulated - point.impulse;
    point.impulse = accumulated;
    applyRow(v.vA, v.wA, v.vB, v.wB, g.inverseMassA, g.inverseMassB, g.normal, point.responseA, point.responseB, applied);
  }
  scatter(g, v, bodies);

  // The relax sweep ends a sub-step: what is accumulated now is what this
  // sub-step applied (the warm start put in the last one's).
  if (!useBias) {
    for (PointLanes& point : g.points) point.total += point.impulse;
    for (int k = 0; k < 2; ++k) g.tangentTotal[k] += g.tangentImpulse[k];
    g.twistTotal += g.twistImpulse;
  }
}

SolvedManifold SoftStepSolver::resultOf(std::size_t m, const BodyContact& contact,
                                        const std::vector<SolverBody>& bodies,
                                        const std::vector<int32_t>& serials,
                                        const ContactSolverSettings& settings) const {
  const Manifold& c = m_manifolds[m];
  SolvedManifold solved = manifoldIdentity(
      contact, serials[static_cast<std::size_t>(c.bodyA)], serials[static_cast<std::size_t>(c.bodyB)]);
  const SolverBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
  const SolverBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
  solved.frictionImpulse = c.tangentTotal[0] * c.tangent1 + c.tangentTotal[1] * c.tangent2;
  solved.twistImpulse = c.twistTotal;
  double totalNormal = 0.0;
  for (int p = 0; p < c.pointCount; ++p) totalNormal += c.points[p].total;
  const double slip1 = c.tangentRows[0].velocity(a.linearVelocity, a.angularVelocity,
                                                 b.linearVelocity, b.angularVelocity);
  const double slip2 = c.tangentRows[1].velocity(a.linearVelocity, a.angularVelocity,
                                                 b.linearVelocity, b.angularVelocity);
  solved.sticking = totalNormal > 0.0 &&
                    slip1 * slip1 + slip2 * slip2 < settings.stickVelocity * settings.stickVelocity;
  for (int p = 0; p < c.pointCount; ++p) {
    const Point& pc = c.points[p];
    const ContactPoint& raw = contact.manifold.points[static_cast<std::size_t>(p)];
    SolvedContactPoint& out = solved.points[p];
    out.point = 0.5 * (raw.pointA + raw.pointB);
    out.depth = pc.depth;
    out.normalImpulse = pc.total;
    out.tangentImpulse =
        totalNormal > 0.0 ? Vec3(solved.frictionImpulse * (pc.total / totalNormal)) : Vec3::Zero();
    out.relativeNormalVelocity = pc.relativeNormalVelocity;
    out.featureId = pc.featureId;
    out.sticking = solved.sticking;
  }
  return solved;
}

}  // namespace rbsim
