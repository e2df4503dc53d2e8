#include "physics/joint/joint_solver.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <utility>

#include "physics/body/integrator.h"

namespace rbsim {

namespace {

JointSidePose poseOf(const Vec3& position, const Quaternion& orientation) {
  return {position, orientation, orientation.toRotationMatrix()};
}

// K = J M⁻¹ Jᵀ over the rows, factorised (sparse LDLᵀ with a fill-reducing
// ordering): two rows couple only through a body they share, so a chain's K
// is block tridiagonal and its factorisation costs O(rows).
class RowSystem {
 public:
  template <class RowList>
  void factor(const RowList& rows, const std::vector<JointBody>& bodies,
              const std::vector<Mat3>& inverseInertia) {
    const auto count = static_cast<Eigen::Index>(rows.size());
    // The rows touching each body, in row order.
    std::vector<std::vector<std::pair<int, bool>>> touching(bodies.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (rows[r].bodyA >= 0) touching[static_cast<std::size_t>(rows[r].bodyA)].push_back({static_cast<int>(r), false});
      if (rows[r].bodyB >= 0) touching[static_cast<std::size_t>(rows[r].bodyB)].push_back({static_cast<int>(r), true});
    }
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t body = 0; body < bodies.size(); ++body) {
      const double inverseMass = bodies[body].inverseMass;
      const Mat3& inverseI = inverseInertia[body];
      const auto& list = touching[body];
      for (std::size_t i = 0; i < list.size(); ++i) {
        const JointRow& ri = rows[static_cast<std::size_t>(list[i].first)].jacobian;
        const Vec3& linI = list[i].second ? ri.linearB : ri.linearA;
        const Vec3 responseI = inverseI * (list[i].second ? ri.angularB : ri.angularA);
        for (std::size_t j = 0; j <= i; ++j) {
          const JointRow& rj = rows[static_cast<std::size_t>(list[j].first)].jacobian;
          const Vec3& linJ = list[j].second ? rj.linearB : rj.linearA;
          const Vec3& angJ = list[j].second ? rj.angularB : rj.angularA;
          const double k = inverseMass * linI.dot(linJ) + angJ.dot(responseI);
          // Lower triangle: row index >= column index.
          const int a = std::max(list[i].first, list[j].first);
          const int b = std::min(list[i].first, list[j].first);
          entries.emplace_back(a, b, k);
        }
      }
    }
    Eigen::SparseMatrix<double> k(count, count);
    k.setFromTriplets(entries.begin(), entries.end());
    // A tiny relative regularisation keeps K definite when joints are
    // redundant (a four-bar's hinges constrain one motion twice). It only
    // changes how fast the iteration converges, not what it converges to:
    // the iteration stops on the constraint errors themselves.
    for (Eigen::Index r = 0; r < count; ++r) k.coeffRef(r, r) *= 1.0 + 1e-10;
    m_ldlt.compute(k);
    m_ok = m_ldlt.info() == Eigen::Success;
  }
  bool ok() const { return m_ok; }
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const { return m_ldlt.solve(rhs); }

 private:
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> m_ldlt;
  bool m_ok = false;
};

// The pose after a drift over h from `fromPosition`/`fromOrientation` with
// the given velocities: the semi-implicit integrator's pose update.
void drift(const Vec3& fromPosition, const Quaternion& fromOrientation, const Vec3& linearVelocity,
           const Vec3& angularVelocity, double h, Vec3& position, Quaternion& orientation) {
  const IntegratedPose pose = advancedPose(fromPosition, fromOrientation, linearVelocity, angularVelocity, h);
  position = pose.position;
  orientation = pose.orientation;
}

}  // namespace

JointSidePose sidePose(const JointLink& link, const std::vector<JointBody>& bodies, bool sideB, bool atStart) {
  const int index = sideB ? link.bodyB : link.bodyA;
  if (index < 0) return sideB ? link.fixedB : link.fixedA;
  const JointBody& body = bodies[static_cast<std::size_t>(index)];
  return atStart ? poseOf(body.startPosition, body.startOrientation) : poseOf(body.position, body.orientation);
}

