#include "physics/joint/joint_solver.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "physics/body/integrator.h"
#include "physics/common/step_part.h"
#include "physics/joint/axis_actuation.h"
#include "physics/math/rotation_matrix.h"

namespace rbsim {

namespace {

// A vector of n numbers from `pool`, kept by size (pool[n]): an Eigen
// vector reallocates whenever its size changes, and a step's counts of rows
// change as limits engage and let go, so each count keeps its own vector
// (allocated the first time that count is seen, not at every step).
Eigen::VectorXd& sizedVector(std::vector<Eigen::VectorXd>& pool, std::size_t n) {
  if (pool.size() <= n) pool.resize(n + 1);
  pool[n].resize(static_cast<Eigen::Index>(n));
  return pool[n];
}

JointSidePose poseOf(const Vec3& position, const Quaternion& orientation) {
  return {position, orientation, orientation.toRotationMatrix()};
}

// Newton's matrix for the drifted errors: dC(x')/dλ, the rows at the current
// poses (exact derivatives) times the drift's response to an impulse along
// the start's rows: h m⁻¹ for the linear part, D I₀⁻¹ for the angular one,
// D the derivative of the pose update's turn (body/integrator.h: q' =
// normalise(q + ½h [0, ω] q)) with respect to ω. Not symmetric, so LU.
class NewtonSystem {
 public:
  void factor(const std::vector<JointSolverRow>& startRows, const std::vector<JointSolverRow>& currentRows,
              const std::vector<JointBody>& bodies, const std::vector<Mat3>& turnResponse, double h) {
    const auto count = static_cast<Eigen::Index>(startRows.size());
    std::vector<std::vector<std::pair<int, int>>> touching(bodies.size());  // (row, side)
    for (std::size_t r = 0; r < startRows.size(); ++r)
      for (int side = 0; side < startRows[r].sideCount(); ++side)
        if (startRows[r].body(side) >= 0)
          touching[static_cast<std::size_t>(startRows[r].body(side))].push_back({static_cast<int>(r), side});
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t body = 0; body < bodies.size(); ++body) {
      const double linearResponse = h * bodies[body].inverseMass;
      const Mat3 angularResponse = turnResponse[body] * bodies[body].startInverseInertia;
      for (const auto& [r, rSide] : touching[body]) {
        const JointSolverRow& now = currentRows[static_cast<std::size_t>(r)];
        const Vec3& linNow = now.linear(rSide);
        const Vec3& angNow = now.angular(rSide);
        for (const auto& [c, cSide] : touching[body]) {
          const JointSolverRow& start = startRows[static_cast<std::size_t>(c)];
          const Vec3& linStart = start.linear(cSide);
          const Vec3& angStart = start.angular(cSide);
          entries.emplace_back(r, c, linearResponse * linNow.dot(linStart) + angNow.dot(angularResponse * angStart));
        }
      }
    }
    Eigen::SparseMatrix<double> a(count, count);
    a.setFromTriplets(entries.begin(), entries.end());
    for (Eigen::Index r = 0; r < count; ++r) a.coeffRef(r, r) *= 1.0 + 1e-10;
    a.makeCompressed();
    m_lu.compute(a);
    m_ok = m_lu.info() == Eigen::Success;
  }
  bool ok() const { return m_ok; }
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) { return m_lu.solve(rhs); }

 private:
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> m_lu;
  bool m_ok = false;
};

// d(turn)/dω of the pose update q' = u / |u|, u = q + ½h [0, ω] q: a change
// δω turns q' by (h / |u|)(r_w 1 − [r_v]×) δω with r = q q'⁻¹ (h 1 for a
// small turn).
Mat3 turnResponse(const Quaternion& from, const Vec3& omega, double h) {
  const Quaternion u = addScaled(from, orientationRate(from, omega), h);
  const double norm = u.norm();
  const Quaternion r = from * Quaternion{u.w / norm, -u.x / norm, -u.y / norm, -u.z / norm};
  return (h / norm) * (r.w * Mat3::Identity() - crossMatrix(r.vec()));
}

}  // namespace

std::vector<double> inverseMasses(const std::vector<JointBody>& bodies) {
  std::vector<double> out;
  return inverseMasses(bodies, out);
}

std::vector<double>& inverseMasses(const std::vector<JointBody>& bodies, std::vector<double>& out) {
  out.clear();
  for (const JointBody& body : bodies) out.push_back(body.inverseMass);
  return out;
}

namespace {

JointSidePose poseOfSide(int index, const JointSidePose& fixed, const std::vector<JointBody>& bodies, bool atStart) {
  if (index < 0) return fixed;
  const JointBody& body = bodies[static_cast<std::size_t>(index)];
  return atStart ? poseOf(body.startPosition, body.startOrientation) : poseOf(body.position, body.orientation);
}

// A joint coordinate's change from `from` to `now`: a revolute's the short
// way round (its coordinate wraps; a step turns it by far less than π).
double coordinateChange(const JointConstraint& joint, double now, double from) {
  const double change = now - from;
  return joint.def.type == JointType::Revolute ? std::remainder(change, 2.0 * 3.14159265358979323846) : change;
}

}  // namespace

JointSidePose sidePose(const JointLink& link, const std::vector<JointBody>& bodies, bool sideB, bool atStart) {
  return sideB ? poseOfSide(link.bodyB, link.fixedB, bodies, atStart) : poseOfSide(link.bodyA, link.fixedA, bodies, atStart);
}

LinkPoses linkPoses(const JointLink& link, const std::vector<JointBody>& bodies, bool atStart) {
  LinkPoses poses;
  poses[0] = poseOfSide(link.bodyA, link.fixedA, bodies, atStart);
  poses[1] = poseOfSide(link.bodyB, link.fixedB, bodies, atStart);
  if (link.isCoupling()) {
    poses[2] = poseOfSide(link.bodyC, link.fixedC, bodies, atStart);
    poses[3] = poseOfSide(link.bodyD, link.fixedD, bodies, atStart);
  }
  return poses;
}

int linkRowCount(const JointLink& link) { return link.isCoupling() ? 1 : link.joint->rowCount(); }

double couplingError(const JointLink& link, const LinkPoses& poses) {
  const double follower = link.joint->coordinate(poses[0], poses[1]);
  const double leader = link.leader->coordinate(poses[2], poses[3]);
  return link.errorFrom + coordinateChange(*link.joint, follower, link.followerFrom) -
         link.joint->def.mimic.multiplier * coordinateChange(*link.leader, leader, link.leaderFrom);
}

void linkErrors(const JointLink& link, const LinkPoses& poses, const JointConstraint::Basis& basis, double* out) {
  if (link.isCoupling()) {
    out[0] = couplingError(link, poses);
    return;
  }
  link.joint->errors(poses[0], poses[1], basis, out);
}

void appendLinkRows(const JointLink& link, int index, const LinkPoses& poses, const JointConstraint::Basis& basis,
                    std::vector<JointSolverRow>& out) {
  if (!link.isCoupling()) {
    JointRow rows[kMaxJointRows];
    link.joint->rows(poses[0], poses[1], basis, rows);
    for (int r = 0; r < link.joint->rowCount(); ++r) out.push_back(JointSolverRow::of(link.bodyA, link.bodyB, index, rows[r]));
    return;
  }
  // The follower's axis row less `multiplier` times the leader's, with a
  // body that is a side of both joints (a gripper's palm) given once.
  JointRow follower, leader;
  link.joint->axisRow(poses[0], poses[1], follower);
  link.leader->axisRow(poses[2], poses[3], leader);
  const double m = link.joint->def.mimic.multiplier;
  struct Side {
    int body;
    Vec3 linear, angular;
  };
  const Side given[4] = {{link.bodyA, follower.linearA, follower.angularA},
                         {link.bodyB, follower.linearB, follower.angularB},
                         {link.bodyC, -m * leader.linearA, -m * leader.angularA},
                         {link.bodyD, -m * leader.linearB, -m * leader.angularB}};
  Side merged[4];
  int count = 0;
  for (const Side& side : given) {
    if (side.body < 0) continue;  // a fixed side takes nothing
    Side* same = std::find_if(merged, merged + count, [&](const Side& m2) { return m2.body == side.body; });
    if (same != merged + count) {
      same->linear += side.linear;
      same->angular += side.angular;
    } else {
      merged[count++] = side;
    }
  }
  JointSolverRow row;
  row.link = index;
  int* bodies[4] = {&row.bodyA, &row.bodyB, &row.bodyC, &row.bodyD};
  Vec3* linear[4] = {&row.jacobian.linearA, &row.jacobian.linearB, &row.second.linearA, &row.second.linearB};
  Vec3* angular[4] = {&row.jacobian.angularA, &row.jacobian.angularB, &row.second.angularA, &row.second.angularB};
  for (int k = 0; k < count; ++k) {
    *bodies[k] = merged[k].body;
    *linear[k] = merged[k].linear;
    *angular[k] = merged[k].angular;
  }
  out.push_back(row);
}

