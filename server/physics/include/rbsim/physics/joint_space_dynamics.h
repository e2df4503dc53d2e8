#pragma once
// A robot's dynamics in its joint coordinates, from the model the world
// simulates: the bodies as they are (merged links, given inertias), the
// joints' axes and anchors as the world made them, the world's gravity.
// What a model-based controller needs (PyBullet's calculateMassMatrix,
// calculateInverseDynamics and calculateJacobian; MuJoCo's qM, qfrc_bias,
// mj_jac):
//   M(q)        the joint-space mass matrix,
//   h(q, q̇)     the bias forces (gravity, Coriolis and centrifugal),
//   g(q)        the gravity torques alone,
//   τ = M q̈ + h inverse dynamics,
//   J           the geometric Jacobian of a point on a body.
// Computed at the world's configuration when the object is made, in the
// world frame: recursive Newton–Euler (Luh, Walker and Paul 1980) for h, g
// and τ; M as Σ_b J_bᵀ M_b J_b over the bodies (the composite inertia
// written through each body's Jacobian), which the tests check against
// Newton–Euler column by column and against a two-link closed form.
//
// The robot is the world's revolute, prismatic and fixed joints whose names
// start with a prefix ("arm/"), forming a tree from a base. Its joints'
// coordinates are its revolute and prismatic joints in the world's joint
// order, each joint's coordinate and rate as JointState reports them; fixed
// joints hold their child to its parent. A mimic follower is a coordinate
// of its own (its coupling is the caller's: q_f = m q_l + offset).
//
// A base that does not move (the world, a static body) is fixed: n
// coordinates. A base that is a free body (a quadruped's trunk, a
// humanoid's pelvis) floats: 6 + n velocity coordinates, first the base
// frame's origin's velocity (m/s, world) and the base's angular velocity
// (rad/s, world), then the joints' rates; M, h, g and J are then
// (6 + n)-sized, and the base rows of h and g are the wrench (N, then N·m
// about the base frame's origin, world) that would hold the base's
// acceleration at zero. The base frame is the frame the base body was
// given in (a URDF root link's). Nothing acts on the floating base but
// gravity and the joints: M ν̇ + h = (0, τ) is the robot in free flight.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "rbsim/physics/expected.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

class World;

class JointSpaceDynamics {
 public:
  // The robot of the joints named "<prefix>…". Errors: no such joint; a
  // spherical or distance joint among them; a body that two of its joints
  // move (not a tree); two bases; a floating base that another joint holds
  // (it is not free); a joint whose body is frozen.
  static Expected<JointSpaceDynamics> ofRobot(const World& world, std::string_view prefix);

  // The coordinates' joints, in order.
  const std::vector<std::string>& jointNames() const { return m_jointNames; }
  // Whether the base floats, and the size of the velocity coordinates:
  // n for a fixed base, 6 + n for a floating one.
  bool floatingBase() const { return m_floating; }
  int dofCount() const { return static_cast<int>(m_qd.size()); }
  const Eigen::VectorXd& positions() const { return m_q; }    // rad or m: the joints' (n)
  // The velocity coordinates: (base origin's velocity, base's angular
  // velocity,) then the joints' rates, rad/s or m/s.
  const Eigen::VectorXd& velocities() const { return m_qd; }
  // The base body ("" for the world) and the origin of its frame, m, world.
  const std::string& baseName() const { return m_baseName; }
  const Vec3& baseOrigin() const { return m_baseOrigin; }

  Eigen::MatrixXd massMatrix() const;      // kg·m² (rad) or kg (m), symmetric positive definite
  Eigen::VectorXd biasForces() const;      // N·m or N: h(q, q̇)
  Eigen::VectorXd gravityTorques() const;  // N·m or N: g(q), the efforts that hold the robot still
  // M q̈ + h: the efforts that give the accelerations `qdd` at the current
  // state (none but gravity acting otherwise).
  Eigen::VectorXd inverseDynamics(const Eigen::VectorXd& qdd) const;
  // The 6 × n Jacobian of the point `worldPoint` fixed on body `body` (one
  // of the robot's, or its base: zeros): rows 0–2 the point's velocity,
  // 3–5 the body's angular velocity, both world frame, per q̇.
  Expected<Eigen::MatrixXd> jacobian(std::string_view body, const Vec3& worldPoint) const;
  // The robot's bodies, parents before children: a floating base first,
  // a fixed base not at all.
  std::vector<std::string> bodyNames() const;

 private:
  // One body of the robot and the joint that carries it.
  struct Link {
    std::string name;
    int parent = -1;      // link index; -1: the base (a floating base is link 0, its own parent -1)
    int coordinate = -1;  // column of the joint's rate; -1: a fixed joint or the floating base
    bool prismatic = false;
    Vec3 axis = Vec3::UnitZ();      // world
    Vec3 anchor = Vec3::Zero();     // m, world: the joint's point on the parent
    Vec3 center = Vec3::Zero();     // m, world: the body's centre of mass
    double mass = 0.0;              // kg
    Mat3 inertia = Mat3::Zero();    // kg·m², world, about the centre of mass
  };
  // Newton–Euler with the accelerations `qdd`, the rates `qd` and gravity
  // scaled by `gravityScale` (0: none).
  Eigen::VectorXd newtonEuler(const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd, double gravityScale) const;
  // The columns of a point's Jacobian on link `link` into `out` (6 × n).
  void pointJacobian(int link, const Vec3& point, Eigen::MatrixXd& out) const;

  std::vector<Link> m_links;  // parents before children; a floating base is link 0
  std::vector<std::string> m_jointNames;
  Eigen::VectorXd m_q, m_qd;
  Vec3 m_gravity = Vec3::Zero();
  bool m_floating = false;
  std::string m_baseName;
  Vec3 m_baseOrigin = Vec3::Zero();  // the floating base link's anchor
};

}  // namespace rbsim
