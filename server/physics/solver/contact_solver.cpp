#include "physics/solver/contact_solver.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rbsim {

namespace {

// A tangent basis that depends only on the normal, so that friction impulses
// accumulated along t1, t2 last step still mean the same thing this step
// (warm starting needs that).
void tangentBasis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const Vec3 axis = std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : Vec3::UnitY();
  t1 = n.cross(axis).normalized();
  t2 = n.cross(t1);
}

// 1 / (1/ma + 1/mb + (rA×d)·IA⁻¹(rA×d) + (rB×d)·IB⁻¹(rB×d)): the seed's
// denominator, the inverse of the effective mass along d at the point.
double effectiveMass(const SolverBody& a, const SolverBody& b, const Vec3& rA, const Vec3& rB,
                     const Vec3& d) {
  const Vec3 rnA = rA.cross(d), rnB = rB.cross(d);
  const double k = a.inverseMass + b.inverseMass + rnA.dot(a.inverseInertia * rnA) +
                   rnB.dot(b.inverseInertia * rnB);
  return k > 0.0 ? 1.0 / k : 0.0;
}

Vec3 relativeVelocity(const SolverBody& a, const SolverBody& b, const Vec3& rA, const Vec3& rB) {
  return b.linearVelocity + b.angularVelocity.cross(rB) - a.linearVelocity -
         a.angularVelocity.cross(rA);
}

void applyImpulse(SolverBody& a, SolverBody& b, const Vec3& rA, const Vec3& rB,
                  const Vec3& impulse) {
  a.linearVelocity -= a.inverseMass * impulse;
  a.angularVelocity -= a.inverseInertia * rA.cross(impulse);
  b.linearVelocity += b.inverseMass * impulse;
  b.angularVelocity += b.inverseInertia * rB.cross(impulse);
}

double twistMass(const SolverBody& a, const SolverBody& b, const Vec3& n) {
  const double k = n.dot(a.inverseInertia * n) + n.dot(b.inverseInertia * n);
  return k > 0.0 ? 1.0 / k : 0.0;
}

// A pure angular impulse (torque impulse) on b, and its opposite on a.
void applyTwist(SolverBody& a, SolverBody& b, const Vec3& angularImpulse) {
  a.angularVelocity -= a.inverseInertia * angularImpulse;
  b.angularVelocity += b.inverseInertia * angularImpulse;
}

using ManifoldKey = std::tuple<int32_t, int32_t, int, int>;

}  // namespace

void ContactSolver::solve(const std::vector<BodyContact>& contacts,
                          const std::vector<PairMaterial>& materials,
                          std::vector<SolverBody>& bodies, const std::vector<int32_t>& serials,
                          const std::vector<SolvedManifold>& previous,
                          const ContactSolverSettings& settings, double dt,
                          std::vector<SolvedManifold>& result, const std::vector<int>& levels) {
  prepare(contacts, materials, bodies, serials, previous, settings, dt, levels);
  if (settings.warmStarting) warmStart(bodies);
  const bool shock = settings.shockPropagation && !levels.empty();
  for (int i = 0; i < settings.velocityIterations; ++i) {
    const bool last = i == settings.velocityIterations - 1;
    if (!(shock && last)) {
      solveVelocities(bodies, false);
      continue;
    }
    // The shock sweep corrects velocities only: its impulses belong to a
    // different system (lower bodies held still), so the accumulated
    // impulses kept for warm starting are those of the regular sweeps.
    const std::vector<ManifoldConstraint> accumulated = m_constraints;
    solveVelocities(bodies, true);
    m_constraints = accumulated;
  }
  solvePositions(bodies, settings, dt);

  result.clear();
  result.reserve(m_constraints.size());
  for (std::size_t m = 0; m < m_constraints.size(); ++m) {
    const ManifoldConstraint& c = m_constraints[m];
    const BodyContact& contact = contacts[m];
    SolvedManifold solved = SolvedManifold::identityOf(
        contact, serials[static_cast<std::size_t>(c.bodyA)], serials[static_cast<std::size_t>(c.bodyB)]);
    const SolverBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
    const SolverBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
    solved.frictionImpulse = c.tangentImpulse[0] * c.tangent1 + c.tangentImpulse[1] * c.tangent2;
    solved.twistImpulse = c.twistImpulse;
    double totalNormal = 0.0;
    for (int p = 0; p < c.pointCount; ++p) totalNormal += c.points[p].normalImpulse;
    // Sticking: the patch does not slip (after the solve) while it carries load.
    const Vec3 v = relativeVelocity(a, b, c.rA, c.rB);
    const double slip = (v - v.dot(c.normal) * c.normal).norm();
    solved.sticking = totalNormal > 0.0 && slip < settings.stickVelocity;
    for (int p = 0; p < c.pointCount; ++p) {
      const PointConstraint& pc = c.points[p];
      const ContactPoint& raw = contact.manifold.points[static_cast<std::size_t>(p)];
      SolvedContactPoint& out = solved.points[p];
      out.point = 0.5 * (raw.pointA + raw.pointB);
      out.depth = pc.depth;
      out.normalImpulse = pc.normalImpulse;
      out.tangentImpulse =
          totalNormal > 0.0 ? Vec3(solved.frictionImpulse * (pc.normalImpulse / totalNormal)) : Vec3::Zero();
      out.relativeNormalVelocity = pc.relativeNormalVelocity;
      out.featureId = pc.featureId;
      out.sticking = solved.sticking;
    }
    result.push_back(solved);
  }
}