void JointGroupSolver::Workspace::reserve(std::size_t jointRows, std::size_t limits) {
  limits = std::min(limits, kReserved);
  const auto joints = static_cast<Eigen::Index>(jointRows);
  for (std::size_t l = 0; l <= limits; ++l) {
    const std::size_t rows = jointRows + l;
    for (std::vector<Eigen::VectorXd>* pool : {&totalBySize, &pseudoTotalBySize, &residualBySize, &impulseBySize,
                                               &rateBySize, &stepBySize, &rateImpulseBySize})
      sizedVector(*pool, rows);
    if (l == 0) continue;
    BorderNumbers& numbers = border(rows, l);
    if (numbers.reserved) continue;
    const auto k = static_cast<Eigen::Index>(l);
    numbers.coupling.resize(joints, k);
    numbers.response.resize(joints, k);
    numbers.schurMatrix.resize(k, k);
    numbers.schur = Eigen::LLT<Eigen::MatrixXd>(k);  // its factor made
    numbers.column.resize(joints);
    numbers.jointPart.resize(joints);
    numbers.limitPart.resize(k);
    numbers.reserved = true;
  }
}

void JointGroupSolver::clearDrift(Drift& drift) {
  drift.fromPosition.clear();
  drift.fromOrientation.clear();
  drift.linearVelocity.clear();
  drift.angularVelocity.clear();
  drift.linearImpulse.clear();
  drift.angularImpulse.clear();
  drift.angularMomentum.clear();
}

void JointGroupSolver::project(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                               const std::vector<JointConstraint::Basis>& bases, const std::vector<double>* targets,
                               Drift& drift, double h, const JointSolverSettings& settings, double& largest,
                               Eigen::VectorXd& total) {
  const auto count = static_cast<Eigen::Index>(m_rows.size());
  total.setZero(count);
  Eigen::VectorXd& residual = sizedVector(work().residualBySize, m_rows.size());
  // The bodies' current rotations, made once per move (a body is the side
  // of several joints).
  std::vector<Mat3>& rotation = work().rotation;
  rotation.resize(bodies.size());
  const auto currentSide = [&](int index, const JointSidePose& fixed) {
    if (index < 0) return fixed;
    const JointBody& body = bodies[static_cast<std::size_t>(index)];
    return JointSidePose{body.position, body.orientation, rotation[static_cast<std::size_t>(index)]};
  };
  const auto currentPoses = [&](const JointLink& link) {
    LinkPoses poses;
    poses[0] = currentSide(link.bodyA, link.fixedA);
    poses[1] = currentSide(link.bodyB, link.fixedB);
    if (link.isCoupling()) {
      poses[2] = currentSide(link.bodyC, link.fixedC);
      poses[3] = currentSide(link.bodyD, link.fixedD);
    }
    return poses;
  };
  // The errors at the current poses less the targets; returns the largest.
  const auto measure = [&] {
    double worst = 0.0;
    Eigen::Index r = 0;
    for (std::size_t l = 0; l < links.size(); ++l) {
      const JointLink& link = links[l];
      double errors[kMaxJointRows];
      linkErrors(link, currentPoses(link), bases[l], errors);
      for (int k = 0; k < linkRowCount(link); ++k, ++r) {
        residual[r] = errors[k] - (targets ? (*targets)[static_cast<std::size_t>(r)] : 0.0);
        worst = std::max(worst, std::abs(residual[r]));
      }
    }
    for (const LimitRow& limit : m_limits) {  // the coordinate at its bound
      const JointLink& link = links[static_cast<std::size_t>(limit.link)];
      const LinkPoses poses = currentPoses(link);
      residual[r] = link.joint->coordinate(poses[0], poses[1]) - limit.bound -
                    (targets ? (*targets)[static_cast<std::size_t>(r)] : 0.0);
      worst = std::max(worst, std::abs(residual[r]));
      ++r;
    }
    return worst;
  };
  const auto omegaOf = [&](std::size_t i) {
    return Vec3(drift.angularVelocity[i] + bodies[i].startInverseInertia * drift.angularImpulse[i]);
  };
  // The angular velocity body i drifts with. For the momenta's drift, the
  // explicit midpoint of the free rotation: L stays, the inertia turns with
  // the body, so ω is I⁻¹ L at the pose half-way (second order for a body
  // tumbling with unequal moments, where a fixed ω is first order). Also
  // the inverse inertia it is taken with (`halfInverseInertia`).
  const bool freeRotation = !drift.angularMomentum.empty();
  const auto driftOmega = [&](std::size_t i, Mat3* halfInverseInertia) {
    const Vec3 omega = omegaOf(i);
    if (!freeRotation) {
      if (halfInverseInertia != nullptr) *halfInverseInertia = bodies[i].startInverseInertia;
      return omega;
    }
    const Quaternion& from = drift.fromOrientation[i];
    const Quaternion half = advancedPose(Vec3::Zero(), from, Vec3::Zero(), omega, 0.5 * h).orientation;
    const Mat3 turn = half.toRotationMatrix() * from.toRotationMatrix().transpose();
    const Mat3 inverseInertia = turn * bodies[i].startInverseInertia * turn.transpose();
    if (halfInverseInertia != nullptr) *halfInverseInertia = inverseInertia;
    return Vec3(inverseInertia * (drift.angularMomentum[i] + drift.angularImpulse[i]));
  };
  const auto moveAll = [&] {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const Vec3 omega = driftOmega(i, nullptr);
      const IntegratedPose pose =
          advancedPose(drift.fromPosition[i], drift.fromOrientation[i],
                       drift.linearVelocity[i] + bodies[i].inverseMass * drift.linearImpulse[i], omega, h);
      bodies[i].position = pose.position;
      bodies[i].orientation = pose.orientation;
      rotation[i] = pose.orientation.toRotationMatrix();
    }
  };
  const auto applyImpulse = [&](const Eigen::VectorXd& impulse, double scale) {
    for (Eigen::Index r = 0; r < count; ++r) {
      const Row& row = m_rows[static_cast<std::size_t>(r)];
      const double lambda = scale * impulse[r];
      for (int side = 0; side < row.sideCount(); ++side) {
        const int body = row.body(side);
        if (body < 0) continue;
        drift.linearImpulse[static_cast<std::size_t>(body)] += lambda * row.linear(side);
        drift.angularImpulse[static_cast<std::size_t>(body)] += lambda * row.angular(side);
      }
    }
  };

  moveAll();
  largest = measure();
  m_projectIterations = 0;
  // Quasi-Newton with the start's K while it converges fast (the usual
  // case: a few iterations); Newton with the exact derivative once it does
  // not (fast turns, where the start's rows are too far from the current
  // ones); an iterate that makes the error larger is halved back.
  bool newton = false;
  std::optional<NewtonSystem> exact;  // made when first needed (its sparse LU allocates when made)
  std::vector<JointSolverRow>& currentRows = work().currentRows;
  std::vector<Mat3>& turns = work().turns;
  turns.resize(bodies.size());
  Eigen::VectorXd& impulse = sizedVector(work().impulseBySize, m_rows.size());
  for (int iteration = 0; systemOk() && iteration < settings.maxIterations; ++iteration) {
    if (largest <= settings.tolerance) break;
    if (newton) {
      // Eigen's sparse LU allocates at every factorisation: the one part of
      // the joint step that does (counted apart, physics/common/step_part.h).
      const StepPartScope fallback(StepPart::JointNewton);
      currentRows.clear();
      for (std::size_t l = 0; l < links.size(); ++l)
        appendLinkRows(links[l], static_cast<int>(l), linkPoses(links[l], bodies, false), bases[l], currentRows);
      for (const LimitRow& limit : m_limits) {
        const JointLink& link = links[static_cast<std::size_t>(limit.link)];
        JointSolverRow row = JointSolverRow::of(link.bodyA, link.bodyB, limit.link);
        link.joint->limitRow(sidePose(link, bodies, false, false), sidePose(link, bodies, true, false), row.jacobian);
        currentRows.push_back(row);
      }
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        // d(turn)/d(impulse) = turnResponse · I_half⁻¹, passed as a turn
        // that the Newton system multiplies by the start's I⁻¹ (the half
        // turn's own dependence on the impulse is O(h) and left out).
        Mat3 halfInverseInertia;
        const Vec3 omega = driftOmega(i, &halfInverseInertia);
        turns[i] = turnResponse(drift.fromOrientation[i], omega, h);
        if (freeRotation) turns[i] = turns[i] * halfInverseInertia * bodies[i].startInverseInertia.inverse();
      }
      if (!exact) exact.emplace();
      exact->factor(m_rows, currentRows, bodies, turns, h);
      if (!exact->ok()) break;
      impulse = exact->solve(-residual);
    } else {
      impulse = -residual / h;
      solveRows(impulse);
    }
    if (!m_systemExact && !newton) {
      // A factor kept from an earlier step: its whole step while that
      // leaves at most keepRatio of the error; else K₀ is made here (the
      // step kept if it helped) and the iteration goes on with it.
      applyImpulse(impulse, 1.0);
      moveAll();
      const double next = measure();
      const bool fast = next <= m_keepRatio * largest;
      if (next < largest) {
        total += impulse;
        largest = next;
      } else {
        applyImpulse(impulse, -1.0);
        moveAll();
        largest = measure();
      }
      ++m_projectIterations;
      if (!fast) {
        factorAtStart(bodies);
        m_refreshed = true;
      }
      continue;
    }
    double scale = 1.0, next = largest;
    for (int halving = 0; halving < 8; ++halving) {
      applyImpulse(impulse, scale);
      moveAll();
      next = measure();
      if (next < largest) break;
      applyImpulse(impulse, -scale);  // back, and try half of it
      scale *= 0.5;
      moveAll();
      measure();
    }
    if (next >= largest) break;  // no step along it helps: keep the best poses
    ++m_projectIterations;
    total += scale * impulse;
    if (next > 0.25 * largest) newton = true;
    largest = next;
  }
}

