#include "physics/solver/contact_solver.h"
#include "physics/solver/previous_manifold.h"
#include "physics/solver/tangent_basis.h"
#include "physics/solver/velocity_projection.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rbsim {

SolvedManifold manifoldIdentity(const BodyContact& contact, int32_t serialA, int32_t serialB) {
  SolvedManifold m;
  m.serialA = serialA;
  m.serialB = serialB;
  m.pieceA = contact.pieceA;
  m.pieceB = contact.pieceB;
  m.bodyA = contact.bodyA;
  m.bodyB = contact.bodyB;
  m.normal = contact.manifold.normal;
  m.pointCount = contact.manifold.pointCount;
  return m;
}

namespace {

double inverseOrZero(double k) { return k > 0.0 ? 1.0 / k : 0.0; }

// The inverse of the leading size × size block of k, zero elsewhere; false
// when that block is (nearly) singular.
bool invertLeadingBlock(const Mat3& k, int size, Mat3& inverse) {
  inverse.setZero();
  if (size == 1) {
    if (!(k(0, 0) > 0.0)) return false;
    inverse(0, 0) = 1.0 / k(0, 0);
    return true;
  }
  if (size == 2) {
    const double det = k(0, 0) * k(1, 1) - k(0, 1) * k(1, 0);
    if (!(det > 1e-12 * k(0, 0) * k(1, 1))) return false;
    inverse(0, 0) = k(1, 1) / det;
    inverse(1, 1) = k(0, 0) / det;
    inverse(0, 1) = -k(0, 1) / det;
    inverse(1, 0) = -k(1, 0) / det;
    return true;
  }
  const double det = k.determinant();
  if (!(det > 1e-12 * k(0, 0) * k(1, 1) * k(2, 2))) return false;
  inverse = k.inverse();
  return true;
}

constexpr int kLocalSweeps = 4;  // Gauss–Seidel passes over a manifold's points when the block solution is infeasible

}  // namespace

void ContactSolver::solve(const std::vector<BodyContact>& contacts,
                          const std::vector<PairMaterial>& materials,
                          std::vector<SolverBody>& bodies, const std::vector<int32_t>& serials,
                          const std::vector<SolvedManifold>& previous,
                          const ContactSolverSettings& settings, double dt,
                          std::vector<SolvedManifold>& result, TaskPool& pool,
                          const std::vector<int>& levels, const VelocityProjection* equalities) {
  prepare(contacts, materials, bodies, serials, previous, settings, dt, levels, pool);
  // Collisions in chains first, from the velocities after the forces: a
  // warm start would add last step's impulses, which the sweeps below may
  // take back but the pairwise pass could not.
  propagateCollisions(bodies, settings, dt, equalities);
  const bool shock = settings.shockPropagation && !levels.empty();
  batchSweeps(bodies, levels, shock && settings.velocityIterations > 0);
  if (settings.warmStarting) warmStart(bodies, pool);
  if (equalities) equalities->project(bodies);
  for (int i = 0; i < settings.velocityIterations; ++i) {
    const bool last = i == settings.velocityIterations - 1;
    if (!(shock && last)) {
      solveVelocities(bodies, false, pool);
      if (equalities) equalities->project(bodies);
      continue;
    }
    // The shock sweep corrects velocities only: its impulses belong to a
    // different system (lower bodies held still), so the accumulated
    // impulses kept for warm starting are those of the regular sweeps.
    m_saved.resize(m_constraints.size());
    for (std::size_t m = 0; m < m_constraints.size(); ++m) {
      const ManifoldConstraint& c = m_constraints[m];
      AccumulatedImpulses& saved = m_saved[m];
      for (int p = 0; p < c.pointCount; ++p) saved.normal[p] = c.points[p].normalImpulse;
      saved.tangent[0] = c.tangentImpulse[0];
      saved.tangent[1] = c.tangentImpulse[1];
      saved.twist = c.twistImpulse;
    }
    solveVelocities(bodies, true, pool);
    if (equalities) equalities->project(bodies);
    for (std::size_t m = 0; m < m_constraints.size(); ++m) {
      ManifoldConstraint& c = m_constraints[m];
      const AccumulatedImpulses& saved = m_saved[m];
      for (int p = 0; p < c.pointCount; ++p) c.points[p].normalImpulse = saved.normal[p];
      c.tangentImpulse[0] = saved.tangent[0];
      c.tangentImpulse[1] = saved.tangent[1];
      c.twistImpulse = saved.twist;
    }
  }
  solvePositions(bodies, settings.positionIterations, pool);

  result.resize(m_constraints.size());
  constexpr std::size_t kResultsPerChunk = 64;
  forEachChunk(pool, m_constraints.size(), kResultsPerChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t m = begin; m < end; ++m) result[m] = resultOf(m, contacts[m], bodies, serials, settings);
  });
}

