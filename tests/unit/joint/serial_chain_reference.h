#pragma once
// A reference for the joint step that owes nothing to it: a serial chain of
// revolute joints from a fixed base, in its joint coordinates q, with its
// equations of motion
//   M(q) q̈ + h(q, q̇) = τ − D q̇
// (M by the composite-rigid-body algorithm, h by recursive Newton–Euler,
// both in world-frame spatial vectors: Featherstone, "Rigid Body Dynamics
// Algorithms", 2008, ch. 5 and 6; the kinematics as a product of
// exponentials of the joints' twists at q = 0: Murray, Li and Sastry, "A
// Mathematical Introduction to Robotic Manipulation", 1994, ch. 3),
// integrated by classical RK4 at a step far below the world's.
//
// The chain is given as the world is given it, in the configuration where
// every q is 0: each link's mass, centre of mass and inertia about it (world
// frame), and the joint that moves it relative to the link before it (the
// first: relative to the base), by its anchor and axis (world frame),
// viscous damping and a constant effort; and the body's own damping. A positive q turns the link
// right-handed about the axis, as JointState::position counts.
//
// Spatial vectors here are (angular; linear) with the linear part taken at
// the world's origin: a twist (ω; v₀), v₀ the velocity of the body point at
// the origin; a wrench (n₀; f), n₀ the moment about the origin.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "rbsim/physics/body_definition.h"
#include "rbsim/physics/joint_definition.h"
#include "rbsim/physics/math_types.h"

