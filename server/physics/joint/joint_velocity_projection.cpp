#include "physics/joint/joint_velocity_projection.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

#include "physics/common/step_part.h"

namespace rbsim {

namespace {

// A joint this close to a bound (or past it) at the step's start is at it:
// the position projection leaves a held limit at its bound to 1e-12.
constexpr double kAtBound = 1e-9;  // m or rad

}  // namespace

void JointGroupProjection::make(const std::vector<JointLink>& links, const std::vector<JointBody>& bodies,
                                const std::vector<std::size_t>& solverIndex, const JointSolver* kept) {
  m_solverIndex.assign(solverIndex.begin(), solverIndex.end());
  m_rows.clear();
  m_limits.clear();
  // Room for every limit of the group at a bound at once: a later step with
  // more of them than this one allocates nothing.
  m_limitCapacity = static_cast<std::size_t>(std::count_if(links.begin(), links.end(), [](const JointLink& link) {
    return !link.isCoupling() && link.joint->hasLimit();
  }));
  m_limits.reserve(m_limitCapacity);
  m_limitResponse.reserve(m_limitCapacity * m_limitCapacity);
  m_haveColumn.reserve(m_limitCapacity);
  if (m_columnVelocities.size() < m_limitCapacity) m_columnVelocities.resize(m_limitCapacity);
  for (std::vector<Vec3>& velocities : m_columnVelocities) velocities.reserve(2 * bodies.size());
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    const LinkPoses poses = linkPoses(link, bodies, true);
    const JointSidePose& a = poses[0];
    const JointSidePose& b = poses[1];
    appendLinkRows(link, static_cast<int>(l), poses, link.joint->basisAt(a), m_rows);
    if (link.isCoupling() || !link.joint->hasLimit()) continue;
    const double q = link.joint->coordinate(a, b);
    const int side = q <= link.joint->limitLower() + kAtBound ? -1 : q >= link.joint->limitUpper() - kAtBound ? +1 : 0;
    if (side == 0) continue;
    Limit limit{JointSolverRow::of(link.bodyA, link.bodyB, static_cast<int>(l)), side};
    link.joint->limitRow(a, b, limit.row.jacobian);
    m_limits.push_back(limit);
  }
  std::vector<Mat3>& inverseInertia = m_inverseInertia;
  inverseInertia.clear();
  for (const JointBody& body : bodies) inverseInertia.push_back(body.startInverseInertia);
  if (!m_rows.empty()) {
    const std::vector<double>& inverseMass = inverseMasses(bodies, m_inverseMass);
    // (A copy into m_system's storage: no allocation once it has grown.)
    if (kept != nullptr)
      if (const RowSystem* made = kept->keptFactor(m_rows, inverseMass, inverseInertia, true)) m_system = *made;
    m_system.factor(m_rows, inverseMass, inverseInertia);  // nothing to do when kept, no analysis when its pattern
  }
  // The scratch bodies for the limits' response: their inverse mass and
  // inertia at the start (made with no limit at a bound too, so that the
  // group's next step with one finds them sized).
  m_scratch.resize(bodies.size());
  m_scratchIndex.clear();
  for (std::size_t local = 0; local < bodies.size(); ++local) {
    SolverBody& body = m_scratch[local];
    body.inverseMass = bodies[local].inverseMass;
    body.inverseInertia = bodies[local].startInverseInertia;
    m_scratchIndex.push_back(local);
  }
  if (m_limits.empty()) return;
  const std::size_t n = m_limits.size();
  m_limitResponse.assign(n * n, 0.0);
  m_haveColumn.assign(n, 0);
  // Never shrunk: a column's list keeps its storage for the next step.
  if (m_columnVelocities.size() < n) m_columnVelocities.resize(n);
}

const double* JointGroupProjection::responseColumn(std::size_t j) const {
  const std::size_t n = m_limits.size();
  double* column = m_limitResponse.data() + n * j;
  if (!m_haveColumn[j]) {
    for (SolverBody& body : m_scratch) {
      body.linearVelocity.setZero();
      body.angularVelocity.setZero();
    }
    push(m_limits[j].row, 1.0, m_scratch, m_scratchIndex);
    projectJoints(m_scratch, m_scratchIndex);
    for (std::size_t i = 0; i < n; ++i) column[i] = rate(m_limits[i].row, m_scratch, m_scratchIndex);
    std::vector<Vec3>& velocities = m_columnVelocities[j];
    velocities.clear();
    for (const SolverBody& body : m_scratch) {
      velocities.push_back(body.linearVelocity);
      velocities.push_back(body.angularVelocity);
    }
    m_haveColumn[j] = 1;
  }
  return column;
}

double JointGroupProjection::rate(const JointSolverRow& row, const std::vector<SolverBody>& bodies,
                                  const std::vector<std::size_t>& index) const {
  double v = 0.0;
  for (int side = 0; side < row.sideCount(); ++side) {
    if (row.body(side) < 0) continue;
    const SolverBody& body = bodies[index[static_cast<std::size_t>(row.body(side))]];
    v += row.linear(side).dot(body.linearVelocity) + row.angular(side).dot(body.angularVelocity);
  }
  return v;
}

