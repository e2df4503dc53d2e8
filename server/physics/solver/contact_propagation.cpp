// The contact solver's propagation pass: collisions in chains of touching
// bodies resolved pair by pair (see contact_solver.h). A simultaneous solve
// of Newton's cradle sends the first ball back at 3/5 of its speed and the
// other four forward at 2/5; the pairwise pass passes the whole momentum
// along, ball to ball, as the real cradle does.
#include <algorithm>
#include <cmath>

#include "physics/solver/contact_solver.h"
#include "physics/solver/velocity_projection.h"

namespace rbsim {

namespace {

// Sweeps over the chain: an impact passes at least one contact further per
// sweep, whatever the contacts' order, and every collision of e < 1 makes the
// next weaker, so few are needed; whatever approach is left after them the
// regular solve stops without a bounce.
constexpr int kPropagationSweeps = 8;
// Rounds that settle one pair again after the equalities' reply (a jointed
// body's effective mass differs from its free one by what its joints hold).
constexpr int kSettleRounds = 4;

}  // namespace

void ContactSolver::propagateCollisions(std::vector<SolverBody>& bodies,
                                        const ContactSolverSettings& settings, double dt,
                                        const VelocityProjection* equalities) {
  const auto bounces = [](const ManifoldConstraint& c) { return c.restitution > 0.0; };
  // A point's target above zero is a bounce (setPointTargets: a gap's is
  // below, a rest's zero).
  const auto colliding = [&](const ManifoldConstraint& c) {
    if (!bounces(c)) return false;
    for (int p = 0; p < c.pointCount; ++p)
      if (c.points[p].targetVelocity > 0.0) return true;
    return false;
  };
  if (std::none_of(m_constraints.begin(), m_constraints.end(), colliding)) return;

  // Is there a chain: a colliding contact with a moving body that has
  // another contact that bounces? A lone collision is the regular solve's.
  std::vector<int> touches(bodies.size(), 0);
  for (const ManifoldConstraint& c : m_constraints) {
    if (!bounces(c)) continue;
    ++touches[static_cast<std::size_t>(c.bodyA)];
    ++touches[static_cast<std::size_t>(c.bodyB)];
  }
  const auto inChain = [&](const ManifoldConstraint& c) {
    return colliding(c) && ((c.inverseMassA > 0.0 && touches[static_cast<std::size_t>(c.bodyA)] > 1) ||
                            (c.inverseMassB > 0.0 && touches[static_cast<std::size_t>(c.bodyB)] > 1));
  };
  if (std::none_of(m_constraints.begin(), m_constraints.end(), inChain)) return;

  if (equalities) equalities->project(bodies);  // the velocities the joints allow
  const double threshold = settings.restitutionThreshold;
  const auto normalVelocity = [&](const ManifoldConstraint& c) {
    const SolverBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
    const SolverBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
    return c.normalRow.velocity(a.linearVelocity, a.angularVelocity, b.linearVelocity, b.angularVelocity);
  };
  for (int sweep = 0; sweep < kPropagationSweeps; ++sweep) {
    bool any = false;
    for (std::size_t m = 0; m < m_constraints.size(); ++m) {
      ManifoldConstraint& c = m_constraints[m];
      if (!bounces(c)) continue;
      double vn = normalVelocity(c);
      if (!(vn < -threshold) || c.gap + vn * dt > 0.0) continue;  // slow, or apart at the step's end
      const double mass = c.block.coupling(0, 0) > 0.0 ? 1.0 / c.block.coupling(0, 0) : 0.0;
      if (mass == 0.0) continue;
      const double target = -c.restitution * vn;
      SolverBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
      SolverBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
      if (!c.propagated) {
        // Its warm start is dropped: a collision's impulses are its own.
        for (int p = 0; p < c.pointCount; ++p) c.points[p].normalImpulse = 0.0;
        c.tangentImpulse[0] = c.tangentImpulse[1] = 0.0;
        c.twistImpulse = 0.0;
        c.propagated = true;
      }
      // The approach it was hit with classifies it (colliding) and keeps
      // its impulse out of the next step's warm start.
      for (int p = 0; p < c.pointCount; ++p)
        c.points[p].relativeNormalVelocity = std::min(c.points[p].relativeNormalVelocity, vn);
      for (int round = 0; round < kSettleRounds; ++round) {
        // The impulse at the centroid along n spreads evenly over the points
        // (the affine pressure of a reduced impulse (λ, 0, 0)).
        const double impulse = mass * (target - vn);
        c.normalRow.apply(impulse, c.inverseMassA, c.inverseMassB, a.linearVelocity, a.angularVelocity,
                          b.linearVelocity, b.angularVelocity);
        for (int p = 0; p < c.pointCount; ++p) c.points[p].collisionImpulse += impulse / c.pointCount;
        if (equalities == nullptr) break;
        equalities->project(bodies);
        vn = normalVelocity(c);
        if (std::abs(vn - target) <= 1e-12 + 1e-9 * std::abs(target)) break;
      }
      any = true;
    }
    if (!any) break;
  }

  // The sweeps then hold the chain at rest on the velocities the pass
  // left: a contact it hit, and one whose bounce of the step's start it
  // answered already, aim for no approach (or their gap's speculative bound).
  for (ManifoldConstraint& c : m_constraints) {
    if (!bounces(c)) continue;
    bool changed = false;
    for (int p = 0; p < c.pointCount; ++p) {
      PointConstraint& pc = c.points[p];
      if (!c.propagated && !(pc.targetVelocity > 0.0)) continue;
      const double gap = -pc.depth;
      pc.targetVelocity = gap > 0.0 ? -gap / dt : 0.0;
      changed = true;
    }
    if (!changed) continue;
    BlockInverses inverses;
    inverses.regular = c.blockInvertible;
    inverses.shock = c.shockBlockInvertible;
    setBlockGoals(c, inverses, settings, dt);
  }
}

}  // namespace rbsim