namespace {

// The rate of a row from the bodies' momenta (velocities with the inverse
// inertias given, one per body), and an impulse along a row into the
// momenta.
double rowRate(const JointSolverRow& row, const std::vector<JointBody>& bodies, const std::vector<Mat3>& inverseInertia) {
  double v = 0.0;
  for (int side = 0; side < row.sideCount(); ++side) {
    if (row.body(side) < 0) continue;
    const auto i = static_cast<std::size_t>(row.body(side));
    v += row.linear(side).dot(bodies[i].inverseMass * bodies[i].linearMomentum) +
         row.angular(side).dot(inverseInertia[i] * bodies[i].angularMomentum);
  }
  return v;
}

// Every row's rate at once: each body's velocities made once (a body is
// the side of several rows), then the rows' dot products.
// `linear` and `angular` are scratch (kept by the caller: no allocation).
void rowRates(const std::vector<JointSolverRow>& rows, const std::vector<JointBody>& bodies,
              const std::vector<Mat3>& inverseInertia, Eigen::VectorXd& out, std::vector<Vec3>& linear,
              std::vector<Vec3>& angular) {
  linear.resize(bodies.size());
  angular.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    linear[i] = bodies[i].inverseMass * bodies[i].linearMomentum;
    angular[i] = inverseInertia[i] * bodies[i].angularMomentum;
  }
  out.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const JointSolverRow& row = rows[r];
    double v = 0.0;
    for (int side = 0; side < row.sideCount(); ++side) {
      if (row.body(side) < 0) continue;
      const auto i = static_cast<std::size_t>(row.body(side));
      v += row.linear(side).dot(linear[i]) + row.angular(side).dot(angular[i]);
    }
    out[static_cast<Eigen::Index>(r)] = v;
  }
}

void pushAlongRow(const JointSolverRow& row, double lambda, std::vector<JointBody>& bodies) {
  for (int side = 0; side < row.sideCount(); ++side) {
    if (row.body(side) < 0) continue;
    JointBody& body = bodies[static_cast<std::size_t>(row.body(side))];
    body.linearMomentum += lambda * row.linear(side);
    body.angularMomentum += lambda * row.angular(side);
  }
}

// Whether a joint has anything acting along its axis besides its limit (a
// distance joint's spring acts along the anchors' line as a drive does).
bool axisActs(const JointConstraint& joint) {
  const JointDef& def = joint.def;
  return (joint.hasAxis() && (def.motor.enabled || def.drive.enabled || def.damping > 0.0 || def.friction > 0.0)) ||
         joint.hasSpring();
}

// The drive's position error, the short way round for a revolute joint
// without limits (a wheel, a continuous joint: its angle wraps at ±2π).
double driveError(const JointConstraint& joint, double position) {
  double error = position - joint.def.drive.target;
  if (joint.def.type == JointType::Revolute && !joint.def.limit.enabled)
    error = std::remainder(error, 2.0 * 3.14159265358979323846);
  return error;
}

}  // namespace

void JointGroupSolver::removeJointRates(std::vector<JointBody>& bodies, const std::vector<Mat3>& inverseInertia) const {
  const auto count = static_cast<Eigen::Index>(m_rows.size());
  Eigen::VectorXd impulse(count);
  std::vector<Vec3> linear, angular;
  rowRates(m_rows, bodies, inverseInertia, impulse, linear, angular);
  impulse = -impulse;
  solveRows(impulse);
  for (Eigen::Index r = 0; r < count; ++r) pushAlongRow(m_rows[static_cast<std::size_t>(r)], impulse[r], bodies);
}

void JointGroupSolver::factorAtStart(const std::vector<JointBody>& bodies) {
  std::vector<Mat3>& startInverseInertia = startInverseInertias(bodies);
  // The joints' rows alone; the limits' rows set aside meanwhile.
  std::vector<Row>& limitRows = work().limitRows;
  limitRows.assign(m_rows.begin() + static_cast<std::ptrdiff_t>(m_jointRows), m_rows.end());
  m_rows.resize(m_jointRows);
  m_system.factor(m_rows, inverseMasses(bodies, work().inverseMass), startInverseInertia);
  m_rows.insert(m_rows.end(), limitRows.begin(), limitRows.end());
  m_systemExact = true;
  makeBorder(bodies, startInverseInertia);
}

void JointGroupSolver::borderAtStart(const std::vector<JointBody>& bodies) {
  makeBorder(bodies, startInverseInertias(bodies));
}

std::vector<Mat3>& JointGroupSolver::startInverseInertias(const std::vector<JointBody>& bodies) {
  std::vector<Mat3>& out = work().startInverseInertia;
  out.clear();
  for (const JointBody& body : bodies) out.push_back(body.startInverseInertia);
  return out;
}

bool JointGroupSolver::mayKeep(const std::vector<JointLink>& links, const JointSolverSettings& settings) const {
  if (!(settings.keepRatio > 0.0)) return false;
  return std::none_of(links.begin(), links.end(),
                      [](const JointLink& l) { return l.inContact || (!l.isCoupling() && axisActs(*l.joint)); });
}

namespace {

// K's entry of two rows: over the bodies they share, m⁻¹ lᵢ·lⱼ + aᵢ·I⁻¹ aⱼ.
double rowCoupling(const JointSolverRow& a, const JointSolverRow& b, const std::vector<JointBody>& bodies,
                   const std::vector<Mat3>& inverseInertia) {
  double k = 0.0;
  for (int sa = 0; sa < a.sideCount(); ++sa) {
    const int body = a.body(sa);
    if (body < 0) continue;
    for (int sb = 0; sb < b.sideCount(); ++sb) {
      if (b.body(sb) != body) continue;
      const auto i = static_cast<std::size_t>(body);
      k += bodies[i].inverseMass * a.linear(sa).dot(b.linear(sb)) + a.angular(sa).dot(inverseInertia[i] * b.angular(sb));
    }
  }
  return k;
}

}  // namespace

bool JointGroupSolver::makeBorder(const std::vector<JointBody>& bodies, const std::vector<Mat3>& inverseInertia) {
  const Eigen::Index joints = m_system.size();
  const Eigen::Index limits = static_cast<Eigen::Index>(m_rows.size()) - joints;
  m_border.ok = joints == 0 || m_system.ok();
  if (!m_border.ok || limits == 0) return m_border.ok;
  BorderNumbers& border = work().border(m_rows.size(), static_cast<std::size_t>(limits));
  border.coupling.resize(joints, limits);
  border.response.resize(joints, limits);
  const auto row = [&](Eigen::Index r) -> const Row& { return m_rows[static_cast<std::size_t>(r)]; };
  for (Eigen::Index j = 0; j < limits; ++j) {
    for (Eigen::Index i = 0; i < joints; ++i)
      border.coupling(i, j) = rowCoupling(row(i), row(joints + j), bodies, inverseInertia);
    if (joints == 0) continue;  // limits alone (ropes): S is K_LL
    Eigen::VectorXd& column = border.column;
    column = border.coupling.col(j);
    m_system.solveInPlace(column);
    border.response.col(j) = column;
  }
  Eigen::MatrixXd& schur = border.schurMatrix;
  schur.resize(limits, limits);
  for (Eigen::Index j = 0; j < limits; ++j)
    for (Eigen::Index i = j; i < limits; ++i) {
      schur(i, j) = rowCoupling(row(joints + i), row(joints + j), bodies, inverseInertia) -
                    border.coupling.col(i).dot(border.response.col(j));
      schur(j, i) = schur(i, j);
    }
  // The same tiny relative regularisation as K's (row_system.cpp): limits
  // that hold one motion twice stay solvable.
  schur.diagonal() *= 1.0 + 1e-10;
  border.schur.compute(schur);
  m_border.ok = border.schur.info() == Eigen::Success;
  return m_border.ok;
}