void ContactSolver::prepare(const std::vector<BodyContact>& contacts,
                            const std::vector<PairMaterial>& materials,
                            const std::vector<SolverBody>& bodies,
                            const std::vector<int32_t>& serials,
                            const std::vector<SolvedManifold>& previous,
                            const ContactSolverSettings& settings, double dt,
                            const std::vector<int>& levels) {
  m_constraints.resize(contacts.size());
  std::size_t previousIndex = 0;  // both lists are sorted by the same key: merge walk
  for (std::size_t m = 0; m < contacts.size(); ++m) {
    const BodyContact& contact = contacts[m];
    const PairMaterial& material = materials[m];
    ManifoldConstraint& c = m_constraints[m];
    c.bodyA = contact.bodyA;
    c.bodyB = contact.bodyB;
    c.normal = contact.manifold.normal;
    tangentBasis(c.normal, c.tangent1, c.tangent2);
    c.pointCount = contact.manifold.pointCount;
    const SolverBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
    const SolverBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
    // Shock propagation: in the last sweep the body nearer the ground (fewer
    // contacts from a static body) holds still, so the bodies above cannot
    // push it down or sideways: weight is carried, not fought over.
    c.frozen = Frozen::None;
    if (!levels.empty()) {
      const int la = levels[static_cast<std::size_t>(c.bodyA)];
      const int lb = levels[static_cast<std::size_t>(c.bodyB)];
      if (la < lb) c.frozen = Frozen::A;
      if (lb < la) c.frozen = Frozen::B;
    }
    const SolverBody still{};  // zero inverse mass and inertia
    const SolverBody& shockA = c.frozen == Frozen::A ? still : a;
    const SolverBody& shockB = c.frozen == Frozen::B ? still : b;

    const ManifoldKey key{serials[static_cast<std::size_t>(c.bodyA)],
                          serials[static_cast<std::size_t>(c.bodyB)], contact.pieceA,
                          contact.pieceB};
    const auto keyOf = [](const SolvedManifold& s) {
      return ManifoldKey{s.serialA, s.serialB, s.pieceA, s.pieceB};
    };
    while (previousIndex < previous.size() && keyOf(previous[previousIndex]) < key) ++previousIndex;
    const SolvedManifold* old = previousIndex < previous.size() && keyOf(previous[previousIndex]) == key
                                    ? &previous[previousIndex]
                                    : nullptr;

    for (int p = 0; p < c.pointCount; ++p) {
      const ContactPoint& raw = contact.manifold.points[static_cast<std::size_t>(p)];
      PointConstraint& pc = c.points[p];
      const Vec3 point = 0.5 * (raw.pointA + raw.pointB);
      pc.rA = point - a.position;
      pc.rB = point - b.position;
      pc.depth = raw.depth;
      pc.featureId = raw.featureId;
      // A point left out of the solve keeps a zero mass: it never gets an impulse.
      const bool included = -raw.depth <= settings.speculativeDistance;
      pc.normalMass = included ? effectiveMass(a, b, pc.rA, pc.rB, c.normal) : 0.0;
      pc.shockNormalMass = included ? effectiveMass(shockA, shockB, pc.rA, pc.rB, c.normal) : 0.0;
      pc.pseudoImpulse = 0.0;

      // Target normal velocity. A gap (depth < 0) may close within the step
      // (speculative contact); a contact that will be hit this step faster
      // than the threshold bounces with −e v_rel (the seed's law of
      // restitution); penetration itself is left to the position pass.
      const double vn = relativeVelocity(a, b, pc.rA, pc.rB).dot(c.normal);
      pc.relativeNormalVelocity = (b.startLinearVelocity + b.startAngularVelocity.cross(pc.rB) -
                                   a.startLinearVelocity - a.startAngularVelocity.cross(pc.rA))
                                      .dot(c.normal);
      const double gap = -raw.depth;
      const bool hitsThisStep = gap <= 0.0 || vn * dt < -gap;
      if (vn < -settings.restitutionThreshold && hitsThisStep && material.restitution > 0.0) {
        pc.targetVelocity = -material.restitution * vn;
      } else {
        pc.targetVelocity = gap > 0.0 ? -gap / dt : 0.0;
      }

      pc.normalImpulse = 0.0;
      if (old != nullptr && included && settings.warmStarting) {
        for (int q = 0; q < old->pointCount; ++q) {
          if (old->points[q].featureId != raw.featureId) continue;
          pc.normalImpulse = old->points[q].normalImpulse;
          break;
        }
      }
    }

    // The friction patch: at the centroid of the points.
    Vec3 centroid = Vec3::Zero();
    for (int p = 0; p < c.pointCount; ++p) centroid += c.points[p].rA;
    centroid /= std::max(1, c.pointCount);  // relative to A's centre of mass
    c.rA = centroid;
    c.rB = centroid + a.position - b.position;
    c.twistRadius = 0.0;
    for (int p = 0; p < c.pointCount; ++p) c.twistRadius += (c.points[p].rA - centroid).norm();
    c.twistRadius /= std::max(1, c.pointCount);
    c.tangentMass[0] = effectiveMass(a, b, c.rA, c.rB, c.tangent1);
    c.tangentMass[1] = effectiveMass(a, b, c.rA, c.rB, c.tangent2);
    c.shockTangentMass[0] = effectiveMass(shockA, shockB, c.rA, c.rB, c.tangent1);
    c.shockTangentMass[1] = effectiveMass(shockA, shockB, c.rA, c.rB, c.tangent2);
    c.twistMass = twistMass(a, b, c.normal);
    c.shockTwistMass = twistMass(shockA, shockB, c.normal);
    c.tangentImpulse[0] = c.tangentImpulse[1] = 0.0;
    c.twistImpulse = 0.0;
    c.friction = material.friction;
    if (old != nullptr) {
      if (settings.warmStarting) {
        c.tangentImpulse[0] = old->frictionImpulse.dot(c.tangent1);
        c.tangentImpulse[1] = old->frictionImpulse.dot(c.tangent2);
        c.twistImpulse = old->twistImpulse;
      }
      if (old->sticking) c.friction = material.staticFriction;
    }
  }
}

