#include "physics/joint/joint_velocity_projection.h"

#include <utility>

namespace rbsim {

JointVelocityProjection::JointVelocityProjection(const std::vector<JointLink>& links,
                                                 const std::vector<JointBody>& bodies,
                                                 std::vector<std::size_t> solverIndex)
    : m_solverIndex(std::move(solverIndex)) {
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    const JointSidePose a = sidePose(link, bodies, false, true);
    const JointSidePose b = sidePose(link, bodies, true, true);
    JointRow rows[kMaxJointRows];
    link.joint->rows(a, b, link.joint->basisAt(a), rows);
    for (int r = 0; r < link.joint->rowCount(); ++r)
      m_rows.push_back({link.bodyA, link.bodyB, static_cast<int>(l), rows[r]});
  }
  std::vector<Mat3> inverseInertia;
  inverseInertia.reserve(bodies.size());
  for (const JointBody& body : bodies) inverseInertia.push_back(body.startInverseInertia);
  if (!m_rows.empty()) m_system.factor(m_rows, bodies, inverseInertia);
}

void JointVelocityProjection::project(std::vector<SolverBody>& bodies) const {
  if (m_rows.empty() || !m_system.ok()) return;
  const auto count = static_cast<Eigen::Index>(m_rows.size());
  const auto solverBody = [&](int local) -> SolverBody& {
    return bodies[m_solverIndex[static_cast<std::size_t>(local)]];
  };
  Eigen::VectorXd rate(count);
  for (Eigen::Index r = 0; r < count; ++r) {
    const JointSolverRow& row = m_rows[static_cast<std::size_t>(r)];
    double v = 0.0;
    if (row.bodyA >= 0) {
      const SolverBody& a = solverBody(row.bodyA);
      v += row.jacobian.linearA.dot(a.linearVelocity) + row.jacobian.angularA.dot(a.angularVelocity);
    }
    if (row.bodyB >= 0) {
      const SolverBody& b = solverBody(row.bodyB);
      v += row.jacobian.linearB.dot(b.linearVelocity) + row.jacobian.angularB.dot(b.angularVelocity);
    }
    rate[r] = v;
  }
  const Eigen::VectorXd impulse = m_system.solve(-rate);
  for (Eigen::Index r = 0; r < count; ++r) {
    const JointSolverRow& row = m_rows[static_cast<std::size_t>(r)];
    const double lambda = impulse[r];
    if (row.bodyA >= 0) {
      SolverBody& a = solverBody(row.bodyA);
      a.linearVelocity += (lambda * a.inverseMass) * row.jacobian.linearA;
      a.angularVelocity += a.inverseInertia * (lambda * row.jacobian.angularA);
    }
    if (row.bodyB >= 0) {
      SolverBody& b = solverBody(row.bodyB);
      b.linearVelocity += (lambda * b.inverseMass) * row.jacobian.linearB;
      b.angularVelocity += b.inverseInertia * (lambda * row.jacobian.angularB);
    }
  }
}

}  // namespace rbsim