namespace rbsim::testing {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

struct ChainLink {
  double mass = 0.0;                // kg
  Vec3 centre = Vec3::Zero();       // m, world, at q = 0
  Mat3 inertia = Mat3::Identity();  // kg·m², about the centre, world axes, at q = 0
  Vec3 anchor = Vec3::Zero();       // m, world: a point on the link's joint axis at q = 0
  Vec3 axis = Vec3::UnitZ();        // world, at q = 0 (normalised by the chain)
  double damping = 0.0;             // N·m·s/rad
  double effort = 0.0;              // N·m, on the link about the axis
  // The body's own damping, as BodyDef's: dP/dt = −c P, dL/dt = −c' L.
  double linearDamping = 0.0;   // 1/s
  double angularDamping = 0.0;  // 1/s
};

// The link that a body of the world and the joint moving it make, from
// their definitions (the body's mass properties given, not from its shape).
inline ChainLink chainLinkOf(const BodyDef& body, const JointDef& joint) {
  const Mat3 R = body.orientation.toRotationMatrix();
  ChainLink link;
  link.mass = body.mass.value_or(0.0);
  link.centre = body.position + R * body.centerOfMass.value_or(Vec3::Zero());
  link.inertia = R * body.inertia.value_or(Mat3::Zero()) * R.transpose();
  link.anchor = joint.anchor;
  link.axis = joint.axis;
  link.damping = joint.damping;
  link.effort = joint.effort;
  link.linearDamping = body.linearDamping.value_or(0.0);
  link.angularDamping = body.angularDamping.value_or(0.0);
  return link;
}

inline Mat3 skew(const Vec3& v) {
  Mat3 s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

// (ω; v) × (ω'; v'): the motion cross product.
inline Vec6 crossMotion(const Vec6& a, const Vec6& b) {
  Vec6 r;
  r.head<3>() = a.head<3>().cross(b.head<3>());
  r.tail<3>() = a.head<3>().cross(b.tail<3>()) + a.tail<3>().cross(b.head<3>());
  return r;
}

// (ω; v) ×* (n; f): the force cross product.
inline Vec6 crossForce(const Vec6& a, const Vec6& f) {
  Vec6 r;
  r.head<3>() = a.head<3>().cross(f.head<3>()) + a.tail<3>().cross(f.tail<3>());
  r.tail<3>() = a.head<3>().cross(f.tail<3>());
  return r;
}

// A body's spatial inertia about the world's origin: its momentum
// (L₀; P) = I (ω; v₀), with P = m (v₀ + ω × c) and L₀ = I_c ω + c × P.
inline Mat6 spatialInertia(double mass, const Vec3& centre, const Mat3& inertiaAboutCentre) {
  const Mat3 c = skew(centre);
  Mat6 I;
  I.topLeftCorner<3, 3>() = inertiaAboutCentre - mass * c * c;
  I.topRightCorner<3, 3>() = mass * c;
  I.bottomLeftCorner<3, 3>() = -mass * c;
  I.bottomRightCorner<3, 3>() = mass * Mat3::Identity();
  return I;
}

class SerialChainReference {
 public:
  // A rigid motion x ↦ R x + p.
  struct Motion {
    Mat3 R = Mat3::Identity();
    Vec3 p = Vec3::Zero();
    Vec3 apply(const Vec3& x) const { return R * x + p; }
  };

  SerialChainReference(std::vector<ChainLink> links, const Vec3& gravity) : m_links(std::move(links)), m_gravity(gravity) {
    for (ChainLink& link : m_links) link.axis.normalize();
  }

  int dof() const { return static_cast<int>(m_links.size()); }

  // Each link's motion from q = 0 (the product of the exponentials of the
  // joints up to it), and each joint's twist now (its axis carried by the
  // links before it).
  void kinematics(const Eigen::VectorXd& q, std::vector<Motion>& motions, std::vector<Vec6>& twists) const {
    const std::size_t n = m_links.size();
    motions.resize(n);
    twists.resize(n);
    Motion g;
    for (std::size_t i = 0; i < n; ++i) {
      const ChainLink& link = m_links[i];
      // The joint's twist at q = 0, (u; a × u), carried by g.
      const Vec3 u = g.R * link.axis, a = g.apply(link.anchor);
      twists[i] << u, a.cross(u);
      // A turn by q about the line through `anchor` along `axis`.
      Motion turn;
      turn.R = Eigen::AngleAxisd(q[static_cast<Eigen::Index>(i)], link.axis).toRotationMatrix();
      turn.p = link.anchor - turn.R * link.anchor;
      g = Motion{g.R * turn.R, g.R * turn.p + g.p};
      motions[i] = g;
    }
  }

  // The links' centres of mass at q, m, world.
  std::vector<Vec3> centres(const Eigen::VectorXd& q) const {
    std::vector<Motion> motions;
    std::vector<Vec6> twists;
    kinematics(q, motions, twists);
    std::vector<Vec3> result;
    for (std::size_t i = 0; i < m_links.size(); ++i) result.push_back(motions[i].apply(m_links[i].centre));
    return result;
  }

  // M(q) by the composite-rigid-body algorithm: M_ij = S_iᵀ I^c_max(i,j) S_j,
  // I^c_k the spatial inertia of links k, k+1, … together.
  Eigen::MatrixXd massMatrix(const Eigen::VectorXd& q) const {
    std::vector<Motion> motions;
    std::vector<Vec6> S;
    kinematics(q, motions, S);
    const std::vector<Mat6> I = inertias(motions);
    const int n = dof();
    Eigen::MatrixXd M(n, n);
    Mat6 composite = Mat6::Zero();
    for (int k = n - 1; k >= 0; --k) {
      composite += I[static_cast<std::size_t>(k)];
      const Vec6 force = composite * S[static_cast<std::size_t>(k)];
      for (int j = 0; j <= k; ++j) M(j, k) = M(k, j) = S[static_cast<std::size_t>(j)].dot(force);
    }
    return M;
  }

  // The joint efforts that give the accelerations qdd at (q, qd) with gravity
  // acting (recursive Newton–Euler; the base accelerates at −g instead of
  // each link feeling g). h(q, q̇) is inverseDynamics(q, q̇, 0).
  Eigen::VectorXd inverseDynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd) const {
    std::vector<Motion> motions;
    std::vector<Vec6> S;
    kinematics(q, motions, S);
    const std::vector<Mat6> I = inertias(motions);
    const std::size_t n = m_links.size();
    std::vector<Vec6> f(n);
    Vec6 V = Vec6::Zero(), A;
    A << Vec3::Zero(), -m_gravity;
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      // Ṡ_i = V_{i−1} × S_i: the axis moves with the link before it.
      A += S[i] * qdd[k] + crossMotion(V, S[i]) * qd[k];
      V += S[i] * qd[k];
      f[i] = I[i] * A + crossForce(V, I[i] * V);
    }
    Eigen::VectorXd tau(static_cast<Eigen::Index>(n));
    Vec6 F = Vec6::Zero();
    for (std::size_t i = n; i-- > 0;) {
      F += f[i];
      tau[static_cast<Eigen::Index>(i)] = S[i].dot(F);
    }
    return tau;
  }