SolvedManifold ContactSolver::resultOf(std::size_t m, const BodyContact& contact,
                                       const std::vector<SolverBody>& bodies,
                                       const std::vector<int32_t>& serials,
                                       const ContactSolverSettings& settings) const {
  const ManifoldConstraint& c = m_constraints[m];
  SolvedManifold solved = manifoldIdentity(
      contact, serials[static_cast<std::size_t>(c.bodyA)], serials[static_cast<std::size_t>(c.bodyB)]);
  const SolverBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
  const SolverBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
  solved.frictionImpulse = c.tangentImpulse[0] * c.tangent1 + c.tangentImpulse[1] * c.tangent2;
  solved.twistImpulse = c.twistImpulse;
  double totalNormal = 0.0;
  for (int p = 0; p < c.pointCount; ++p)
    totalNormal += c.points[p].normalImpulse + c.points[p].collisionImpulse;
  // Sticking: the patch does not slip (after the solve) while it carries load.
  const double slip1 = c.tangentRows[0].velocity(a.linearVelocity, a.angularVelocity,
                                                 b.linearVelocity, b.angularVelocity);
  const double slip2 = c.tangentRows[1].velocity(a.linearVelocity, a.angularVelocity,
                                                 b.linearVelocity, b.angularVelocity);
  solved.sticking = totalNormal > 0.0 &&
                    slip1 * slip1 + slip2 * slip2 < settings.stickVelocity * settings.stickVelocity;
  for (int p = 0; p < c.pointCount; ++p) {
    const PointConstraint& pc = c.points[p];
    const ContactPoint& raw = contact.manifold.points[static_cast<std::size_t>(p)];
    SolvedContactPoint& out = solved.points[p];
    out.point = 0.5 * (raw.pointA + raw.pointB);
    out.depth = pc.depth;
    out.normalImpulse = pc.normalImpulse + pc.collisionImpulse;
    out.tangentImpulse =
        totalNormal > 0.0 ? Vec3(solved.frictionImpulse * (out.normalImpulse / totalNormal)) : Vec3::Zero();
    out.relativeNormalVelocity = pc.relativeNormalVelocity;
    out.featureId = pc.featureId;
    out.sticking = solved.sticking;
  }
  return solved;
}

void ContactSolver::prepare(const std::vector<BodyContact>& contacts,
                            const std::vector<PairMaterial>& materials,
                            const std::vector<SolverBody>& bodies,
                            const std::vector<int32_t>& serials,
                            const std::vector<SolvedManifold>& previous,
                            const ContactSolverSettings& settings, double dt,
                            const std::vector<int>& levels, TaskPool& pool) {
  m_constraints.resize(contacts.size());
  // Last step's manifold of each contact: both lists are sorted by the same
  // key, so one merge walk finds them all.
  m_previousOf.resize(contacts.size());
  std::size_t previousIndex = 0;
  for (std::size_t m = 0; m < contacts.size(); ++m) {
    const BodyContact& contact = contacts[m];
    const ManifoldKey key{serials[static_cast<std::size_t>(contact.bodyA)],
                          serials[static_cast<std::size_t>(contact.bodyB)], contact.pieceA,
                          contact.pieceB};
    m_previousOf[m] = previousManifold(previous, key, previousIndex);
  }
  constexpr std::size_t kContactsPerChunk = 32;
  forEachChunk(pool, contacts.size(), kContactsPerChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t m = begin; m < end; ++m)
      prepareOne(m, contacts[m], materials[m], bodies, m_previousOf[m], settings, dt, levels);
  });
}

void ContactSolver::prepareOne(std::size_t m, const BodyContact& contact, const PairMaterial& material,
                               const std::vector<SolverBody>& bodies, const SolvedManifold* old,
                               const ContactSolverSettings& settings, double dt,
                               const std::vector<int>& levels) {
  ManifoldConstraint& c = m_constraints[m];
  c.bodyA = contact.bodyA;
  c.bodyB = contact.bodyB;
  c.normal = contact.manifold.normal;
  tangentBasis(c.normal, c.tangent1, c.tangent2);
  c.pointCount = contact.manifold.pointCount;
  const SolverBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
  const SolverBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
  c.inverseMassA = a.inverseMass;
  c.inverseMassB = b.inverseMass;

  const ShockHold hold = chooseShockHold(c, a, b, levels);
  const Vec3 centroid = setPatchRows(c, contact.manifold, a, b);
  setTiltAxes(c, contact.manifold, centroid, a, b);
  const BlockInverses inverses = setNormalBlockCoupling(c, a, b, hold);
  setPointTargets(c, contact.manifold, a, b, material.restitution,
                  settings.warmStarting ? old : nullptr, settings, dt);
  c.restitution = material.restitution;
  c.propagated = false;
  c.gap = c.pointCount > 0 ? -c.points[0].depth : 0.0;
  for (int p = 1; p < c.pointCount; ++p) c.gap = std::min(c.gap, -c.points[p].depth);
  c.blockInvertible = inverses.regular;
  c.shockBlockInvertible = inverses.shock;
  setBlockGoals(c, inverses, settings, dt);
  setFrictionPatch(c, a, b, hold, material, old, settings.warmStarting);
}