void JointGroupSolver::solveRows(Eigen::VectorXd& x) const {
  const Eigen::Index joints = m_system.size();
  const Eigen::Index limits = x.size() - joints;
  if (limits == 0) {
    if (joints > 0) m_system.solveInPlace(x);
    return;
  }
  // [K_JJ K_JL; K_LJ K_LL] [x_J; x_L] = [r_J; r_L]: x_J = K_JJ⁻¹ r_J − Y x_L,
  // S x_L = r_L − K_LJ K_JJ⁻¹ r_J, Y = K_JJ⁻¹ K_JL.
  // (Into the border's own vectors, and without Eigen's temporaries:
  // a = b − A c made as a = b, a −= A c, which is what Eigen does with a
  // temporary, to the same bits.)
  const BorderNumbers& border =
      work().bordersBySize[static_cast<std::size_t>(x.size())][static_cast<std::size_t>(limits)];
  Eigen::VectorXd& jointPart = border.jointPart;
  Eigen::VectorXd& limitPart = border.limitPart;
  jointPart = x.head(joints);
  if (joints > 0) m_system.solveInPlace(jointPart);
  limitPart.noalias() = x.tail(limits) - border.coupling.transpose() * jointPart;
  border.schur.solveInPlace(limitPart);
  x.head(joints).noalias() = jointPart - border.response * limitPart;
  x.tail(limits) = limitPart;
}

void JointGroupSolver::actuateAxes(const std::vector<JointLink>& links, std::vector<JointBody>& bodies, double h,
                              const std::vector<Mat3>& inverseInertia, bool atEnd,
                              std::vector<JointLinkResult>& results, bool beforeContacts) {
  // The laws along the axes (axis_actuation.h) act as RATTLE's kicks do:
  // half of the step before the drift, on the rate the drift moves with
  // (the drive's spring at the position the drift reaches), and half after
  // the second half kick, on the rate the step ends with (the spring where
  // the drift left it). So a motor holds its rate, and friction or a drive
  // holds a joint still against a load, at both: nothing creeps.
  //
  // They act together with the joints' rows (m_rows, K as m_system holds
  // it), so that an actuator moves what the joints let it move (an arm
  // about its hinge, not the bob about its own centre). With the joints
  // holding, axis i's rate is
  //   w_i = w_free_i + Σ_j A_ij Λ_j,
  // A_ij = J_i (M⁻¹ − M⁻¹JᵀK⁻¹JM⁻¹) J_jᵀ, and each Λ_i obeys its axis's
  // law. Gauss–Seidel over the axes, each solved exactly given the others:
  // one sweep for a single axis; for coupled axes (an arm's joints) it
  // converges because the laws are monotone and A is positive definite
  // (a convex problem).
  //
  // Joint damping is the exception in an island that touches nothing: its
  // first half is not implicit but acts on the rate the step starts with,
  // as the first half kick's forces act at the start. Explicit Euler over
  // h/2 then implicit Euler over h/2 is a method composed with its adjoint:
  // symmetric and second order (Hairer, Lubich and Wanner, "Geometric
  // Numerical Integration", 2006, ch. II; Störmer–Verlet with a
  // velocity-dependent force), where two implicit halves leave c² h²/4 a
  // step: first order. A spatial arm's links were 1.2e-4 m off their
  // equations of motion after 0.5 s at 1 ms that way, halving with dt
  // (JointArmReference.*).
  const double half = 0.5 * h;
  struct Axis {
    std::size_t link;
    Row row;
    AxisLaw law;
    AxisImpulse impulse;
    double startDamping = 0.0;    // c of the explicit first half (then not in `law`)
    double dampingImpulse = 0.0;  // its impulse, fixed before the laws are solved
  };
  std::vector<Axis> axes;
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    const JointConstraint& joint = *link.joint;
    if (link.isCoupling() || !axisActs(joint)) continue;
    if (link.wholeKick != beforeContacts) continue;
    const double span = beforeContacts ? h : half;
    const JointDef& def = joint.def;
    AxisLaw law;
    law.h = span;
    // The actuator's limits bound whatever it is commanded.
    const JointActuatorLimits& limits = def.actuatorLimits;
    law.motor = def.motor.enabled;
    law.motorTarget = std::clamp(def.motor.targetRate, -limits.rate, limits.rate);
    law.motorCap = std::min(def.motor.maxEffort, limits.effort) * span;
    law.drive = def.drive.enabled;
    law.driveCap = std::min(def.drive.maxEffort, limits.effort) * span;
    if (joint.hasAxis()) law.driveRateLimit = limits.rate;
    law.driveLookahead = atEnd ? 0.0 : h;
    const bool explicitDamping = !atEnd && !beforeContacts && !link.inContact;
    law.damping = explicitDamping ? 0.0 : def.damping;
    law.frictionCap = def.friction * span;
    Axis axis{l, JointSolverRow::of(link.bodyA, link.bodyB, static_cast<int>(l)), law, {}, explicitDamping ? def.damping : 0.0, 0.0};
    const JointSidePose a = sidePose(link, bodies, false, !atEnd);
    const JointSidePose b = sidePose(link, bodies, true, !atEnd);
    joint.limitRow(a, b, axis.row.jacobian);  // the coordinate's row: the axis, or a spring's line
    if (law.drive) axis.law.driveError = driveError(joint, joint.coordinate(a, b));
    axes.push_back(axis);
  }
  if (axes.empty()) return;

  // Unit impulse along each axis, with the joints' reply: the columns of A.
  // An axis the joints lock (a loop's redundant hinge, a limit held) takes
  // no law: nothing along it can move.
  const std::vector<JointBody> start = bodies;
  const auto n = axes.size();
  Eigen::MatrixXd response(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  std::vector<char> locked(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (JointBody& body : bodies) {
      body.linearMomentum.setZero();
      body.angularMomentum.setZero();
    }
    pushAlongRow(axes[i].row, 1.0, bodies);
    const double unconstrained = rowRate(axes[i].row, bodies, inverseInertia);
    if (systemOk()) removeJointRates(bodies, inverseInertia);
    for (std::size_t j = 0; j < n; ++j)
      response(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(i)) = rowRate(axes[j].row, bodies, inverseInertia);
    const auto ii = static_cast<Eigen::Index>(i);
    locked[i] = !(response(ii, ii) > 1e-9 * unconstrained);
  }
  // The free rates: the momenta with the joints' rates removed.
  bodies = start;
  if (systemOk()) removeJointRates(bodies, inverseInertia);
  Eigen::VectorXd freeRate(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) freeRate[static_cast<Eigen::Index>(i)] = rowRate(axes[i].row, bodies, inverseInertia);

  // A drive given as a frequency and damping ratio: k = m ω², c = 2 ζ m ω
  // with m the axis's effective mass or inertia, 1 / A_ii (none on a
  // locked axis).
  for (std::size_t i = 0; i < n; ++i) {
    const JointDrive& drive = links[axes[i].link].joint->def.drive;
    AxisLaw& law = axes[i].law;
    if (!law.drive) continue;
    if (drive.frequency > 0.0) {
      if (locked[i]) continue;
      const double mass = 1.0 / response(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i));
      const double omega = 2.0 * 3.14159265358979323846 * drive.frequency;
      law.driveStiffness = mass * omega * omega;
      law.driveDamping = 2.0 * drive.dampingRatio * mass * omega;
    } else {
      law.driveStiffness = drive.stiffness;
      law.driveDamping = drive.damping;
    }
    law.driveTargetRate = drive.targetRate;
  }

  // Damping's explicit first half: −c (h/2) w₀ on the start's rate w₀ (the
  // momenta the step starts with, tangent to the joints), for small
  // x = c h A_ii; in general −(1 − e⁻ˣ (1 + x/2)) w₀ / A_ii, which differs
  // from it by O(x³) but never pushes an axis past rest, so that with the
  // implicit second half, 1 / (1 + x/2), a lone damped axis decays by
  // exactly e⁻ˣ a step at any c h / I (a strongly damped light link would
  // otherwise turn back at every step).
  if (std::any_of(axes.begin(), axes.end(), [](const Axis& a) { return a.startDamping > 0.0; })) {
    std::vector<JointBody> atStart = start;
    for (JointBody& body : atStart) {
      body.linearMomentum = body.startLinearMomentum;
      body.angularMomentum = body.startAngularMomentum;
    }
    if (systemOk()) removeJointRates(atStart, inverseInertia);
    for (std::size_t i = 0; i < n; ++i) {
      if (locked[i] || !(axes[i].startDamping > 0.0)) continue;
      const double a = response(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i));
      const double x = axes[i].startDamping * h * a;
      const double share = -std::expm1(-x) - 0.5 * x * std::exp(-x);  // 1 − e⁻ˣ (1 + x/2), ≈ x/2
      axes[i].dampingImpulse = -share * rowRate(axes[i].row, atStart, inverseInertia) / a;
      axes[i].impulse.total = axes[i].dampingImpulse;
    }
  }

  constexpr int kSweeps = 200;
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    double change = 0.0, size = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (locked[i]) continue;
      const auto ii = static_cast<Eigen::Index>(i);
      double others = 0.0;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i) others += response(ii, static_cast<Eigen::Index>(j)) * axes[j].impulse.total;
      const double fixed = axes[i].dampingImpulse;
      AxisImpulse next = solveAxisLaw(axes[i].law, freeRate[ii] + others + response(ii, ii) * fixed, response(ii, ii));
      next.total += fixed;
      change = std::max(change, std::abs(next.total - axes[i].impulse.total));
      size = std::max(size, std::abs(next.total));
      axes[i].impulse = next;
    }
    if (n == 1 || change <= 1e-14 * size) break;
  }

  // The impulses into the momenta, then the joints' rates removed again:
  // the same end velocities as A says, by linearity.
  bodies = start;
  for (const Axis& axis : axes) pushAlongRow(axis.row, axis.impulse.total, bodies);
  if (systemOk()) removeJointRates(bodies, inverseInertia);
  for (const Axis& axis : axes) {
    JointLinkResult& result = results[axis.link];
    result.axisImpulse += axis.impulse.actuation;
    result.linearImpulse += axis.impulse.total * axis.row.jacobian.linearB;
    result.angularImpulse += axis.impulse.total * axis.row.jacobian.angularB;
  }
  // A locked axis moves nothing, but its actuator still pushes (a servo or a
  // spring against its stop, a motor stalled): its push at the rate the
  // lock holds is reported as its effort. The lock carries it, so the
  // bodies and the joint's force are the same as without it. (A drive given
  // as a frequency has no gains on an axis of infinite mass: it reports
  // nothing.)
  for (std::size_t i = 0; i < n; ++i)
    if (locked[i]) results[axes[i].link].axisImpulse += actuationAtRate(axes[i].law, freeRate[static_cast<Eigen::Index>(i)]);
}