void JointSolver::solvePositions(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                                 double h, const JointSolverSettings& settings,
                                 std::vector<JointLinkResult>& results) {
  results.assign(links.size(), JointLinkResult{});
  m_rows.clear();
  // The rows at the step's start, and the errors there (kept by the
  // momentum projection; removed by the position-only one).
  std::vector<JointConstraint::Basis> bases(links.size());
  std::vector<double> startErrors;
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    const JointSidePose a = sidePose(link, bodies, false, true);
    const JointSidePose b = sidePose(link, bodies, true, true);
    bases[l] = link.joint->basisAt(a);
    JointRow rows[kMaxJointRows];
    double errors[kMaxJointRows];
    link.joint->rows(a, b, bases[l], rows);
    link.joint->errors(a, b, bases[l], errors);
    for (int r = 0; r < link.joint->rowCount(); ++r) {
      m_rows.push_back({link.bodyA, link.bodyB, static_cast<int>(l), rows[r]});
      startErrors.push_back(errors[r]);
    }
  }
  for (JointBody& body : bodies) {
    body.position = body.startPosition;
    body.orientation = body.startOrientation;
  }
  if (m_rows.empty()) return;
  std::vector<Mat3> startInverseInertia;
  startInverseInertia.reserve(bodies.size());
  for (const JointBody& body : bodies) startInverseInertia.push_back(body.startInverseInertia);
  RowSystem system;
  system.factor(m_rows, bodies, startInverseInertia);

  const auto count = static_cast<Eigen::Index>(m_rows.size());
  Eigen::VectorXd total = Eigen::VectorXd::Zero(count);  // the momentum impulses, N·s
  // The errors at the current poses, less `target`; returns the largest.
  Eigen::VectorXd residual(count);
  const auto measure = [&](const std::vector<double>* target) {
    double largest = 0.0;
    Eigen::Index r = 0;
    for (std::size_t l = 0; l < links.size(); ++l) {
      const JointLink& link = links[l];
      double errors[kMaxJointRows];
      link.joint->errors(sidePose(link, bodies, false, false), sidePose(link, bodies, true, false), bases[l], errors);
      for (int k = 0; k < link.joint->rowCount(); ++k, ++r) {
        residual[r] = errors[k] - (target ? (*target)[static_cast<std::size_t>(r)] : 0.0);
        largest = std::max(largest, std::abs(residual[r]));
      }
    }
    return largest;
  };

  // Steps 1 and 2: drift, then impulses along the start's rows until the
  // drifted poses have the start's errors.
  const auto driftAll = [&] {
    for (JointBody& body : bodies)
      drift(body.startPosition, body.startOrientation, body.inverseMass * body.linearMomentum,
            body.startInverseInertia * body.angularMomentum, h, body.position, body.orientation);
  };
  driftAll();
  for (int iteration = 0; system.ok() && iteration < settings.maxIterations; ++iteration) {
    if (measure(&startErrors) <= settings.tolerance) break;
    const Eigen::VectorXd impulse = system.solve(-residual / h);
    for (Eigen::Index r = 0; r < count; ++r) {
      const Row& row = m_rows[static_cast<std::size_t>(r)];
      const double lambda = impulse[r];
      if (row.bodyA >= 0) {
        JointBody& body = bodies[static_cast<std::size_t>(row.bodyA)];
        body.linearMomentum += lambda * row.jacobian.linearA;
        body.angularMomentum += lambda * row.jacobian.angularA;
      }
      if (row.bodyB >= 0) {
        JointBody& body = bodies[static_cast<std::size_t>(row.bodyB)];
        body.linearMomentum += lambda * row.jacobian.linearB;
        body.angularMomentum += lambda * row.jacobian.angularB;
      }
    }
    total += impulse;
    driftAll();
  }

  // Step 3: the contacts' pseudo-velocities and the start's errors, by
  // moving positions along the same rows (a velocity that only positions see).
  const bool anyPseudo = std::any_of(bodies.begin(), bodies.end(), [](const JointBody& b) {
    return !b.pseudoLinear.isZero(0.0) || !b.pseudoAngular.isZero(0.0);
  });
  if (system.ok() && (anyPseudo || measure(nullptr) > settings.tolerance)) {
    std::vector<Vec3> fromPosition, pseudoLinear, pseudoAngular;
    std::vector<Quaternion> fromOrientation;
    for (const JointBody& body : bodies) {
      fromPosition.push_back(body.position);
      fromOrientation.push_back(body.orientation);
      pseudoLinear.push_back(body.pseudoLinear);
      pseudoAngular.push_back(body.pseudoAngular);
    }
    const auto movePseudo = [&] {
      for (std::size_t i = 0; i < bodies.size(); ++i)
        drift(fromPosition[i], fromOrientation[i], pseudoLinear[i], pseudoAngular[i], h, bodies[i].position,
              bodies[i].orientation);
    };
    movePseudo();
    for (int iteration = 0; iteration < settings.maxIterations; ++iteration) {
      if (measure(nullptr) <= settings.tolerance) break;
      const Eigen::VectorXd impulse = system.solve(-residual / h);
      for (Eigen::Index r = 0; r < count; ++r) {
        const Row& row = m_rows[static_cast<std::size_t>(r)];
        for (const bool sideB : {false, true}) {
          const int index = sideB ? row.bodyB : row.bodyA;
          if (index < 0) continue;
          const JointBody& body = bodies[static_cast<std::size_t>(index)];
          const auto i = static_cast<std::size_t>(index);
          pseudoLinear[i] += impulse[r] * body.inverseMass * (sideB ? row.jacobian.linearB : row.jacobian.linearA);
          pseudoAngular[i] += impulse[r] * (body.startInverseInertia * (sideB ? row.jacobian.angularB : row.jacobian.angularA));
        }
      }
      movePseudo();
    }
  }

  // What each joint did to B, and the error it leaves.
  measure(nullptr);
  for (Eigen::Index r = 0; r < count; ++r) {
    const Row& row = m_rows[static_cast<std::size_t>(r)];
    JointLinkResult& result = results[static_cast<std::size_t>(row.link)];
    result.linearImpulse += total[r] * row.jacobian.linearB;
    result.angularImpulse += total[r] * row.jacobian.angularB;
    result.error = std::max(result.error, std::abs(residual[r]));
  }
  for (std::size_t l = 0; l < links.size(); ++l) {
    // The couple about B's anchor rather than about its centre of mass.
    const JointSidePose b = sidePose(links[l], bodies, true, true);
    const Vec3 arm = b.rotation * links[l].joint->anchorB;
    results[l].angularImpulse -= arm.cross(results[l].linearImpulse);
  }
}