// Shock propagation: in the last sweep the body nearer the ground (fewer
// contacts from a static body) holds still, so the bodies above cannot push
// it down or sideways: weight is carried, not fought over. Returns the hold
// that changes the shock sweep's masses: none when the held body is static,
// since holding it still changes nothing.
ContactSolver::ShockHold ContactSolver::chooseShockHold(ManifoldConstraint& c, const SolverBody& a,
                                                        const SolverBody& b,
                                                        const std::vector<int>& levels) {
  c.held = ShockHold::None;
  if (!levels.empty()) {
    const int la = levels[static_cast<std::size_t>(c.bodyA)];
    const int lb = levels[static_cast<std::size_t>(c.bodyB)];
    if (la < lb) c.held = ShockHold::A;
    if (lb < la) c.held = ShockHold::B;
  }
  const bool heldIsStatic = (c.held == ShockHold::A && a.inverseMass == 0.0) ||
                            (c.held == ShockHold::B && b.inverseMass == 0.0);
  return heldIsStatic ? ShockHold::None : c.held;
}

// The patch: the normal, friction and twist rows act at the centroid of the
// points, so that friction is one impulse per manifold rather than one per
// corner (see the header). Returns the centroid.
Vec3 ContactSolver::setPatchRows(ManifoldConstraint& c, const ContactManifold& manifold,
                                 const SolverBody& a, const SolverBody& b) {
  Vec3 centroid = Vec3::Zero();
  for (int p = 0; p < c.pointCount; ++p) {
    const ContactPoint& raw = manifold.points[static_cast<std::size_t>(p)];
    centroid += 0.5 * (raw.pointA + raw.pointB);
  }
  centroid /= std::max(1, c.pointCount);
  const Vec3 rA = centroid - a.position;
  const Vec3 rB = centroid - b.position;
  const Mat3& invIA = a.inverseInertia;
  const Mat3& invIB = b.inverseInertia;
  c.normalRow.set(c.normal, rA.cross(c.normal), rB.cross(c.normal), invIA, invIB);
  c.tangentRows[0].set(c.tangent1, rA.cross(c.tangent1), rB.cross(c.tangent1), invIA, invIB);
  c.tangentRows[1].set(c.tangent2, rA.cross(c.tangent2), rB.cross(c.tangent2), invIA, invIB);
  c.twistRow.set(Vec3::Zero(), c.normal, c.normal, invIA, invIB);
  return centroid;
}

// Tilt axes: the principal axes of Σ g_i g_iᵀ, g_i = (p_i − c)×n, in the
// tangent plane. Along them the points' normal velocities decouple into the
// reduced coordinates of the normal block; an axis the points hardly spread
// along is dropped. Also sets the twist radius (the points' mean distance
// from the centroid), which the torsional friction needs.
void ContactSolver::setTiltAxes(ManifoldConstraint& c, const ContactManifold& manifold,
                                const Vec3& centroid, const SolverBody& a, const SolverBody& b) {
  Vec3 offsets[4];
  double s11 = 0.0, s12 = 0.0, s22 = 0.0;
  c.twistRadius = 0.0;
  for (int p = 0; p < c.pointCount; ++p) {
    const ContactPoint& raw = manifold.points[static_cast<std::size_t>(p)];
    const Vec3 d = 0.5 * (raw.pointA + raw.pointB) - centroid;
    c.twistRadius += d.norm();
    offsets[p] = d.cross(c.normal);
    const double g1 = offsets[p].dot(c.tangent1), g2 = offsets[p].dot(c.tangent2);
    s11 += g1 * g1;
    s12 += g1 * g2;
    s22 += g2 * g2;
  }
  c.twistRadius /= std::max(1, c.pointCount);
  const double angle = 0.5 * std::atan2(2.0 * s12, s11 - s22);
  const Vec3 axes[2] = {std::cos(angle) * c.tangent1 + std::sin(angle) * c.tangent2,
                        -std::sin(angle) * c.tangent1 + std::cos(angle) * c.tangent2};
  NormalBlock& block = c.block;
  block.size = 1;
  double largestMoment = 0.0;
  for (int k = 0; k < 2; ++k) {
    double moment = 0.0;
    for (int p = 0; p < c.pointCount; ++p)
      moment += offsets[p].dot(axes[k]) * offsets[p].dot(axes[k]);
    largestMoment = std::max(largestMoment, moment);
    // An axis the points hardly spread along (a line of points, one point)
    // carries no independent tilt.
    constexpr double kMinimumMoment = 1e-10;  // m²: points 10 µm apart
    const bool kept = moment > kMinimumMoment && moment > 1e-8 * largestMoment;
    const int slot = block.size - 1;
    if (!kept) continue;
    block.tiltMoment[slot] = moment;
    c.tiltRows[slot].set(Vec3::Zero(), axes[k], axes[k], a.inverseInertia, b.inverseInertia);
    for (int p = 0; p < c.pointCount; ++p)
      c.points[p].direction[slot + 1] = offsets[p].dot(axes[k]);
    ++block.size;
  }
  for (int slot = block.size - 1; slot < 2; ++slot) {
    block.tiltMoment[slot] = 0.0;
    c.tiltRows[slot] = VelocityRow{};
    for (int p = 0; p < c.pointCount; ++p) c.points[p].direction[slot + 1] = 0.0;
  }
}