void JointGroupSolver::actuateBeforeContacts(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                                             double h, std::vector<JointLinkResult>& results, const JointSolver* kept) {
  results.assign(links.size(), JointLinkResult{});
  m_border.ok = true;
  // Nothing acts along an axis (a ragdoll): no K₀ to make.
  if (!std::any_of(links.begin(), links.end(),
                   [](const JointLink& l) { return l.wholeKick && !l.isCoupling() && axisActs(*l.joint); }))
    return;
  m_rows.clear();
  m_limits.clear();
  for (std::size_t l = 0; l < links.size(); ++l) {
    const LinkPoses poses = linkPoses(links[l], bodies, true);
    appendLinkRows(links[l], static_cast<int>(l), poses, links[l].joint->basisAt(poses[0]), m_rows);
  }
  std::vector<Mat3> startInverseInertia;
  startInverseInertia.reserve(bodies.size());
  for (const JointBody& body : bodies) startInverseInertia.push_back(body.startInverseInertia);
  const std::vector<double> inverseMass = inverseMasses(bodies);
  m_jointRows = m_rows.size();
  if (kept != nullptr)
    if (const RowSystem* made = kept->keptFactor(m_rows, inverseMass, startInverseInertia)) m_system = *made;
  m_system.factor(m_rows, inverseMass, startInverseInertia);
  actuateAxes(links, bodies, h, startInverseInertia, false, results, true);
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointSidePose b = sidePose(links[l], bodies, true, true);
    const Vec3 arm = b.rotation * links[l].joint->anchorB;
    results[l].angularImpulse -= arm.cross(results[l].linearImpulse);
  }
}