void ContactSolver::warmStart(std::vector<SolverBody>& bodies) const {
  for (const ManifoldConstraint& c : m_constraints) {
    SolverBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
    SolverBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
    for (int p = 0; p < c.pointCount; ++p) {
      const PointConstraint& pc = c.points[p];
      applyImpulse(a, b, pc.rA, pc.rB, pc.normalImpulse * c.normal);
    }
    applyImpulse(a, b, c.rA, c.rB, c.tangentImpulse[0] * c.tangent1 + c.tangentImpulse[1] * c.tangent2);
    applyTwist(a, b, c.twistImpulse * c.normal);
  }
}

void ContactSolver::solveVelocities(std::vector<SolverBody>& bodies, bool shock) {
  SolverBody still;  // stands in for a frozen body: impulses on it go nowhere
  for (ManifoldConstraint& c : m_constraints) {
    const bool freezeA = shock && c.frozen == Frozen::A;
    const bool freezeB = shock && c.frozen == Frozen::B;
    SolverBody& realA = bodies[static_cast<std::size_t>(c.bodyA)];
    SolverBody& realB = bodies[static_cast<std::size_t>(c.bodyB)];
    if (freezeA || freezeB) {
      still = freezeA ? realA : realB;
      still.inverseMass = 0.0;
      still.inverseInertia.setZero();
    }
    SolverBody& a = freezeA ? still : realA;
    SolverBody& b = freezeB ? still : realB;
    const bool oneSided = freezeA || freezeB;

    // Friction first, limited by the normal impulses of the previous
    // iteration, then the normal impulses (non-penetration has the last word).
    double totalNormal = 0.0;
    for (int p = 0; p < c.pointCount; ++p) totalNormal += c.points[p].normalImpulse;
    {
      const Vec3 v = relativeVelocity(a, b, c.rA, c.rB);
      const double old1 = c.tangentImpulse[0], old2 = c.tangentImpulse[1];
      const double* mass = oneSided ? c.shockTangentMass : c.tangentMass;
      double new1 = old1 - mass[0] * v.dot(c.tangent1);
      double new2 = old2 - mass[1] * v.dot(c.tangent2);
      // Coulomb: the accumulated tangential impulse stays in the disc of radius μ Σjn.
      const double limit = c.friction * totalNormal;
      const double magnitude = std::sqrt(new1 * new1 + new2 * new2);
      if (magnitude > limit) {
        const double scale = magnitude > 0.0 ? limit / magnitude : 0.0;
        new1 *= scale;
        new2 *= scale;
      }
      c.tangentImpulse[0] = new1;
      c.tangentImpulse[1] = new2;
      applyImpulse(a, b, c.rA, c.rB, (new1 - old1) * c.tangent1 + (new2 - old2) * c.tangent2);
    }
    {
      // Torsion: the patch resists spinning about the normal up to μ r Σjn.
      const double spin = (b.angularVelocity - a.angularVelocity).dot(c.normal);
      const double limit = c.friction * c.twistRadius * totalNormal;
      const double mass = oneSided ? c.shockTwistMass : c.twistMass;
      const double accumulated = std::clamp(c.twistImpulse - mass * spin, -limit, limit);
      applyTwist(a, b, (accumulated - c.twistImpulse) * c.normal);
      c.twistImpulse = accumulated;
    }
    for (int p = 0; p < c.pointCount; ++p) {
      PointConstraint& pc = c.points[p];
      const double vn = relativeVelocity(a, b, pc.rA, pc.rB).dot(c.normal);
      const double mass = oneSided ? pc.shockNormalMass : pc.normalMass;
      const double accumulated = std::max(pc.normalImpulse - mass * (vn - pc.targetVelocity), 0.0);
      const double delta = accumulated - pc.normalImpulse;
      pc.normalImpulse = accumulated;
      applyImpulse(a, b, pc.rA, pc.rB, delta * c.normal);
    }
  }
}