// The normal block's effective inverse mass K over the normal and tilt rows,
// and its inverse; again with the shock sweep's held body still (the same
// matrices when nothing that moves is held). Says which of the two can be
// inverted: only those may be solved as a whole.
ContactSolver::BlockInverses ContactSolver::setNormalBlockCoupling(ManifoldConstraint& c,
                                                                   const SolverBody& a,
                                                                   const SolverBody& b,
                                                                   ShockHold hold) {
  NormalBlock& block = c.block;
  const VelocityRow* rows[3] = {&c.normalRow, &c.tiltRows[0], &c.tiltRows[1]};
  block.coupling.setZero();
  for (int i = 0; i < block.size; ++i)
    for (int j = 0; j <= i; ++j)
      block.coupling(i, j) = block.coupling(j, i) =
          rows[i]->coupling(*rows[j], a.inverseMass, b.inverseMass, true, true);
  BlockInverses inverses;
  inverses.regular = invertLeadingBlock(block.coupling, block.size, block.inverse);
  inverses.shock = inverses.regular;
  if (hold == ShockHold::None) {
    block.shockCoupling = block.coupling;
    block.shockInverse = block.inverse;
  } else {
    block.shockCoupling.setZero();
    for (int i = 0; i < block.size; ++i)
      for (int j = 0; j <= i; ++j)
        block.shockCoupling(i, j) = block.shockCoupling(j, i) =
            rows[i]->coupling(*rows[j], a.inverseMass, b.inverseMass, movesA(hold), movesB(hold));
    inverses.shock = invertLeadingBlock(block.shockCoupling, block.size, block.shockInverse);
  }
  return inverses;
}

