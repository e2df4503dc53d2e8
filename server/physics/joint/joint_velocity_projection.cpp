#include "physics/joint/joint_velocity_projection.h"

#include <cmath>
#include <utility>

namespace rbsim {

namespace {

// A joint this close to a bound (or past it) at the step's start is at it:
// the position projection leaves a held limit at its bound to 1e-12.
constexpr double kAtBound = 1e-9;  // m or rad

}  // namespace

JointVelocityProjection::JointVelocityProjection(const std::vector<JointLink>& links,
                                                 const std::vector<JointBody>& bodies,
                                                 std::vector<std::size_t> solverIndex)
    : m_bodies(bodies), m_solverIndex(std::move(solverIndex)) {
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    const JointSidePose a = sidePose(link, bodies, false, true);
    const JointSidePose b = sidePose(link, bodies, true, true);
    JointRow rows[kMaxJointRows];
    link.joint->rows(a, b, link.joint->basisAt(a), rows);
    for (int r = 0; r < link.joint->rowCount(); ++r)
      m_rows.push_back({link.bodyA, link.bodyB, static_cast<int>(l), rows[r]});
    if (!link.joint->hasLimit()) continue;
    const double q = link.joint->coordinate(a, b);
    const int side = q <= link.joint->limitLower() + kAtBound ? -1 : q >= link.joint->limitUpper() - kAtBound ? +1 : 0;
    if (side == 0) continue;
    Limit limit{{link.bodyA, link.bodyB, static_cast<int>(l), {}}, side};
    link.joint->limitRow(a, b, limit.row.jacobian);
    m_limits.push_back(limit);
  }
  m_inverseInertia.reserve(bodies.size());
  for (const JointBody& body : bodies) m_inverseInertia.push_back(body.startInverseInertia);
}

double JointVelocityProjection::rate(const JointSolverRow& row, const std::vector<SolverBody>& bodies) const {
  double v = 0.0;
  if (row.bodyA >= 0) {
    const SolverBody& a = bodies[m_solverIndex[static_cast<std::size_t>(row.bodyA)]];
    v += row.jacobian.linearA.dot(a.linearVelocity) + row.jacobian.angularA.dot(a.angularVelocity);
  }
  if (row.bodyB >= 0) {
    const SolverBody& b = bodies[m_solverIndex[static_cast<std::size_t>(row.bodyB)]];
    v += row.jacobian.linearB.dot(b.linearVelocity) + row.jacobian.angularB.dot(b.angularVelocity);
  }
  return v;
}

void JointVelocityProjection::push(const JointSolverRow& row, double lambda, std::vector<SolverBody>& bodies) const {
  if (row.bodyA >= 0) {
    SolverBody& a = bodies[m_solverIndex[static_cast<std::size_t>(row.bodyA)]];
    a.linearVelocity += (lambda * a.inverseMass) * row.jacobian.linearA;
    a.angularVelocity += a.inverseInertia * (lambda * row.jacobian.angularA);
  }
  if (row.bodyB >= 0) {
    SolverBody& b = bodies[m_solverIndex[static_cast<std::size_t>(row.bodyB)]];
    b.linearVelocity += (lambda * b.inverseMass) * row.jacobian.linearB;
    b.angularVelocity += b.inverseInertia * (lambda * row.jacobian.angularB);
  }
}

void JointVelocityProjection::factorFor(const std::vector<char>& active) const {
  if (m_factored && active == m_factoredActive) return;
  std::vector<JointSolverRow> rows = m_rows;
  for (std::size_t k = 0; k < m_limits.size(); ++k)
    if (active[k]) rows.push_back(m_limits[k].row);
  m_system.factor(rows, m_bodies, m_inverseInertia);
  m_factoredActive = active;
  m_factored = true;
}

void JointVelocityProjection::project(std::vector<SolverBody>& bodies) const {
  if (m_rows.empty() && m_limits.empty()) return;
  // Start from the set the last sweep ended with (all the limits at first).
  std::vector<char> active = m_factored ? m_factoredActive : std::vector<char>(m_limits.size(), 1);
  const std::vector<SolverBody> start = bodies;
  for (std::size_t round = 0; round <= m_limits.size(); ++round) {
    factorFor(active);
    std::vector<const JointSolverRow*> rows;
    for (const JointSolverRow& row : m_rows) rows.push_back(&row);
    std::vector<std::size_t> limitOf;  // per limit row, its limit
    for (std::size_t k = 0; k < m_limits.size(); ++k) {
      if (!active[k]) continue;
      rows.push_back(&m_limits[k].row);
      limitOf.push_back(k);
    }
    if (rows.empty() || !m_system.ok()) return;
    const auto count = static_cast<Eigen::Index>(rows.size());
    Eigen::VectorXd rates(count);
    for (Eigen::Index r = 0; r < count; ++r) rates[r] = rate(*rows[static_cast<std::size_t>(r)], bodies);
    const Eigen::VectorXd impulse = m_system.solve(-rates);
    // A lower bound pushes the coordinate up (λ >= 0), an upper one down:
    // a limit row that pulls is dropped and the projection made again.
    bool dropped = false;
    for (std::size_t i = 0; i < limitOf.size(); ++i) {
      const double lambda = impulse[static_cast<Eigen::Index>(m_rows.size() + i)];
      if (lambda * m_limits[limitOf[i]].side > 0.0) {
        active[limitOf[i]] = 0;
        dropped = true;
      }
    }
    if (dropped) continue;
    for (Eigen::Index r = 0; r < count; ++r) push(*rows[static_cast<std::size_t>(r)], impulse[r], bodies);
    // A dropped limit's joint may now move into it: take it back.
    bool retaken = false;
    for (std::size_t k = 0; k < m_limits.size(); ++k) {
      if (active[k] || rate(m_limits[k].row, bodies) * m_limits[k].side <= 0.0) continue;
      active[k] = 1;
      retaken = true;
    }
    if (!retaken) return;
    bodies = start;
  }
}

}  // namespace rbsim
