#include "physics/solver/soft_step_solver.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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

// A pair's velocities in locals, written back once (see PairVelocities in
// contact_solver.cpp: registers, no aliasing). A body that does not move
// (static, or asleep) is read and never written: other threads may read it
// at the same time.
struct Pair {
  Pair(const SolverBody& a, const SolverBody& b, bool aMoves, bool bMoves)
      : vA(a.linearVelocity), wA(a.angularVelocity), vB(b.linearVelocity), wB(b.angularVelocity),
        movesA(aMoves), movesB(bMoves) {}

  double velocity(const VelocityRow& row) const { return row.velocity(vA, wA, vB, wB); }
  void apply(const VelocityRow& row, double impulse, double inverseMassA, double inverseMassB) {
    if (movesA) {
      vA -= (impulse * inverseMassA) * row.linear;
      wA -= impulse * row.responseA;
    }
    if (movesB) {
      vB += (impulse * inverseMassB) * row.linear;
      wB += impulse * row.responseB;
    }
  }
  void applyRotation(const VelocityRow& row, double impulse) {
    if (movesA) wA -= impulse * row.responseA;
    if (movesB) wB += impulse * row.responseB;
  }
  void store(SolverBody& a, SolverBody& b) const {
    if (movesA) {
      a.linearVelocity = vA;
      a.angularVelocity = wA;
    }
    if (movesB) {
      b.linearVelocity = vB;
      b.angularVelocity = wB;
    }
  }

  Vec3 vA, wA, vB, wB;
  const bool movesA, movesB;
};

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
    if (settings.warmStarting)
      sweepInBatches(m_sweep, pool, [&](std::size_t m) { warmStartOne(m_manifolds[m], bodies); });
    sweepInBatches(m_sweep, pool, [&](std::size_t m) {
      solveOne(m_manifolds[m], bodies, true, inverseH, maxPush);
    });
    forEachMoving([&](std::size_t, SolverBody& b, Motion& motion) {
      motion.linear += h * b.linearVelocity;
      motion.angular += h * b.angularVelocity;
    });
    sweepInBatches(m_sweep, pool, [&](std::size_t m) { relaxOne(m_manifolds[m], bodies, inverseH); });
  }
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

void SoftStepSolver::warmStartOne(Manifold& c, std::vector<SolverBody>& bodies) const {
  SolverBody& bodyA = bodies[static_cast<std::size_t>(c.bodyA)];
  SolverBody& bodyB = bodies[static_cast<std::size_t>(c.bodyB)];
  Pair v(bodyA, bodyB, c.inverseMassA != 0.0, c.inverseMassB != 0.0);
  for (int p = 0; p < c.pointCount; ++p) {
    const Point& pc = c.points[p];
    const double impulse = pc.impulse;
    if (v.movesA) {
      v.vA -= (impulse * c.inverseMassA) * c.normal;
      v.wA -= impulse * pc.responseA;
    }
    if (v.movesB) {
      v.vB += (impulse * c.inverseMassB) * c.normal;
      v.wB += impulse * pc.responseB;
    }
  }
  v.apply(c.tangentRows[0], c.tangentImpulse[0], c.inverseMassA, c.inverseMassB);
  v.apply(c.tangentRows[1], c.tangentImpulse[1], c.inverseMassA, c.inverseMassB);
  if (c.twistImpulse != 0.0) v.applyRotation(c.twistRow, c.twistImpulse);
  v.store(bodyA, bodyB);
}