// Per point: its share of the block (affine pressure, effective masses), the
// normal velocity the impulses aim for, the split-impulse target, and the
// normal impulse it starts from: last step's at the same feature of `old`
// (the same manifold last step; null when there was none or warm starting
// is off).
void ContactSolver::setPointTargets(ManifoldConstraint& c, const ContactManifold& manifold,
                                    const SolverBody& a, const SolverBody& b, double restitution,
                                    const SolvedManifold* old,
                                    const ContactSolverSettings& settings, double dt) {
  const NormalBlock& block = c.block;
  // Reduced velocities now (after this step's forces) and at the step start.
  const Vec3 u(c.normalRow.velocity(a.linearVelocity, a.angularVelocity, b.linearVelocity,
                                    b.angularVelocity),
               c.tiltRows[0].velocity(a.linearVelocity, a.angularVelocity, b.linearVelocity,
                                      b.angularVelocity),
               c.tiltRows[1].velocity(a.linearVelocity, a.angularVelocity, b.linearVelocity,
                                      b.angularVelocity));
  const Vec3 uStart(c.normalRow.velocity(a.startLinearVelocity, a.startAngularVelocity,
                                         b.startLinearVelocity, b.startAngularVelocity),
                    c.tiltRows[0].velocity(a.startLinearVelocity, a.startAngularVelocity,
                                           b.startLinearVelocity, b.startAngularVelocity),
                    c.tiltRows[1].velocity(a.startLinearVelocity, a.startAngularVelocity,
                                           b.startLinearVelocity, b.startAngularVelocity));
  for (int p = 0; p < c.pointCount; ++p) {
    const ContactPoint& raw = manifold.points[static_cast<std::size_t>(p)];
    PointConstraint& pc = c.points[p];
    pc.depth = raw.depth;
    pc.featureId = raw.featureId;
    pc.direction[0] = 1.0;
    const Vec3& weights = pc.direction;
    pc.pressure = Vec3(1.0 / c.pointCount, block.size > 1 ? weights[1] / block.tiltMoment[0] : 0.0,
                       block.size > 2 ? weights[2] / block.tiltMoment[1] : 0.0);
    pc.normalMass = inverseOrZero(weights.dot(block.coupling * weights));
    pc.shockNormalMass = inverseOrZero(weights.dot(block.shockCoupling * weights));
    pc.pseudoImpulse = 0.0;

    // Target normal velocity. A touching contact hit faster than the
    // threshold bounces with −e v_rel (Newton's law of restitution, as in
    // Baraff's rigid-body notes); a gap (depth < 0) may close within the
    // step but no further (speculative contact); penetration itself is left
    // to the position pass.
    const double vn = weights.dot(u);
    pc.relativeNormalVelocity = weights.dot(uStart);
    const double gap = -raw.depth;
    const bool touching = gap <= settings.touchingDistance;
    if (vn < -settings.restitutionThreshold && touching && restitution > 0.0) {
      pc.targetVelocity = -restitution * vn;
    } else {
      pc.targetVelocity = gap > 0.0 ? -gap / dt : 0.0;
    }
    // Split impulses remove a fraction of the penetration beyond the slop.
    const double error = raw.depth - settings.linearSlop;
    pc.positionTarget =
        std::min(settings.baumgarte * std::max(error, 0.0) / dt, settings.maxCorrectionVelocity);

    // A warm start carries a load over from last step; a bounce's impulse
    // is no load (the collision is over), and a chain of touching bodies
    // would take it back only over many sweeps.
    pc.normalImpulse = 0.0;
    pc.collisionImpulse = 0.0;
    if (old != nullptr) {
      for (int q = 0; q < old->pointCount; ++q) {
        if (old->points[q].featureId != raw.featureId) continue;
        const bool bounced = restitution > 0.0 &&
                             old->points[q].relativeNormalVelocity < -settings.restitutionThreshold;
        if (!bounced) pc.normalImpulse = old->points[q].normalImpulse;
        break;
      }
    }
  }
}

// The reduced goals of the block solves, u_goal = (AᵀA)⁻¹ Aᵀ t with AᵀA =
// diag(n, σ1, σ2) (least squares over the points' targets), and whether the
// block solution may be tried: K invertible and one motion meeting every
// point's target (see NormalBlock).
void ContactSolver::setBlockGoals(ManifoldConstraint& c, const BlockInverses& inverses,
                                  const ContactSolverSettings& settings, double dt) {
  NormalBlock& block = c.block;
  block.velocityGoal.setZero();
  block.positionGoal.setZero();
  for (int p = 0; p < c.pointCount; ++p) {
    const PointConstraint& pc = c.points[p];
    block.velocityGoal[0] += pc.targetVelocity;
    block.positionGoal[0] += pc.positionTarget;
    for (int k = 0; k + 1 < block.size; ++k) {
      block.velocityGoal[k + 1] += pc.direction[k + 1] * pc.targetVelocity;
      block.positionGoal[k + 1] += pc.direction[k + 1] * pc.positionTarget;
    }
  }
  block.velocityGoal[0] /= std::max(1, c.pointCount);
  block.positionGoal[0] /= std::max(1, c.pointCount);
  for (int k = 0; k + 1 < block.size; ++k) {
    block.velocityGoal[k + 1] /= block.tiltMoment[k];
    block.positionGoal[k + 1] /= block.tiltMoment[k];
  }
  // Targets count as met by one motion when the least-squares goal misses
  // none by more than a hundredth of the slop over the step (e.g. a resting
  // face whose corners are a few nanometres apart or into the ground).
  const double tolerance = 0.01 * settings.linearSlop / dt;
  const auto consistent = [&](const Vec3& goal, double PointConstraint::*target) {
    for (int p = 0; p < c.pointCount; ++p) {
      const PointConstraint& pc = c.points[p];
      const double reached = pc.direction.dot(goal);
      if (std::abs(reached - pc.*target) > tolerance) return false;
    }
    return true;
  };
  const bool velocityConsistent = consistent(block.velocityGoal, &PointConstraint::targetVelocity);
  block.velocityExact = inverses.regular && velocityConsistent;
  block.shockExact = inverses.shock && velocityConsistent;
  block.positionExact =
      inverses.regular && consistent(block.positionGoal, &PointConstraint::positionTarget);
}