void JointGroupProjection::push(const JointSolverRow& row, double lambda, std::vector<SolverBody>& bodies,
                                const std::vector<std::size_t>& index) const {
  for (int side = 0; side < row.sideCount(); ++side) {
    if (row.body(side) < 0) continue;
    SolverBody& body = bodies[index[static_cast<std::size_t>(row.body(side))]];
    body.linearVelocity += (lambda * body.inverseMass) * row.linear(side);
    body.angularVelocity += body.inverseInertia * (lambda * row.angular(side));
  }
}

void JointGroupProjection::projectJoints(std::vector<SolverBody>& bodies,
                                         const std::vector<std::size_t>& index) const {
  if (m_rows.empty() || !m_system.ok()) return;
  const auto count = static_cast<Eigen::Index>(m_rows.size());
  m_impulse.resize(count);
  for (Eigen::Index r = 0; r < count; ++r) m_impulse[r] = -rate(m_rows[static_cast<std::size_t>(r)], bodies, index);
  m_system.solveInPlace(m_impulse);
  // The rows' impulses summed per body, then through its inverse mass and
  // inertia once.
  m_linearImpulse.assign(index.size(), Vec3::Zero());
  m_angularImpulse.assign(index.size(), Vec3::Zero());
  for (Eigen::Index r = 0; r < count; ++r) {
    const JointSolverRow& row = m_rows[static_cast<std::size_t>(r)];
    const double lambda = m_impulse[r];
    for (int side = 0; side < row.sideCount(); ++side) {
      if (row.body(side) < 0) continue;
      m_linearImpulse[static_cast<std::size_t>(row.body(side))] += lambda * row.linear(side);
      m_angularImpulse[static_cast<std::size_t>(row.body(side))] += lambda * row.angular(side);
    }
  }
  for (std::size_t local = 0; local < m_solverIndex.size(); ++local) {
    SolverBody& body = bodies[index[local]];
    body.linearVelocity += body.inverseMass * m_linearImpulse[local];
    body.angularVelocity += body.inverseInertia * m_angularImpulse[local];
  }
}

void JointGroupProjection::project(std::vector<SolverBody>& bodies, JointLimitScratch& scratch) const {
  projectJoints(bodies, m_solverIndex);
  if (m_limits.empty()) return;
  // With s = −side (a lower bound pushes up), μ = s Λ ≥ 0 the limits'
  // pushes and u = s w their rates away from the bounds: u = q + M μ with
  // q = s w now and M = S A S, u ≥ 0, μ ≥ 0, u·μ = 0. Pivoting on the set
  // of limits that push: each round solves M_PP μ_P = −q_P, drops a push
  // that came out negative or takes in a limit still moved into.
  const auto n = static_cast<Eigen::Index>(m_limits.size());
  if (scratch.lcpBySize.size() <= m_limits.size()) scratch.lcpBySize.resize(m_limits.size() + 1);
  JointLimitScratch::Lcp& lcp = scratch.lcpBySize[m_limits.size()];
  Eigen::VectorXd& q = lcp.q;
  Eigen::VectorXd& s = lcp.s;
  q.resize(n);
  s.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    s[i] = -m_limits[static_cast<std::size_t>(i)].side;
    q[i] = s[i] * rate(m_limits[static_cast<std::size_t>(i)].row, bodies, m_solverIndex);
  }
  std::vector<char>& pushing = scratch.pushing;
  pushing.assign(static_cast<std::size_t>(n), 0);
  bool anyInto = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    pushing[static_cast<std::size_t>(i)] = q[i] < 0.0;
    anyInto = anyInto || q[i] < 0.0;
  }
  if (!anyInto) return;  // every limit free to leave its bound: nothing to do
  // M's columns as the pushing set needs them (the others stay zero, and
  // only enter M μ through μ = 0).
  Eigen::MatrixXd& m = lcp.m;
  m.setZero(n, n);
  std::vector<char>& haveColumn = scratch.haveM;
  haveColumn.assign(static_cast<std::size_t>(n), 0);
  const auto needColumn = [&](Eigen::Index j) {
    if (haveColumn[static_cast<std::size_t>(j)]) return;
    m.col(j) = s.asDiagonal() * Eigen::Map<const Eigen::VectorXd>(responseColumn(static_cast<std::size_t>(j)), n) * s[j];
    haveColumn[static_cast<std::size_t>(j)] = 1;
  };
  Eigen::VectorXd& mu = lcp.mu;
  mu.setZero(n);
  for (Eigen::Index round = 0; round <= 2 * n; ++round) {
    std::vector<Eigen::Index>& set = scratch.set;
    set.clear();
    for (Eigen::Index i = 0; i < n; ++i)
      if (pushing[static_cast<std::size_t>(i)]) {
        set.push_back(i);
        needColumn(i);
      }
    mu.setZero();
    if (!set.empty()) {
      const auto k = static_cast<Eigen::Index>(set.size());
      if (scratch.pushingBySize.size() <= set.size()) scratch.pushingBySize.resize(set.size() + 1);
      JointLimitScratch::PushingSet& pushingSet = scratch.pushingBySize[set.size()];
      Eigen::MatrixXd& mPP = pushingSet.mPP;
      Eigen::VectorXd& qP = pushingSet.qP;
      mPP.resize(k, k);
      qP.resize(k);
      for (Eigen::Index a = 0; a < k; ++a) {
        qP[a] = q[set[static_cast<std::size_t>(a)]];
        for (Eigen::Index b = 0; b < k; ++b) mPP(a, b) = m(set[static_cast<std::size_t>(a)], set[static_cast<std::size_t>(b)]);
      }
      // A tiny relative regularisation, as K's: limits that constrain one
      // motion twice stay solvable.
      mPP.diagonal() *= 1.0 + 1e-10;
      pushingSet.ldlt.compute(mPP);
      Eigen::VectorXd& solved = pushingSet.solved;
      solved = pushingSet.ldlt.solve(-qP);
      for (Eigen::Index a = 0; a < k; ++a) mu[set[static_cast<std::size_t>(a)]] = solved[a];
    }
    Eigen::VectorXd& u = lcp.u;
    u.noalias() = q + m * mu;  // as a fresh vector's u = q, u += m mu: no temporary
    bool changed = false;
    for (Eigen::Index i = 0; i < n && !changed; ++i) {
      char& p = pushing[static_cast<std::size_t>(i)];
      if (p && mu[i] < 0.0) {
        p = 0;
        changed = true;
      }
    }
    for (Eigen::Index i = 0; i < n && !changed; ++i) {
      char& p = pushing[static_cast<std::size_t>(i)];
      if (!p && u[i] < -1e-14 * (1.0 + std::abs(q[i]))) {
        p = 1;
        changed = true;
      }
    }
    if (!changed) break;
  }
  // The limits' pushes with the joints' reply: by linearity, each push's
  // velocities as its column of A has them (projecting the pushed
  // velocities again would give the same to rounding, at a solve's cost).
  for (Eigen::Index i = 0; i < n; ++i) {
    if (mu[i] <= 0.0) continue;
    const double scale = s[i] * mu[i];
    const std::vector<Vec3>& velocities = m_columnVelocities[static_cast<std::size_t>(i)];
    for (std::size_t k = 0; k < m_solverIndex.size(); ++k) {
      SolverBody& body = bodies[m_solverIndex[k]];
      body.linearVelocity += scale * velocities[2 * k];
      body.angularVelocity += scale * velocities[2 * k + 1];
    }
  }
}