void SoftStepSolver::solveOne(Manifold& c, std::vector<SolverBody>& bodies, bool useBias,
                              double inverseH, double maxPush) const {
  SolverBody& bodyA = bodies[static_cast<std::size_t>(c.bodyA)];
  SolverBody& bodyB = bodies[static_cast<std::size_t>(c.bodyB)];
  Pair v(bodyA, bodyB, c.inverseMassA != 0.0, c.inverseMassB != 0.0);

  // Friction first, bounded by the normal impulses so far in this sub-step
  // (non-penetration has the last word).
  double totalNormal = 0.0;
  for (int p = 0; p < c.pointCount; ++p) totalNormal += c.points[p].impulse;
  {
    const double old1 = c.tangentImpulse[0], old2 = c.tangentImpulse[1];
    double new1 = old1 - c.tangentMass[0] * v.velocity(c.tangentRows[0]);
    double new2 = old2 - c.tangentMass[1] * v.velocity(c.tangentRows[1]);
    const double limit = c.friction * totalNormal;
    const double magnitude = std::sqrt(new1 * new1 + new2 * new2);
    if (magnitude > limit) {
      const double scale = magnitude > 0.0 ? limit / magnitude : 0.0;
      new1 *= scale;
      new2 *= scale;
    }
    c.tangentImpulse[0] = new1;
    c.tangentImpulse[1] = new2;
    v.apply(c.tangentRows[0], new1 - old1, c.inverseMassA, c.inverseMassB);
    v.apply(c.tangentRows[1], new2 - old2, c.inverseMassA, c.inverseMassB);
  }
  if (c.twistRadius > 0.0) {
    const double spin = c.twistRow.armB.dot(v.wB) - c.twistRow.armA.dot(v.wA);
    const double limit = c.friction * c.twistRadius * totalNormal;
    const double accumulated = std::clamp(c.twistImpulse - c.twistMass * spin, -limit, limit);
    v.applyRotation(c.twistRow, accumulated - c.twistImpulse);
    c.twistImpulse = accumulated;
  }

  // The bodies' motion since the step's start moves the points' separation.
  const Motion& motionA = m_motion[static_cast<std::size_t>(c.bodyA)];
  const Motion& motionB = m_motion[static_cast<std::size_t>(c.bodyB)];
  const bool movedA = c.inverseMassA != 0.0, movedB = c.inverseMassB != 0.0;
  const Vec3 zero = Vec3::Zero();
  const Vec3& linearA = movedA ? motionA.linear : zero;
  const Vec3& angularA = movedA ? motionA.angular : zero;
  const Vec3& linearB = movedB ? motionB.linear : zero;
  const Vec3& angularB = movedB ? motionB.angular : zero;
  const double approach = c.normal.dot(linearB - linearA);
  for (int p = 0; p < c.pointCount; ++p) {
    Point& pc = c.points[p];
    const double separation =
        pc.baseSeparation + approach + pc.armB.dot(angularB) - pc.armA.dot(angularA);
    double bias = 0.0, massScale = 1.0, impulseScale = 0.0;
    if (separation > 0.0) {
      // Speculative: the gap may close in this sub-step, no further. The
      // relax sweep comes after the positions moved: held to the gap there
      // it would look one sub-step ahead, past the step's end in the last
      // one, and stop a body short of a collision that the next step
      // answers at its time of impact. The relax has no bias of a gap to
      // take back, so it leaves such points alone.
      if (!useBias) continue;
      bias = separation * inverseH;
    } else if (useBias) {
      bias = std::max(c.soft.biasRate * separation, -maxPush);
      massScale = c.soft.massScale;
      impulseScale = c.soft.impulseScale;
    }
    const double vn = c.normal.dot(v.vB - v.vA) + pc.armB.dot(v.wB) - pc.armA.dot(v.wA);
    const double delta = -pc.normalMass * massScale * (vn + bias) - impulseScale * pc.impulse;
    const double accumulated = std::max(pc.impulse + delta, 0.0);
    const double applied = accumulated - pc.impulse;
    pc.impulse = accumulated;
    if (v.movesA) {
      v.vA -= (applied * c.inverseMassA) * c.normal;
      v.wA -= applied * pc.responseA;
    }
    if (v.movesB) {
      v.vB += (applied * c.inverseMassB) * c.normal;
      v.wB += applied * pc.responseB;
    }
  }
  v.store(bodyA, bodyB);

}

void SoftStepSolver::relaxOne(Manifold& c, std::vector<SolverBody>& bodies, double inverseH) const {
  solveOne(c, bodies, false, inverseH, 0.0);
  // The relax sweep ends a sub-step: what is accumulated now is what this
  // sub-step applied (the warm start put in the last one's).
  {
    for (int p = 0; p < c.pointCount; ++p) c.points[p].total += c.points[p].impulse;
    c.tangentTotal[0] += c.tangentImpulse[0];
    c.tangentTotal[1] += c.tangentImpulse[1];
    c.twistTotal += c.twistImpulse;
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