// The friction patch: effective masses of the two tangent rows and the
// twist row (regular and with the shock sweep's held body still), the
// impulses they start from (last step's patch impulse, projected on this
// step's tangents), and μ: static when the patch was sticking last step.
void ContactSolver::setFrictionPatch(ManifoldConstraint& c, const SolverBody& a,
                                     const SolverBody& b, ShockHold hold,
                                     const PairMaterial& material, const SolvedManifold* old,
                                     bool warmStarting) {
  for (int k = 0; k < 2; ++k) {
    const VelocityRow& row = c.tangentRows[k];
    c.tangentMass[k] = inverseOrZero(row.coupling(row, a.inverseMass, b.inverseMass, true, true));
    c.shockTangentMass[k] = hold == ShockHold::None
                                ? c.tangentMass[k]
                                : inverseOrZero(row.coupling(row, a.inverseMass, b.inverseMass,
                                                             movesA(hold), movesB(hold)));
  }
  c.twistMass =
      inverseOrZero(c.twistRow.coupling(c.twistRow, a.inverseMass, b.inverseMass, true, true));
  c.shockTwistMass =
      hold == ShockHold::None
          ? c.twistMass
          : inverseOrZero(c.twistRow.coupling(c.twistRow, a.inverseMass, b.inverseMass,
                                              movesA(hold), movesB(hold)));
  c.tangentImpulse[0] = c.tangentImpulse[1] = 0.0;
  c.twistImpulse = 0.0;
  c.friction = material.friction;
  if (old != nullptr) {
    if (warmStarting) {
      c.tangentImpulse[0] = old->frictionImpulse.dot(c.tangent1);
      c.tangentImpulse[1] = old->frictionImpulse.dot(c.tangent2);
      c.twistImpulse = c.twistRadius > 0.0 ? old->twistImpulse : 0.0;  // a point has no torsion
    }
    if (old->sticking) c.friction = material.staticFriction;
  }
}

void ContactSolver::batchSweeps(const std::vector<SolverBody>& bodies, const std::vector<int>& levels,
                                bool shock) {
  m_moves.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) m_moves[i] = bodies[i].inverseMass > 0.0 ? 1 : 0;
  m_constraintBodies.resize(m_constraints.size());
  for (std::size_t m = 0; m < m_constraints.size(); ++m)
    m_constraintBodies[m] = {m_constraints[m].bodyA, m_constraints[m].bodyB};
  m_batcher.build(m_constraintBodies, m_moves, {}, m_sweep);
  if (!shock) return;
  // The shock sweep holds each contact's lower body still: it passes the
  // weight upwards in one sweep only if each level's contacts are solved
  // after those below them have moved it.
  m_shockStage.resize(m_constraints.size());
  for (std::size_t m = 0; m < m_constraints.size(); ++m)
    m_shockStage[m] = std::min(levels[static_cast<std::size_t>(m_constraints[m].bodyA)],
                               levels[static_cast<std::size_t>(m_constraints[m].bodyB)]);
  m_batcher.build(m_constraintBodies, m_moves, m_shockStage, m_shockSweep);
}

void ContactSolver::warmStart(std::vector<SolverBody>& bodies, TaskPool& pool) {
  sweepInBatches(m_sweep, pool, [&](std::size_t m) { warmStartOne(m_constraints[m], bodies); });
}

namespace {

// The velocities one constraint's impulses change, copied into locals and
// written back once at the end: the compiler keeps them in registers, where
// updating the bodies in place made every row re-read what the last one
// wrote (the two bodies might, for all it knows, alias the rows). A body
// that must not change (static: other threads may read it at the same time;
// held still by the shock sweep) is read and never written, and its copy
// does not move.
struct PairVelocities {
  PairVelocities(const SolverBody& a, const SolverBody& b, Vec3 SolverBody::*linearOf,
                 Vec3 SolverBody::*angularOf, bool aMoves, bool bMoves)
      : vA(a.*linearOf),
        wA(a.*angularOf),
        vB(b.*linearOf),
        wB(b.*angularOf),
        movesA(aMoves),
        movesB(bMoves) {}

  double velocity(const VelocityRow& row) const { return row.velocity(vA, wA, vB, wB); }
  // VelocityRow::apply, with the bodies that must not change left out.
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
  // The same for a row of pure rotation (tilt, twist: no linear part),
  // which a manifold's sweep meets three times: half the arithmetic.
  double rotationVelocity(const VelocityRow& row) const {
    return row.armB.dot(wB) - row.armA.dot(wA);
  }
  void applyRotation(const VelocityRow& row, double impulse) {
    if (movesA) wA -= impulse * row.responseA;
    if (movesB) wB += impulse * row.responseB;
  }
  void store(SolverBody& a, SolverBody& b, Vec3 SolverBody::*linearOf,
             Vec3 SolverBody::*angularOf) const {
    if (movesA) {
      a.*linearOf = vA;
      a.*angularOf = wA;
    }
    if (movesB) {
      b.*linearOf = vB;
      b.*angularOf = wB;
    }
  }