bool JointGroupSolver::solvePositions(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                                 double h, const JointSolverSettings& settings,
                                 std::vector<JointLinkResult>& results) {
  results.assign(links.size(), JointLinkResult{});
  m_rows.clear();
  m_limits.clear();
  // Room for a limit row per link (the most a step holds), so that a step
  // with more limits held than any before allocates nothing.
  m_limits.reserve(links.size());
  work().keptLimits.reserve(links.size());
  m_border.ok = true;
  m_keepAtEnd = false;  // until this step's momentum projection says
  // The rows at the step's start, and the errors there. An error from the
  // last step's rounding is closed with the rest; a larger one came from
  // outside and is kept by the momentum projection, then removed by the
  // positions-only one (so that it turns into no velocity).
  constexpr double kOutsideError = 1e-9;  // m or rad
  std::vector<JointConstraint::Basis>& bases = work().bases;
  bases.resize(links.size());
  std::vector<double>& targets = work().targets;
  targets.clear();
  bool outsideError = false;
  // A joint that starts beyond a limit (created there, or set there) is
  // held where it is by the momentum projection and brought back by the
  // positions-only one, at most kLimitReturn a step: no velocity comes of
  // it, and a body is not thrown through what it touches.
  m_startBeyond.assign(links.size(), 0.0);
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    const LinkPoses poses = linkPoses(link, bodies, true);
    bases[l] = link.joint->basisAt(poses[0]);
    double errors[kMaxJointRows];
    appendLinkRows(link, static_cast<int>(l), poses, bases[l], m_rows);
    linkErrors(link, poses, bases[l], errors);
    for (int r = 0; r < linkRowCount(link); ++r) {
      const bool outside = std::abs(errors[r]) > kOutsideError;
      targets.push_back(outside ? errors[r] : 0.0);
      outsideError = outsideError || outside;
    }
    if (!link.isCoupling() && link.joint->hasLimit()) {
      const double q = link.joint->coordinate(poses[0], poses[1]);
      if (q < link.joint->limitLower() - kOutsideError) m_startBeyond[l] = q - link.joint->limitLower();
      if (q > link.joint->limitUpper() + kOutsideError) m_startBeyond[l] = q - link.joint->limitUpper();
      outsideError = outsideError || m_startBeyond[l] != 0.0;
    }
  }
  for (JointBody& body : bodies) {
    body.position = body.startPosition;
    body.orientation = body.startOrientation;
  }
  const bool anyLimit = std::any_of(links.begin(), links.end(), [](const JointLink& l) { return !l.isCoupling() && l.joint->hasLimit(); });
  const bool anyAxis = std::any_of(links.begin(), links.end(), [](const JointLink& l) { return !l.isCoupling() && axisActs(*l.joint); });
  if (m_rows.empty() && !anyLimit && !anyAxis) return true;
  const std::size_t jointRows = m_rows.size();
  m_jointRows = jointRows;
  m_rows.reserve(jointRows + links.size());
  work().reserve(jointRows, static_cast<std::size_t>(std::count_if(links.begin(), links.end(), [](const JointLink& l) {
                   return !l.isCoupling() && l.joint->hasLimit();
                 })));
  work().allTargets.reserve(jointRows + links.size());
  work().positionTargets.reserve(jointRows + links.size());
  const std::vector<Mat3>& startInverseInertia = startInverseInertias(bodies);
  // K₀: the last step's end factor when this step starts where it ended
  // (kept, bit-identical); else, for a group that may, the factor of an
  // earlier step with the same pattern, kept while it converges (project);
  // else made here.
  m_keepRatio = mayKeep(links, settings) ? settings.keepRatio : 0.0;
  m_refreshed = false;
  {
    const std::vector<double>& inverseMass = inverseMasses(bodies, work().inverseMass);
    if (m_keepRatio > 0.0 && m_system.ok() && m_system.madeFor(m_rows) &&
        !m_system.madeFrom(m_rows, inverseMass, startInverseInertia)) {
      m_systemExact = false;
    } else {
      m_system.factor(m_rows, inverseMass, startInverseInertia);
      m_systemExact = true;
    }
    makeBorder(bodies, startInverseInertia);  // none yet
  }

  // The motors, drives, damping and friction: their first half, on the
  // velocities the drift will use.
  actuateAxes(links, bodies, h, startInverseInertia, false, results);

  // Steps 1 and 2: from the start with the momenta's velocities; the
  // impulses change the momenta. Limits by active set: a coordinate that
  // the drift carries beyond a bound gets a row holding it there, and a
  // limit row that pulls is dropped; each change solves the step again.
  std::vector<Vec3>& kickedLinear = work().kickedLinear;
  std::vector<Vec3>& kickedAngular = work().kickedAngular;
  kickedLinear.clear();
  kickedAngular.clear();
  for (const JointBody& body : bodies) {
    kickedLinear.push_back(body.linearMomentum);
    kickedAngular.push_back(body.angularMomentum);
  }
  Drift& momenta = work().momenta;
  Eigen::VectorXd* total = nullptr;  // the last round's impulses, by row
  double left = 0.0;
  const bool startedKept = !m_systemExact;
  int firstIterations = 0;
  constexpr int kLimitRounds = 6;
  for (int round = 0; round < kLimitRounds; ++round) {
    clearDrift(momenta);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const JointBody& body = bodies[i];
      momenta.fromPosition.push_back(body.startPosition);
      momenta.fromOrientation.push_back(body.startOrientation);
      momenta.linearVelocity.push_back(body.inverseMass * kickedLinear[i]);
      momenta.angularVelocity.push_back(body.startInverseInertia * kickedAngular[i]);
      momenta.angularMomentum.push_back(kickedAngular[i]);
    }
    momenta.linearImpulse.assign(bodies.size(), Vec3::Zero());
    momenta.angularImpulse.assign(bodies.size(), Vec3::Zero());
    // A limit held where its joint started beyond it (offset from its
    // bound by the start's excess); every other at its bound.
    std::vector<double>& allTargets = work().allTargets;
    allTargets.assign(targets.begin(), targets.end());
    for (const LimitRow& limit : m_limits) allTargets.push_back(heldBeyond(limit));
    total = &sizedVector(work().totalBySize, m_rows.size());
    project(links, bodies, bases, &allTargets, momenta, h, settings, left, *total);
    if (round == 0) firstIterations = m_projectIterations;
    // Which limits the end poses break, and which active ones pull.
    bool changed = false;
    std::vector<LimitRow>& kept = work().keptLimits;
    kept.clear();
    for (std::size_t k = 0; k < m_limits.size(); ++k) {
      const double lambda = (*total)[static_cast<Eigen::Index>(jointRows + k)];
      // A lower bound pushes the coordinate up (λ >= 0), an upper one down.
      if (lambda * m_limits[k].side > 0.0) {
        changed = true;
        continue;
      }
      kept.push_back(m_limits[k]);
    }
    for (std::size_t l = 0; l < links.size(); ++l) {
      const JointLink& link = links[l];
      const JointConstraint& joint = *link.joint;
      if (link.isCoupling() || !joint.hasLimit()) continue;
      const bool active = std::any_of(kept.begin(), kept.end(), [&](const LimitRow& r) { return r.link == static_cast<int>(l); });
      if (active) continue;
      const double q = joint.coordinate(sidePose(link, bodies, false, false), sidePose(link, bodies, true, false));
      const LimitRow lower{static_cast<int>(l), joint.limitLower(), -1};
      const LimitRow upper{static_cast<int>(l), joint.limitUpper(), +1};
      if (q < lower.bound + heldBeyond(lower) - settings.tolerance) {
        kept.push_back(lower);
        changed = true;
      } else if (q > upper.bound + heldBeyond(upper) + settings.tolerance) {
        kept.push_back(upper);
        changed = true;
      }
    }
    // The last round keeps the set it was solved with: the impulses, the
    // rows and the factor below must all be of one set of limits.
    if (!changed || round == kLimitRounds - 1) break;
    m_limits.assign(kept.begin(), kept.end());
    m_rows.resize(jointRows);
    for (const LimitRow& limit : m_limits) {
      const JointLink& link = links[static_cast<std::size_t>(limit.link)];
      JointRow row;
      link.joint->limitRow(sidePose(link, bodies, false, true), sidePose(link, bodies, true, true), row);
      m_rows.push_back(JointSolverRow::of(link.bodyA, link.bodyB, limit.link, row));
    }
    borderAtStart(bodies);  // the limits by their Schur complement: no factorisation
  }
  // The impulses by row, to which the positions-only pass's limit rows add
  // none (a list that keeps its storage, where an Eigen vector would not).
  std::vector<double>& totalRows = work().totalRows;
  totalRows.assign(total->data(), total->data() + total->size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies[i].linearMomentum = kickedLinear[i] + momenta.linearImpulse[i];
    bodies[i].angularMomentum = kickedAngular[i] + momenta.angularImpulse[i];
  }

  // Step 3: the contacts' pseudo-velocities and the outside errors, by
  // moving positions along the same rows (velocities only positions see).
  // A joint that started beyond a limit and is still beyond it comes back
  // by at most kLimitReturn (its limit row is added for this pass if the
  // momentum projection did not hold it).
  std::vector<double>& positionTargets = work().positionTargets;
  positionTargets.assign(jointRows, 0.0);
  {
    bool added = false;
    for (std::size_t l = 0; l < links.size(); ++l) {
      if (m_startBeyond[l] == 0.0) continue;
      const bool held = std::any_of(m_limits.begin(), m_limits.end(), [&](const LimitRow& r) { return r.link == static_cast<int>(l); });
      if (held) continue;
      const JointLink& link = links[l];
      const double q = link.joint->coordinate(sidePose(link, bodies, false, false), sidePose(link, bodies, true, false));
      LimitRow limit{static_cast<int>(l), m_startBeyond[l] < 0.0 ? link.joint->limitLower() : link.joint->limitUpper(),
                     m_startBeyond[l] < 0.0 ? -1 : +1};
      if ((q - limit.bound) * limit.side <= 0.0) continue;  // back within by itself
      m_limits.push_back(limit);
      JointSolverRow row = JointSolverRow::of(link.bodyA, link.bodyB, limit.link);
      link.joint->limitRow(sidePose(link, bodies, false, true), sidePose(link, bodies, true, true), row.jacobian);
      m_rows.push_back(row);
      added = true;
    }
    if (added) {
      borderAtStart(bodies);
      totalRows.resize(m_rows.size(), 0.0);
    }
    for (const LimitRow& limit : m_limits) {
      const JointLink& link = links[static_cast<std::size_t>(limit.link)];
      const double q = link.joint->coordinate(sidePose(link, bodies, false, false), sidePose(link, bodies, true, false));
      const double excess = (q - limit.bound) * limit.side;  // > 0: beyond
      const double step = limitReturn(*link.joint);
      positionTargets.push_back(m_startBeyond[static_cast<std::size_t>(limit.link)] != 0.0 && excess > step
                                    ? limit.side * (excess - step)
                                    : 0.0);
    }
  }
  const bool anyPseudo = std::any_of(bodies.begin(), bodies.end(), [](const JointBody& b) {
    return !b.pseudoLinear.isZero(0.0) || !b.pseudoAngular.isZero(0.0);
  });
  if (anyPseudo || outsideError) {
    // The pass may push a joint that the momentum projection left within
    // its limits past one (contacts pushing a limb out of the ground):
    // such a limit is then held at its bound and the pass done again from
    // the same poses, as the momentum projection's rounds do.
    std::vector<Vec3>& fromPosition = work().fromPosition;
    std::vector<Quaternion>& fromOrientation = work().fromOrientation;
    fromPosition.clear();
    fromOrientation.clear();
    for (const JointBody& body : bodies) {
      fromPosition.push_back(body.position);
      fromOrientation.push_back(body.orientation);
    }
    for (int round = 0; round < kLimitRounds; ++round) {
      Drift& pseudo = work().pseudo;
      clearDrift(pseudo);
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        bodies[i].position = fromPosition[i];
        bodies[i].orientation = fromOrientation[i];
        pseudo.fromPosition.push_back(fromPosition[i]);
        pseudo.fromOrientation.push_back(fromOrientation[i]);
        pseudo.linearVelocity.push_back(bodies[i].pseudoLinear);
        pseudo.angularVelocity.push_back(bodies[i].pseudoAngular);
      }
      pseudo.linearImpulse.assign(bodies.size(), Vec3::Zero());
      pseudo.angularImpulse.assign(bodies.size(), Vec3::Zero());
      double pseudoLeft = 0.0;
      project(links, bodies, bases, &positionTargets, pseudo, h, settings, pseudoLeft,
              sizedVector(work().pseudoTotalBySize, m_rows.size()));
      if (round == kLimitRounds - 1) break;
      bool added = false;
      for (std::size_t l = 0; l < links.size(); ++l) {
        const JointLink& link = links[l];
        const JointConstraint& joint = *link.joint;
        if (link.isCoupling() || !joint.hasLimit()) continue;
        if (std::any_of(m_limits.begin(), m_limits.end(), [&](const LimitRow& r) { return r.link == static_cast<int>(l); }))
          continue;
        const double q = joint.coordinate(sidePose(link, bodies, false, false), sidePose(link, bodies, true, false));
        const LimitRow lower{static_cast<int>(l), joint.limitLower(), -1};
        const LimitRow upper{static_cast<int>(l), joint.limitUpper(), +1};
        const bool below = q < lower.bound - settings.tolerance, above = q > upper.bound + settings.tolerance;
        if (!below && !above) continue;
        const LimitRow& limit = below ? lower : upper;
        m_limits.push_back(limit);
        JointSolverRow row = JointSolverRow::of(link.bodyA, link.bodyB, limit.link);
        joint.limitRow(sidePose(link, bodies, false, true), sidePose(link, bodies, true, true), row.jacobian);
        m_rows.push_back(row);
        positionTargets.push_back(0.0);
        added = true;
      }
      if (!added) break;
      borderAtStart(bodies);
      totalRows.resize(m_rows.size(), 0.0);
    }
  }

  m_keepAtEnd = m_keepRatio > 0.0 && !m_refreshed && (startedKept || firstIterations <= 1);

  // What each joint did to B, and the error it leaves.
  const auto count = static_cast<Eigen::Index>(m_rows.size());
  for (Eigen::Index r = 0; r < count; ++r) {
    const Row& row = m_rows[static_cast<std::size_t>(r)];
    JointLinkResult& result = results[static_cast<std::size_t>(row.link)];
    if (links[static_cast<std::size_t>(row.link)].isCoupling()) {
      result.axisImpulse += totalRows[static_cast<std::size_t>(r)];  // along the follower's axis
      continue;
    }
    result.linearImpulse += totalRows[static_cast<std::size_t>(r)] * row.jacobian.linearB;
    result.angularImpulse += totalRows[static_cast<std::size_t>(r)] * row.jacobian.angularB;
  }
  for (const LimitRow& limit : m_limits) results[static_cast<std::size_t>(limit.link)].atLimit = limit.side;
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    // The couple about B's anchor rather than about its centre of mass.
    const JointSidePose b = sidePose(link, bodies, true, true);
    const Vec3 arm = b.rotation * link.joint->anchorB;
    results[l].angularImpulse -= arm.cross(results[l].linearImpulse);
    double errors[kMaxJointRows];
    linkErrors(link, linkPoses(link, bodies, false), bases[l], errors);
    for (int k = 0; k < linkRowCount(link); ++k) results[l].error = std::max(results[l].error, std::abs(errors[k]));
    if (link.isCoupling()) results[l].couplingError = errors[0];
  }
  return left <= settings.tolerance;
}