void JointVelocityProjection::make(const std::vector<JointLink>& links, const std::vector<JointBody>& bodies,
                                   const std::vector<std::size_t>& solverIndex, const JointSolver* kept) {
  m_grouping.make(links, bodies.size());
  const std::vector<int>& localIndex = m_grouping.localIndex();
  m_count = 0;
  for (std::size_t g = 0; g < m_grouping.size(); ++g) {
    const JointGroup& group = m_grouping[g];
    if (group.links.empty()) continue;
    m_groupLinks.clear();
    for (const int l : group.links) m_groupLinks.push_back(inGroup(links[static_cast<std::size_t>(l)], localIndex));
    m_groupBodies.clear();
    m_groupIndex.clear();
    for (const int i : group.bodies) {
      m_groupBodies.push_back(bodies[static_cast<std::size_t>(i)]);
      m_groupIndex.push_back(solverIndex[static_cast<std::size_t>(i)]);
    }
    // Never shrunk: a group past this step's count keeps its storage.
    if (m_groups.size() <= m_count) m_groups.emplace_back();
    m_groups[m_count].make(m_groupLinks, m_groupBodies, m_groupIndex, kept);
    m_limitScratch.reserve(m_groups[m_count].limitCapacity());
    ++m_count;
  }
}

void JointLimitScratch::reserve(std::size_t n) {
  n = std::min(n, kReserved);
  if (lcpBySize.size() > n) return;
  const std::size_t from = lcpBySize.size();
  lcpBySize.resize(n + 1);
  pushingBySize.resize(n + 1);
  for (std::size_t size = from; size <= n; ++size) {
    const auto k = static_cast<Eigen::Index>(size);
    Lcp& lcp = lcpBySize[size];
    lcp.m.resize(k, k);
    lcp.q.resize(k);
    lcp.s.resize(k);
    lcp.mu.resize(k);
    lcp.u.resize(k);
    PushingSet& pushingSet = pushingBySize[size];
    pushingSet.mPP.resize(k, k);
    pushingSet.qP.resize(k);
    pushingSet.solved.resize(k);
    pushingSet.ldlt = Eigen::LDLT<Eigen::MatrixXd>(k);  // its factor, transpositions and temporary made
  }
  pushing.reserve(n);
  haveM.reserve(n);
  set.reserve(n);
}

void JointVelocityProjection::project(std::vector<SolverBody>& bodies) const {
  const StepPartScope inJoints(StepPart::Joints);  // called from the contact sweeps
  for (std::size_t g = 0; g < m_count; ++g) m_groups[g].project(bodies, m_limitScratch);
}

}  // namespace rbsim