  Vec3 vA, wA, vB, wB;
  const bool movesA, movesB;
};

}  // namespace

void ContactSolver::warmStartOne(const ManifoldConstraint& c, std::vector<SolverBody>& bodies) const {
  if (c.propagated) return;  // its impulses are the pass's, and applied
  SolverBody& bodyA = bodies[static_cast<std::size_t>(c.bodyA)];
  SolverBody& bodyB = bodies[static_cast<std::size_t>(c.bodyB)];
  PairVelocities v(bodyA, bodyB, &SolverBody::linearVelocity, &SolverBody::angularVelocity,
                   c.inverseMassA != 0.0, c.inverseMassB != 0.0);
  double lambda[3] = {0.0, 0.0, 0.0};
  for (int p = 0; p < c.pointCount; ++p) {
    const PointConstraint& pc = c.points[p];
    lambda[0] += pc.normalImpulse;
    lambda[1] += pc.direction[1] * pc.normalImpulse;
    lambda[2] += pc.direction[2] * pc.normalImpulse;
  }
  const auto apply = [&](const VelocityRow& row, double impulse) {
    v.apply(row, impulse, c.inverseMassA, c.inverseMassB);
  };
  apply(c.normalRow, lambda[0]);
  for (int k = 0; k + 1 < c.block.size; ++k) v.applyRotation(c.tiltRows[k], lambda[k + 1]);
  apply(c.tangentRows[0], c.tangentImpulse[0]);
  apply(c.tangentRows[1], c.tangentImpulse[1]);
  if (c.twistImpulse != 0.0) v.applyRotation(c.twistRow, c.twistImpulse);
  v.store(bodyA, bodyB, &SolverBody::linearVelocity, &SolverBody::angularVelocity);
}

Vec3 ContactSolver::solveNormalBlock(ManifoldConstraint& c, const Vec3& u, bool exact, bool shock,
                                     double PointConstraint::*impulse,
                                     double PointConstraint::*target, const Vec3& goal) {
  const NormalBlock& block = c.block;
  const int n = c.pointCount;
  if (exact) {
    // The whole manifold at once: the affine pressure that meets the goal.
    Vec3 lambda = Vec3::Zero();
    for (int p = 0; p < n; ++p) {
      const PointConstraint& pc = c.points[p];
      lambda += pc.direction * (pc.*impulse);
    }
    const Vec3 delta = (shock ? block.shockInverse : block.inverse) * (goal - u);
    const Vec3 solved = lambda + delta;
    double pressures[4];
    bool feasible = true;
    for (int p = 0; p < n; ++p) {
      const PointConstraint& pc = c.points[p];
      const double x = pc.pressure.dot(solved);
      pressures[p] = x;
      feasible = feasible && x >= 0.0;
    }
    if (feasible) {
      for (int p = 0; p < n; ++p) c.points[p].*impulse = pressures[p];
      return delta;
    }
  }
  // Projected Gauss–Seidel over the points, in the reduced space: an
  // impulse δ at point i is δ a_i there and moves u by K δ a_i.
  const Mat3& coupling = shock ? block.shockCoupling : block.coupling;
  Vec3 velocity = u;
  Vec3 total = Vec3::Zero();
  for (int sweep = 0; sweep < kLocalSweeps; ++sweep) {
    for (int p = 0; p < n; ++p) {
      PointConstraint& pc = c.points[p];
      const double mass = shock ? pc.shockNormalMass : pc.normalMass;
      if (mass == 0.0) continue;
      const Vec3& weights = pc.direction;
      const double vn = weights.dot(velocity);
      const double accumulated = std::max(pc.*impulse - mass * (vn - pc.*target), 0.0);
      const double step = accumulated - pc.*impulse;
      pc.*impulse = accumulated;
      total += step * weights;
      velocity += coupling * (step * weights);
    }
  }
  return total;
}

void ContactSolver::solveVelocities(std::vector<SolverBody>& bodies, bool shock, TaskPool& pool) {
  sweepInBatches(shock ? m_shockSweep : m_sweep, pool,
        [&](std::size_t m) { solveVelocity(m_constraints[m], bodies, shock); });
}