void JointGroupSolver::projectVelocities(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                                    const std::vector<Mat3>& inverseInertia, double h,
                                    std::vector<JointLinkResult>& results) {
  m_rows.clear();
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    const LinkPoses poses = linkPoses(link, bodies, false);
    appendLinkRows(link, static_cast<int>(l), poses, link.joint->basisAt(poses[0]), m_rows);
  }
  // K₁ of the joints' rows at the end poses: the projection is exact with
  // it, and the next step, which starts at these poses, finds it as its K₀
  // (RowSystem keeps a factor asked for again with the same inputs). The
  // limits moved into join it as a border (makeBorder), so that it stays
  // the joints' rows' alone.
  //
  // A group that may keep a factor across steps (keepRatio) keeps the one
  // it has while its iterations converge fast enough; K₁ is made when one
  // does not.
  const std::size_t jointRows = m_rows.size();
  m_jointRows = jointRows;
  m_rows.reserve(jointRows + links.size());
  work().endLimits.reserve(links.size());
  const std::vector<double>& inverseMass = inverseMasses(bodies, work().inverseMass);
  bool kept = m_keepAtEnd && m_system.ok() && m_system.madeFor(m_rows) &&
              !m_system.madeFrom(m_rows, inverseMass, inverseInertia);
  if (!kept) m_system.factor(m_rows, inverseMass, inverseInertia);  // none for no rows
  m_systemExact = !kept;
  m_border.ok = true;
  // K₁ of the joints' rows alone, the limits' rows set aside meanwhile.
  const auto makeEndFactor = [&] {
    std::vector<Row>& limitRows = work().limitRows;
    limitRows.assign(m_rows.begin() + static_cast<std::ptrdiff_t>(jointRows), m_rows.end());
    m_rows.resize(jointRows);
    m_system.factor(m_rows, inverseMass, inverseInertia);
    m_rows.insert(m_rows.end(), limitRows.begin(), limitRows.end());
    kept = false;
    m_systemExact = true;
    return makeBorder(bodies, inverseInertia);
  };
  const auto rateOf = [&](const Row& row) { return rowRate(row, bodies, inverseInertia); };
  // A joint held at a limit leaves with no rate into it. Which limits are
  // moved into is looked at before the projection and again after it: the
  // joints' reply can turn a kick into a rate into a limit (gravity's pull
  // on a hinged arm's centre becomes a turn about the hinge once the hinge
  // holds).
  std::vector<int>& endLimits = work().endLimits;  // the links whose limit rows follow the joints' rows
  endLimits.clear();
  const auto addLimitsMovedInto = [&] {
    bool added = false;
    for (std::size_t l = 0; l < links.size(); ++l) {
      const int side = results[l].atLimit;
      if (side == 0 || std::find(endLimits.begin(), endLimits.end(), static_cast<int>(l)) != endLimits.end()) continue;
      const JointLink& link = links[l];
      Row row = JointSolverRow::of(link.bodyA, link.bodyB, static_cast<int>(l));
      link.joint->limitRow(sidePose(link, bodies, false, false), sidePose(link, bodies, true, false), row.jacobian);
      if (rateOf(row) * side > 0.0) {  // moving into it
        m_rows.push_back(row);
        endLimits.push_back(static_cast<int>(l));
        added = true;
      }
    }
    return added;
  };
  const bool axesAct = std::any_of(links.begin(), links.end(), [](const JointLink& l) {
    return !l.isCoupling() && !l.wholeKick && axisActs(*l.joint);
  });
  addLimitsMovedInto();
  for (int round = 0; round < 2; ++round) {
    if (round == 1 && !addLimitsMovedInto()) break;
    if (m_rows.empty() || !makeBorder(bodies, inverseInertia)) break;
    const auto count = static_cast<Eigen::Index>(m_rows.size());
    // With K exact, one solve leaves rates of rounding size; the loop
    // takes what rounding leaves above 1e-13. With a kept factor, each
    // solve must leave at most keepRatio of the rates, else K₁ is made.
    Eigen::VectorXd& impulse = sizedVector(work().rateImpulseBySize, m_rows.size());
    impulse.setZero();
    Eigen::VectorXd& rate = sizedVector(work().rateBySize, m_rows.size());
    double previous = INFINITY;
    constexpr int kIterations = 8;
    for (int exactIterations = 0, keptIterations = 0;;) {
      rowRates(m_rows, bodies, inverseInertia, rate, work().linear, work().angular);
      const double largest = rate.cwiseAbs().maxCoeff();
      if (largest <= 1e-13) break;
      if (kept && (largest > m_keepRatio * previous || keptIterations == kIterations)) {
        if (!makeEndFactor()) break;
        previous = INFINITY;
      }
      if (kept) {
        ++keptIterations;
      } else {
        if (largest >= previous || exactIterations == kIterations) break;
        ++exactIterations;
      }
      previous = largest;
      Eigen::VectorXd& step = sizedVector(work().stepBySize, m_rows.size());
      step = -rate;
      solveRows(step);
      for (Eigen::Index r = 0; r < count; ++r) pushAlongRow(m_rows[static_cast<std::size_t>(r)], step[r], bodies);
      impulse += step;
    }
    for (Eigen::Index r = 0; r < count; ++r) {
      const Row& row = m_rows[static_cast<std::size_t>(r)];
      const double lambda = impulse[r];
      JointLinkResult& result = results[static_cast<std::size_t>(row.link)];
      if (links[static_cast<std::size_t>(row.link)].isCoupling()) {
        result.axisImpulse += lambda;
        continue;
      }
      const JointSidePose b = sidePose(links[static_cast<std::size_t>(row.link)], bodies, true, false);
      const Vec3 arm = b.rotation * links[static_cast<std::size_t>(row.link)].joint->anchorB;
      result.linearImpulse += lambda * row.jacobian.linearB;
      result.angularImpulse += lambda * (row.jacobian.angularB - arm.cross(row.jacobian.linearB));
    }
  }
  if (axesAct) actuateAxesAtEnd(links, bodies, inverseInertia, h, results);
}

void JointGroupSolver::actuateAxesAtEnd(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                                   const std::vector<Mat3>& inverseInertia, double h,
                                   std::vector<JointLinkResult>& results) {
  // The axes' second half, on the rates the step ends with; its impulses
  // on B are taken about B's anchor as the rest.
  std::vector<JointLinkResult> second(links.size());
  actuateAxes(links, bodies, h, inverseInertia, true, second);
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointSidePose b = sidePose(links[l], bodies, true, false);
    const Vec3 arm = b.rotation * links[l].joint->anchorB;
    results[l].axisImpulse += second[l].axisImpulse;
    results[l].linearImpulse += second[l].linearImpulse;
    results[l].angularImpulse += second[l].angularImpulse - arm.cross(second[l].linearImpulse);
  }
}