void ContactSolver::solvePositions(std::vector<SolverBody>& bodies,
                                   const ContactSolverSettings& settings, double dt) {
  // Pseudo-velocities that remove a fraction of the penetration beyond the
  // slop; they move positions only and are discarded after the step.
  for (int iteration = 0; iteration < settings.positionIterations; ++iteration) {
    for (ManifoldConstraint& c : m_constraints) {
      SolverBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
      SolverBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
      for (int p = 0; p < c.pointCount; ++p) {
        PointConstraint& pc = c.points[p];
        const double error = pc.depth - settings.linearSlop;
        if (error <= 0.0 && pc.pseudoImpulse == 0.0) continue;
        const double bias =
            std::min(settings.baumgarte * std::max(error, 0.0) / dt, settings.maxCorrectionVelocity);
        const double vn = (b.pseudoLinear + b.pseudoAngular.cross(pc.rB) - a.pseudoLinear -
                           a.pseudoAngular.cross(pc.rA))
                              .dot(c.normal);
        const double accumulated = std::max(pc.pseudoImpulse - pc.normalMass * (vn - bias), 0.0);
        const Vec3 impulse = (accumulated - pc.pseudoImpulse) * c.normal;
        pc.pseudoImpulse = accumulated;
        a.pseudoLinear -= a.inverseMass * impulse;
        a.pseudoAngular -= a.inverseInertia * pc.rA.cross(impulse);
        b.pseudoLinear += b.inverseMass * impulse;
        b.pseudoAngular += b.inverseInertia * pc.rB.cross(impulse);
      }
    }
  }
}

}  // namespace rbsim