void ContactSolver::solveVelocity(ManifoldConstraint& c, std::vector<SolverBody>& bodies, bool shock) {
  // A body the shock sweep holds still: its velocities are read, and the
  // impulses on it are dropped. A static body is treated alike (its
  // impulses would add zeros), so that contacts on the ground may share it
  // across threads.
  const bool holdA = shock && c.held == ShockHold::A;
  const bool holdB = shock && c.held == ShockHold::B;
  const bool oneSided = holdA || holdB;
  SolverBody& bodyA = bodies[static_cast<std::size_t>(c.bodyA)];
  SolverBody& bodyB = bodies[static_cast<std::size_t>(c.bodyB)];
  PairVelocities v(bodyA, bodyB, &SolverBody::linearVelocity, &SolverBody::angularVelocity,
                   !holdA && c.inverseMassA != 0.0, !holdB && c.inverseMassB != 0.0);
  const auto apply = [&](const VelocityRow& row, double impulse) {
    v.apply(row, impulse, c.inverseMassA, c.inverseMassB);
  };
  // Friction first, limited by the normal impulses of the previous
  // iteration, then the normal impulses (non-penetration has the last word).
  double totalNormal = 0.0;
  for (int p = 0; p < c.pointCount; ++p)
    totalNormal += c.points[p].normalImpulse + c.points[p].collisionImpulse;
  {
    const double* mass = oneSided ? c.shockTangentMass : c.tangentMass;
    const double old1 = c.tangentImpulse[0], old2 = c.tangentImpulse[1];
    double new1 = old1 - mass[0] * v.velocity(c.tangentRows[0]);
    double new2 = old2 - mass[1] * v.velocity(c.tangentRows[1]);
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
    apply(c.tangentRows[0], new1 - old1);
    apply(c.tangentRows[1], new2 - old2);
  }
  if (c.twistRadius > 0.0) {
    // Torsion: the patch resists spinning about the normal up to μ r Σjn
    // (nothing for a single point).
    const double spin = v.rotationVelocity(c.twistRow);
    const double limit = c.friction * c.twistRadius * totalNormal;
    const double mass = oneSided ? c.shockTwistMass : c.twistMass;
    const double accumulated = std::clamp(c.twistImpulse - mass * spin, -limit, limit);
    v.applyRotation(c.twistRow, accumulated - c.twistImpulse);
    c.twistImpulse = accumulated;
  }
  Vec3 u(v.velocity(c.normalRow), 0.0, 0.0);
  for (int k = 0; k + 1 < c.block.size; ++k) u[k + 1] = v.rotationVelocity(c.tiltRows[k]);
  const Vec3 delta = solveNormalBlock(c, u, shock ? c.block.shockExact : c.block.velocityExact,
                                      shock, &PointConstraint::normalImpulse,
                                      &PointConstraint::targetVelocity, c.block.velocityGoal);
  apply(c.normalRow, delta[0]);
  for (int k = 0; k + 1 < c.block.size; ++k) v.applyRotation(c.tiltRows[k], delta[k + 1]);
  v.store(bodyA, bodyB, &SolverBody::linearVelocity, &SolverBody::angularVelocity);
}

void ContactSolver::solvePositions(std::vector<SolverBody>& bodies, int iterations, TaskPool& pool) {
  // Pseudo-velocities that remove a fraction of the penetration beyond the
  // slop; they move positions only and are discarded after the step.
  for (int iteration = 0; iteration < iterations; ++iteration)
    sweepInBatches(m_sweep, pool, [&](std::size_t m) { solvePosition(m_constraints[m], bodies); });
}

void ContactSolver::solvePosition(ManifoldConstraint& c, std::vector<SolverBody>& bodies) {
  bool needed = false;
  for (int p = 0; p < c.pointCount; ++p)
    needed = needed || c.points[p].positionTarget > 0.0 || c.points[p].pseudoImpulse > 0.0;
  if (!needed) return;
  SolverBody& bodyA = bodies[static_cast<std::size_t>(c.bodyA)];
  SolverBody& bodyB = bodies[static_cast<std::size_t>(c.bodyB)];
  PairVelocities v(bodyA, bodyB, &SolverBody::pseudoLinear, &SolverBody::pseudoAngular,
                   c.inverseMassA != 0.0, c.inverseMassB != 0.0);
  Vec3 u(v.velocity(c.normalRow), 0.0, 0.0);
  for (int k = 0; k + 1 < c.block.size; ++k) u[k + 1] = v.rotationVelocity(c.tiltRows[k]);
  const Vec3 delta = solveNormalBlock(c, u, c.block.positionExact, false, &PointConstraint::pseudoImpulse,
                                      &PointConstraint::positionTarget, c.block.positionGoal);
  v.apply(c.normalRow, delta[0], c.inverseMassA, c.inverseMassB);
  for (int k = 0; k + 1 < c.block.size; ++k) v.applyRotation(c.tiltRows[k], delta[k + 1]);
  v.store(bodyA, bodyB, &SolverBody::pseudoLinear, &SolverBody::pseudoAngular);
}

}  // namespace rbsim