void JointGrouping::make(const std::vector<JointLink>& links, std::size_t bodyCount) {
  // Union–find over the bodies the links join.
  std::vector<int>& parent = m_parent;
  parent.resize(bodyCount);
  for (std::size_t i = 0; i < bodyCount; ++i) parent[i] = static_cast<int>(i);
  const auto root = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
      i = parent[static_cast<std::size_t>(i)];
    }
    return i;
  };
  for (const JointLink& link : links) {
    const int sides[4] = {link.bodyA, link.bodyB, link.bodyC, link.bodyD};
    int first = -1;
    for (const int side : sides) {
      if (side < 0) continue;
      if (first < 0) {
        first = side;
        continue;
      }
      const int a = root(first), b = root(side);
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  }
  m_groupOfRoot.assign(bodyCount, -1);
  m_count = 0;
  m_localIndex.assign(bodyCount, -1);
  for (std::size_t i = 0; i < bodyCount; ++i) {
    int& group = m_groupOfRoot[static_cast<std::size_t>(root(static_cast<int>(i)))];
    if (group < 0) {
      group = static_cast<int>(m_count++);
      if (m_groups.size() < m_count) m_groups.emplace_back();
      m_groups[m_count - 1].bodies.clear();
      m_groups[m_count - 1].links.clear();
    }
    std::vector<int>& members = m_groups[static_cast<std::size_t>(group)].bodies;
    m_localIndex[i] = static_cast<int>(members.size());
    members.push_back(static_cast<int>(i));
  }
  for (std::size_t l = 0; l < links.size(); ++l) {
    const JointLink& link = links[l];
    const int any = link.bodyA >= 0 ? link.bodyA : link.bodyB >= 0 ? link.bodyB : link.bodyC >= 0 ? link.bodyC : link.bodyD;
    if (any < 0) continue;  // between fixed sides only: nothing to move
    m_groups[static_cast<std::size_t>(m_groupOfRoot[static_cast<std::size_t>(root(any))])].links.push_back(static_cast<int>(l));
  }
}

JointLink inGroup(JointLink link, const std::vector<int>& localIndex) {
  if (link.bodyA >= 0) link.bodyA = localIndex[static_cast<std::size_t>(link.bodyA)];
  if (link.bodyB >= 0) link.bodyB = localIndex[static_cast<std::size_t>(link.bodyB)];
  if (link.bodyC >= 0) link.bodyC = localIndex[static_cast<std::size_t>(link.bodyC)];
  if (link.bodyD >= 0) link.bodyD = localIndex[static_cast<std::size_t>(link.bodyD)];
  return link;
}

bool JointSolver::solvePositions(const std::vector<JointLink>& links, std::vector<JointBody>& bodies, double h,
                                 const JointSolverSettings& settings, std::vector<JointLinkResult>& results) {
  m_groups.make(links, bodies.size());
  m_solvers.resize(std::max<std::size_t>(m_groups.size(), 1));
  for (JointGroupSolver& solver : m_solvers) solver.useWorkspace(&m_workspace);
  if (m_groups.size() <= 1) {  // one group (a chain, an arm): as it is
    return m_solvers[0].solvePositions(links, bodies, h, settings, results);
  }
  results.assign(links.size(), JointLinkResult{});
  bool closed = true;
  for (std::size_t g = 0; g < m_groups.size(); ++g) {
    const JointGroup& group = m_groups[g];
    m_groupBodies.clear();
    for (const int i : group.bodies) m_groupBodies.push_back(bodies[static_cast<std::size_t>(i)]);
    m_groupLinks.clear();
    for (const int l : group.links) {
      m_groupLinks.push_back(inGroup(links[static_cast<std::size_t>(l)], m_groups.localIndex()));
    }
    closed = m_solvers[g].solvePositions(m_groupLinks, m_groupBodies, h, settings, m_groupResults) && closed;
    for (std::size_t k = 0; k < group.bodies.size(); ++k)
      bodies[static_cast<std::size_t>(group.bodies[k])] = m_groupBodies[k];
    for (std::size_t k = 0; k < group.links.size(); ++k)
      results[static_cast<std::size_t>(group.links[k])] = m_groupResults[k];
  }
  return closed;
}

void JointSolver::actuateBeforeContacts(const std::vector<JointLink>& links, std::vector<JointBody>& bodies, double h,
                                        std::vector<JointLinkResult>& results) {
  JointGrouping& groups = m_kickGroups;
  groups.make(links, bodies.size());
  const std::vector<int>& localIndex = groups.localIndex();
  m_kickSolvers.resize(std::max(m_kickSolvers.size(), groups.size()));
  for (JointGroupSolver& solver : m_kickSolvers) solver.useWorkspace(&m_workspace);
  results.assign(links.size(), JointLinkResult{});
  std::vector<JointLink>& groupLinks = m_groupLinks;
  std::vector<JointBody>& groupBodies = m_groupBodies;
  std::vector<JointLinkResult>& groupResults = m_groupResults;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const JointGroup& group = groups[g];
    const bool acts = std::any_of(group.links.begin(), group.links.end(),
                                  [&](int l) { return links[static_cast<std::size_t>(l)].wholeKick; });
    if (!acts) continue;
    groupBodies.clear();
    for (const int i : group.bodies) groupBodies.push_back(bodies[static_cast<std::size_t>(i)]);
    groupLinks.clear();
    for (const int l : group.links) groupLinks.push_back(inGroup(links[static_cast<std::size_t>(l)], localIndex));
    m_kickSolvers[g].actuateBeforeContacts(groupLinks, groupBodies, h, groupResults, this);
    for (std::size_t k = 0; k < group.bodies.size(); ++k)
      bodies[static_cast<std::size_t>(group.bodies[k])] = groupBodies[k];
    for (std::size_t k = 0; k < group.links.size(); ++k)
      results[static_cast<std::size_t>(group.links[k])] = groupResults[k];
  }
}

const RowSystem* JointSolver::keptFactor(const std::vector<JointSolverRow>& rows,
                                         const std::vector<double>& inverseMass,
                                         const std::vector<Mat3>& inverseInertia, bool orSamePattern) const {
  for (const JointGroupSolver& solver : m_solvers)
    if (solver.system().madeFrom(rows, inverseMass, inverseInertia)) return &solver.system();
  if (orSamePattern)
    for (const JointGroupSolver& solver : m_solvers)
      if (solver.system().madeFor(rows)) return &solver.system();
  return nullptr;
}

std::vector<RowSystem::Inputs> JointSolver::factorInputs() const {
  std::vector<RowSystem::Inputs> out;
  out.reserve(m_solvers.size());
  for (const JointGroupSolver& solver : m_solvers) out.push_back(solver.system().inputs());
  return out;
}

void JointSolver::restoreFactors(const std::vector<RowSystem::Inputs>& inputs) {
  m_solvers.assign(inputs.size(), JointGroupSolver{});
  for (std::size_t g = 0; g < inputs.size(); ++g)
    if (inputs[g].made) m_solvers[g].system().factor(inputs[g].rows, inputs[g].inverseMass, inputs[g].inverseInertia);
}

void JointSolver::projectVelocities(const std::vector<JointLink>& links, std::vector<JointBody>& bodies,
                                    const std::vector<Mat3>& inverseInertia, double h,
                                    std::vector<JointLinkResult>& results) {
  for (JointGroupSolver& solver : m_solvers) solver.useWorkspace(&m_workspace);
  if (m_groups.size() <= 1) {
    m_solvers[0].projectVelocities(links, bodies, inverseInertia, h, results);
    return;
  }
  for (std::size_t g = 0; g < m_groups.size(); ++g) {
    const JointGroup& group = m_groups[g];
    m_groupBodies.clear();
    m_groupInertia.clear();
    for (const int i : group.bodies) {
      m_groupBodies.push_back(bodies[static_cast<std::size_t>(i)]);
      m_groupInertia.push_back(inverseInertia[static_cast<std::size_t>(i)]);
    }
    m_groupLinks.clear();
    m_groupResults.clear();
    for (const int l : group.links) {
      m_groupLinks.push_back(inGroup(links[static_cast<std::size_t>(l)], m_groups.localIndex()));
      m_groupResults.push_back(results[static_cast<std::size_t>(l)]);
    }
    m_solvers[g].projectVelocities(m_groupLinks, m_groupBodies, m_groupInertia, h, m_groupResults);
    for (std::size_t k = 0; k < group.bodies.size(); ++k)
      bodies[static_cast<std::size_t>(group.bodies[k])] = m_groupBodies[k];
    for (std::size_t k = 0; k < group.links.size(); ++k)
      results[static_cast<std::size_t>(group.links[k])] = m_groupResults[k];
  }
}

}  // namespace rbsim