  // The joint efforts of the bodies' own damping: each body's wrench
  // (−c m v_c at its centre, −c' I_c ω) taken to the joints before it,
  // Q_j = S_j · Σ_{i ≥ j} W_i.
  Eigen::VectorXd bodyDampingEfforts(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    std::vector<Motion> motions;
    std::vector<Vec6> S;
    kinematics(q, motions, S);
    const std::size_t n = m_links.size();
    std::vector<Vec6> W(n);
    Vec6 V = Vec6::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const ChainLink& link = m_links[i];
      V += S[i] * qd[static_cast<Eigen::Index>(i)];
      const Vec3 omega = V.head<3>(), c = motions[i].apply(link.centre);
      const Vec3 force = -link.linearDamping * link.mass * (V.tail<3>() + omega.cross(c));
      const Vec3 couple = -link.angularDamping * (motions[i].R * link.inertia * motions[i].R.transpose() * omega);
      W[i] << couple + c.cross(force), force;
    }
    Eigen::VectorXd Q(static_cast<Eigen::Index>(n));
    Vec6 sum = Vec6::Zero();
    for (std::size_t i = n; i-- > 0;) {
      sum += W[i];
      Q[static_cast<Eigen::Index>(i)] = S[i].dot(sum);
    }
    return Q;
  }

  // q̈ = M⁻¹ (τ − D q̇ − h + Q_bodies).
  Eigen::VectorXd acceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    Eigen::VectorXd rhs = -inverseDynamics(q, qd, Eigen::VectorXd::Zero(dof()));
    for (int i = 0; i < dof(); ++i) rhs[i] += m_links[static_cast<std::size_t>(i)].effort - m_links[static_cast<std::size_t>(i)].damping * qd[i];
    if (std::any_of(m_links.begin(), m_links.end(), [](const ChainLink& l) { return l.linearDamping != 0.0 || l.angularDamping != 0.0; }))
      rhs += bodyDampingEfforts(q, qd);
    return massMatrix(q).llt().solve(rhs);
  }

  // Kinetic plus potential energy, J (for the reference's own check).
  double energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    double potential = 0.0;
    const std::vector<Vec3> c = centres(q);
    for (std::size_t i = 0; i < m_links.size(); ++i) potential -= m_links[i].mass * m_gravity.dot(c[i]);
    return 0.5 * qd.dot(massMatrix(q) * qd) + potential;
  }

  // (q, q̇) after `seconds` from (q, q̇) by RK4 at about `step`.
  void integrate(Eigen::VectorXd& q, Eigen::VectorXd& qd, double seconds, double step) const {
    const long steps = std::max(1L, std::lround(seconds / step));
    const double h = seconds / static_cast<double>(steps);
    for (long s = 0; s < steps; ++s) {
      const Eigen::VectorXd k1q = qd, k1v = acceleration(q, qd);
      const Eigen::VectorXd k2q = qd + 0.5 * h * k1v, k2v = acceleration(q + 0.5 * h * k1q, k2q);
      const Eigen::VectorXd k3q = qd + 0.5 * h * k2v, k3v = acceleration(q + 0.5 * h * k2q, k3q);
      const Eigen::VectorXd k4q = qd + h * k3v, k4v = acceleration(q + h * k3q, k4q);
      q += (h / 6.0) * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
      qd += (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
  }

  // The links' centres of mass at `samples` equal times over `seconds`,
  // released from rest at q = 0 (RK4 at 1e-5 s).
  std::vector<std::vector<Vec3>> centresReleasedFromRest(double seconds, int samples) const {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(dof()), qd = q;
    std::vector<std::vector<Vec3>> sampled;
    for (int s = 0; s < samples; ++s) {
      integrate(q, qd, seconds / samples, 1e-5);
      sampled.push_back(centres(q));
    }
    return sampled;
  }

 private:
  std::vector<Mat6> inertias(const std::vector<Motion>& motions) const {
    std::vector<Mat6> I;
    for (std::size_t i = 0; i < m_links.size(); ++i) {
      const Motion& g = motions[i];
      I.push_back(spatialInertia(m_links[i].mass, g.apply(m_links[i].centre), g.R * m_links[i].inertia * g.R.transpose()));
    }
    return I;
  }

  std::vector<ChainLink> m_links;
  Vec3 m_gravity;
};

}  // namespace rbsim::testing