void JointSolver::projectVelocities(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                                    const std::vector<Mat3>& inverseInertia,
                                    std::vector<JointLinkResult>& results) {
  m_rows.clear();
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    const JointSidePose a = sidePose(link, bodies, false, false);
    const JointSidePose b = sidePose(link, bodies, true, false);
    JointRow rows[kMaxJointRows];
    link.joint->rows(a, b, link.joint->basisAt(a), rows);
    for (int r = 0; r < link.joint->rowCount(); ++r)
      m_rows.push_back({link.bodyA, link.bodyB, static_cast<int>(l), rows[r]});
  }
  if (m_rows.empty()) return;
  RowSystem system;
  system.factor(m_rows, bodies, inverseInertia);
  if (!system.ok()) return;
  const auto count = static_cast<Eigen::Index>(m_rows.size());
  const auto velocityOf = [&](int index, bool linear) -> Vec3 {
    const JointBody& body = bodies[static_cast<std::size_t>(index)];
    return linear ? Vec3(body.inverseMass * body.linearMomentum)
                  : Vec3(inverseInertia[static_cast<std::size_t>(index)] * body.angularMomentum);
  };
  Eigen::VectorXd rate(count);
  for (Eigen::Index r = 0; r < count; ++r) {
    const Row& row = m_rows[static_cast<std::size_t>(r)];
    double v = 0.0;
    if (row.bodyA >= 0)
      v += row.jacobian.linearA.dot(velocityOf(row.bodyA, true)) + row.jacobian.angularA.dot(velocityOf(row.bodyA, false));
    if (row.bodyB >= 0)
      v += row.jacobian.linearB.dot(velocityOf(row.bodyB, true)) + row.jacobian.angularB.dot(velocityOf(row.bodyB, false));
    rate[r] = v;
  }
  const Eigen::VectorXd impulse = system.solve(-rate);
  for (Eigen::Index r = 0; r < count; ++r) {
    const Row& row = m_rows[static_cast<std::size_t>(r)];
    const double lambda = impulse[r];
    if (row.bodyA >= 0) {
      JointBody& body = bodies[static_cast<std::size_t>(row.bodyA)];
      body.linearMomentum += lambda * row.jacobian.linearA;
      body.angularMomentum += lambda * row.jacobian.angularA;
    }
    if (row.bodyB >= 0) {
      JointBody& body = bodies[static_cast<std::size_t>(row.bodyB)];
      body.linearMomentum += lambda * row.jacobian.linearB;
      body.angularMomentum += lambda * row.jacobian.angularB;
    }
    JointLinkResult& result = results[static_cast<std::size_t>(row.link)];
    const JointSidePose b = sidePose(links[static_cast<std::size_t>(row.link)], bodies, true, false);
    const Vec3 arm = b.rotation * links[static_cast<std::size_t>(row.link)].joint->anchorB;
    result.linearImpulse += lambda * row.jacobian.linearB;
    result.angularImpulse += lambda * (row.jacobian.angularB - arm.cross(row.jacobian.linearB));
  }
}

}  // namespace rbsim
