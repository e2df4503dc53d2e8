// Joint-space dynamics (rbsim/physics/joint_space_dynamics.h) against
// closed forms and against the simulation itself: a planar two-link arm's
// M(q), h(q, q̇) and gravity torques to 1e-9 relative of the textbook
// formulas; on a spatial arm with unequal inertias and skew axes, M
// symmetric positive definite and equal column by column to Newton–Euler,
// the Jacobian giving the bodies' own velocities, and the efforts of
// inverse dynamics reproducing the accelerations asked for in one step, to
// the step's first order in dt. A floating base (a free trunk with two
// legs): M ν is the whole robot's momentum and angular momentum, the base
// rows of g are gravity's wrench on it, the Jacobian gives every body's
// velocity, and M ν̇ + h = (0, τ) predicts the free flight the simulation
// takes, to the step's first order.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdio>
#include <string>

#include "joint/joint_test_worlds.h"
#include "rbsim/physics/joint_space_dynamics.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::hinge;

constexpr double kG = 9.81;

// A planar two-link arm in the x–y plane, hinges along z, gravity along −y:
// link i a box of length l_i and mass m_i, its centre at half its length.
// q1 from +x, q2 relative to link 1; the bodies placed and moving as (q, q̇)
// say.
struct TwoLink {
  double l1 = 0.8, l2 = 0.6, m1 = 2.0, m2 = 1.5;
  World world;
  TwoLink(double q1, double q2, double qd1, double qd2) : world(settings()) {
    const double a1 = q1, a2 = q1 + q2;
    const Vec3 d1(std::cos(a1), std::sin(a1), 0), d2(std::cos(a2), std::sin(a2), 0);
    const Vec3 elbow = l1 * d1;
    BodyDef one, two;
    one.name = "r/link1";
    one.shape = BoxShape{Vec3(0.5 * l1, 0.03, 0.02)};
    one.mass = m1;
    one.position = 0.5 * l1 * d1;
    one.orientation = Quaternion::fromAxisAngle(Vec3::UnitZ(), a1);
    one.angularVelocity = Vec3(0, 0, qd1);
    one.linearVelocity = Vec3(0, 0, qd1).cross(one.position);
    two.name = "r/link2";
    two.shape = BoxShape{Vec3(0.5 * l2, 0.03, 0.02)};
    two.mass = m2;
    two.position = elbow + 0.5 * l2 * d2;
    two.orientation = Quaternion::fromAxisAngle(Vec3::UnitZ(), a2);
    two.angularVelocity = Vec3(0, 0, qd1 + qd2);
    two.linearVelocity = Vec3(0, 0, qd1).cross(elbow) + Vec3(0, 0, qd1 + qd2).cross(two.position - elbow);
    const BodyId b1 = world.createBody(one).value(), b2 = world.createBody(two).value();
    JointDef shoulder = hinge("r/shoulder", BodyId{}, b1, Vec3::Zero(), Vec3::UnitZ());
    shoulder.position = q1;
    JointDef elbowJoint = hinge("r/elbow", b1, b2, elbow, Vec3::UnitZ());
    elbowJoint.position = q2;
    addJoint(world, shoulder);
    addJoint(world, elbowJoint);
  }
  static WorldSettings settings() {
    WorldSettings s;
    s.gravity = Vec3(0, -kG, 0);
    s.contact.sleeping = false;
    return s;
  }
  double inertia(int link) const {  // about the centre of mass, along z
    return world.body(world.findBody(link == 1 ? "r/link1" : "r/link2")).inertiaWorld()(2, 2);
  }
};

TEST(JointSpaceDynamics, ATwoLinkArmMatchesTheClosedForm) {
  for (const auto& [q1, q2, qd1, qd2] : {std::array<double, 4>{0.3, 0.9, 1.1, -0.7},
                                         std::array<double, 4>{-1.2, 2.1, -0.4, 2.5},
                                         std::array<double, 4>{0.0, 0.0, 0.0, 0.0}}) {
    SCOPED_TRACE(::testing::Message() << "q " << q1 << " " << q2 << ", q̇ " << qd1 << " " << qd2);
    TwoLink arm(q1, q2, qd1, qd2);
    const Expected<JointSpaceDynamics> dynamics = JointSpaceDynamics::ofRobot(arm.world, "r/");
    ASSERT_TRUE(dynamics.ok()) << dynamics.error().message;
    ASSERT_EQ(dynamics->jointNames(), (std::vector<std::string>{"r/shoulder", "r/elbow"}));
    EXPECT_NEAR(dynamics->positions()[0], q1, 1e-12);
    EXPECT_NEAR(dynamics->positions()[1], q2, 1e-12);
    EXPECT_NEAR(dynamics->velocities()[0], qd1, 1e-12);
    EXPECT_NEAR(dynamics->velocities()[1], qd2, 1e-12);
    // The textbook planar 2R arm (Spong, Hutchinson and Vidyasagar, "Robot
    // Modeling and Control", §7.4), centres at half length.
    const double lc1 = 0.5 * arm.l1, lc2 = 0.5 * arm.l2, I1 = arm.inertia(1), I2 = arm.inertia(2);
    const double m2 = arm.m2, l1 = arm.l1, c2 = std::cos(q2), s2 = std::sin(q2);
    Eigen::Matrix2d M;
    M(0, 0) = arm.m1 * lc1 * lc1 + m2 * (l1 * l1 + lc2 * lc2 + 2 * l1 * lc2 * c2) + I1 + I2;
    M(0, 1) = M(1, 0) = m2 * (lc2 * lc2 + l1 * lc2 * c2) + I2;
    M(1, 1) = m2 * lc2 * lc2 + I2;
    const double hC = -m2 * l1 * lc2 * s2;
    Eigen::Vector2d g;
    g[0] = (arm.m1 * lc1 + m2 * l1) * kG * std::cos(q1) + m2 * lc2 * kG * std::cos(q1 + q2);
    g[1] = m2 * lc2 * kG * std::cos(q1 + q2);
    Eigen::Vector2d h;
    h[0] = hC * (2 * qd1 * qd2 + qd2 * qd2) + g[0];
    h[1] = -hC * qd1 * qd1 + g[1];
    const Eigen::MatrixXd mass = dynamics->massMatrix();
    EXPECT_LT((mass - M).cwiseAbs().maxCoeff(), 1e-9 * M.cwiseAbs().maxCoeff()) << mass << "\nvs\n" << M;
    EXPECT_LT((dynamics->gravityTorques() - g).cwiseAbs().maxCoeff(), 1e-9 * (1 + g.cwiseAbs().maxCoeff()));
    EXPECT_LT((dynamics->biasForces() - h).cwiseAbs().maxCoeff(), 1e-9 * (1 + h.cwiseAbs().maxCoeff()))
        << dynamics->biasForces().transpose() << " vs " << h.transpose();
  }
}

// A spatial arm: four links with unequal principal moments on hinges along
// z, y, a skew axis and a slider, fixed to the world; moving.
World spatialArm(double dt) {
  WorldSettings settings;
  settings.dt = dt;
  settings.gravity = Vec3(0, 0, -kG);
  settings.contact.sleeping = false;
  World world(settings);
  const BodyId a = addBody(world, "s/a", BoxShape{Vec3(0.05, 0.06, 0.2)}, 3.0, Vec3(0, 0, 0.2),
                           Quaternion::fromAxisAngle(Vec3(1, 2, 0).normalized(), 0.2));
  const BodyId b = addBody(world, "s/b", BoxShape{Vec3(0.25, 0.04, 0.03)}, 2.0, Vec3(0.25, 0, 0.42),
                           Quaternion::fromAxisAngle(Vec3(0, 1, 1).normalized(), 0.3));
  const BodyId c = addBody(world, "s/c", BoxShape{Vec3(0.03, 0.2, 0.05)}, 1.2, Vec3(0.5, 0.2, 0.42));
  const BodyId d = addBody(world, "s/d", BoxShape{Vec3(0.04, 0.04, 0.1)}, 0.6, Vec3(0.5, 0.42, 0.35));
  JointDef j1 = hinge("s/j1", BodyId{}, a, Vec3(0, 0, 0), Vec3::UnitZ());
  JointDef j2 = hinge("s/j2", a, b, Vec3(0, 0, 0.42), Vec3::UnitY());
  JointDef j3 = hinge("s/j3", b, c, Vec3(0.5, 0, 0.42), Vec3(1, 0.3, 0.2).normalized());
  JointDef j4 = testing::slider("s/j4", c, d, Vec3(0.5, 0.42, 0.42), Vec3(0, 0.2, -1).normalized());
  for (const JointDef& def : {j1, j2, j3, j4}) addJoint(world, def);
  return world;
}

// Sets the arm moving: efforts for a while (no damping, no friction).
void setMoving(World& world) {
  const char* names[] = {"s/j1", "s/j2", "s/j3", "s/j4"};
  const double efforts[] = {2.0, -6.0, 1.5, 3.0};
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(world.setJointEffort(world.findJoint(names[k]), efforts[k]).ok());
  const int steps = static_cast<int>(std::lround(0.15 / world.settings().dt));
  for (int k = 0; k < steps; ++k) world.step();
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(world.setJointEffort(world.findJoint(names[k]), 0.0).ok());
}

TEST(JointSpaceDynamics, TheMassMatrixIsNewtonEulersAndPositiveDefinite) {
  World world = spatialArm(1e-3);
  setMoving(world);
  const Expected<JointSpaceDynamics> dynamics = JointSpaceDynamics::ofRobot(world, "s/");
  ASSERT_TRUE(dynamics.ok()) << dynamics.error().message;
  ASSERT_EQ(dynamics->dofCount(), 4);
  EXPECT_GT(dynamics->velocities().cwiseAbs().minCoeff(), 0.05) << "every joint moves";
  const Eigen::MatrixXd mass = dynamics->massMatrix();
  EXPECT_LT((mass - mass.transpose()).cwiseAbs().maxCoeff(), 1e-12 * mass.cwiseAbs().maxCoeff());
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(mass).info(), Eigen::Success);
  // Newton–Euler with a unit acceleration of one joint, less the bias: M's
  // column (the two algorithms share nothing but the model).
  const Eigen::VectorXd bias = dynamics->biasForces();
  for (int k = 0; k < 4; ++k) {
    const Eigen::VectorXd column = dynamics->inverseDynamics(Eigen::VectorXd::Unit(4, k)) - bias;
    EXPECT_LT((column - mass.col(k)).cwiseAbs().maxCoeff(), 1e-9 * mass.cwiseAbs().maxCoeff()) << "column " << k;
  }
}

TEST(JointSpaceDynamics, TheJacobianGivesTheBodiesOwnVelocities) {
  World world = spatialArm(1e-3);
  setMoving(world);
  const Expected<JointSpaceDynamics> dynamics = JointSpaceDynamics::ofRobot(world, "s/");
  ASSERT_TRUE(dynamics.ok()) << dynamics.error().message;
  for (const std::string& name : dynamics->bodyNames()) {
    const BodyView body = world.body(world.findBody(name));
    const Vec3 point = body.bodyToWorld(Vec3(0.03, -0.02, 0.05));  // a point fixed on the body
    const Expected<Eigen::MatrixXd> jacobian = dynamics->jacobian(name, point);
    ASSERT_TRUE(jacobian.ok()) << jacobian.error().message;
    const Eigen::VectorXd twist = *jacobian * dynamics->velocities();
    EXPECT_LT((twist.head<3>() - body.velocityAtPoint(point)).norm(), 1e-9) << name;
    EXPECT_LT((twist.tail<3>() - body.angularVelocity()).norm(), 1e-9) << name;
  }
  EXPECT_FALSE(dynamics->jacobian("nobody", Vec3::Zero()).ok());
}

TEST(JointSpaceDynamics, InverseDynamicsEffortsGiveTheAccelerationsAskedFor) {
  // τ = M q̈ + h applied as the joints' efforts: after one step the rates
  // changed by q̈ dt, to the step's first order (the state moves within the
  // step): the error at 0.5 ms about half that at 1 ms.
  const Eigen::Vector4d wanted(1.5, -2.0, 3.0, 0.8);  // rad/s², m/s²
  double errors[2];
  int k = 0;
  for (const double dt : {1e-3, 5e-4}) {
    World world = spatialArm(dt);
    setMoving(world);
    const Expected<JointSpaceDynamics> dynamics = JointSpaceDynamics::ofRobot(world, "s/");
    ASSERT_TRUE(dynamics.ok()) << dynamics.error().message;
    const Eigen::VectorXd tau = dynamics->inverseDynamics(wanted);
    for (int j = 0; j < 4; ++j)
      ASSERT_TRUE(world.setJointEffort(world.findJoint(dynamics->jointNames()[static_cast<std::size_t>(j)]), tau[j]).ok());
    world.step();
    const Expected<JointSpaceDynamics> after = JointSpaceDynamics::ofRobot(world, "s/");
    ASSERT_TRUE(after.ok());
    const Eigen::VectorXd measured = (after->velocities() - dynamics->velocities()) / dt;
    errors[k++] = (measured - wanted).cwiseAbs().maxCoeff();
    // Without the efforts the accelerations would be M⁻¹(−h): far off.
    const Eigen::VectorXd passive = dynamics->massMatrix().llt().solve(-dynamics->biasForces());
    EXPECT_GT((passive - wanted).cwiseAbs().maxCoeff(), 1.0);
  }
  std::printf("inverse dynamics: worst acceleration error %.4g rad/s² at 1 ms, %.4g at 0.5 ms\n", errors[0], errors[1]);
  // Within 5 % of the largest acceleration asked for at 1 ms (0.145 rad/s²
  // measured), and halving with dt: the efforts are right to the step's
  // order, the difference the state's own motion within the step.
  EXPECT_LT(errors[0], 0.05 * wanted.cwiseAbs().maxCoeff()) << "rad/s² at 1 ms";
  EXPECT_GT(errors[1], 0.4 * errors[0]) << "first order: " << errors[1] << " at 0.5 ms vs " << errors[0];
  EXPECT_LT(errors[1], 0.6 * errors[0]) << "first order: " << errors[1] << " at 0.5 ms vs " << errors[0];
}

// A floating robot: a free trunk whose frame is not at its centre of mass
// (given mass properties), tumbling and drifting, with a leg on a skew
// hinge and a slider below it, and a second leg on a hinge; set moving by
// efforts.
World floatingRobot(double dt) {
  WorldSettings settings;
  settings.dt = dt;
  settings.gravity = Vec3(0, 0, -kG);
  settings.contact.sleeping = false;
  World world(settings);
  BodyDef trunk;
  trunk.name = "q/trunk";
  trunk.shape = BoxShape{Vec3(0.3, 0.12, 0.08)};
  trunk.mass = 6.0;
  trunk.inertia = Vec3(0.04, 0.12, 0.14).asDiagonal().toDenseMatrix();
  trunk.centerOfMass = Vec3(0.05, -0.02, 0.01);
  trunk.position = Vec3(0, 0, 1);
  trunk.orientation = Quaternion::fromAxisAngle(Vec3(1, 1, 0).normalized(), 0.3);
  trunk.linearVelocity = Vec3(0.4, -0.2, 1.0);
  trunk.angularVelocity = Vec3(0.5, -1.0, 0.7);
  trunk.collides = false;
  const BodyId body = world.createBody(trunk).value();
  const Vec3 hipA(0.25, 0.1, 0.95);
  const BodyId thigh = addBody(world, "q/thigh", BoxShape{Vec3(0.03, 0.04, 0.12)}, 1.0, hipA + Vec3(0, 0, -0.12));
  const BodyId shin = addBody(world, "q/shin", BoxShape{Vec3(0.02, 0.02, 0.1)}, 0.5, hipA + Vec3(0, 0, -0.32));
  const BodyId other = addBody(world, "q/other", BoxShape{Vec3(0.03, 0.03, 0.15)}, 0.8, Vec3(-0.25, -0.1, 0.8));
  addJoint(world, hinge("q/hip", body, thigh, hipA, Vec3(0.2, 1, 0.1).normalized()));
  addJoint(world, testing::slider("q/knee", thigh, shin, hipA + Vec3(0, 0, -0.24), Vec3(0, 0.1, 1).normalized()));
  addJoint(world, hinge("q/hip2", body, other, Vec3(-0.25, -0.1, 0.95), Vec3::UnitX()));
  const char* names[] = {"q/hip", "q/knee", "q/hip2"};
  const double efforts[] = {1.5, 4.0, -1.0};
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(world.setJointEffort(world.findJoint(names[k]), efforts[k]).ok());
  const int steps = static_cast<int>(std::lround(0.1 / dt));
  for (int k = 0; k < steps; ++k) world.step();
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(world.setJointEffort(world.findJoint(names[k]), 0.0).ok());
  return world;
}

TEST(JointSpaceDynamics, AFloatingBasesMomentumAndGravityAreTheWholeRobots) {
  const World world = floatingRobot(1e-3);
  const Expected<JointSpaceDynamics> dynamics = JointSpaceDynamics::ofRobot(world, "q/");
  ASSERT_TRUE(dynamics.ok()) << dynamics.error().message;
  ASSERT_TRUE(dynamics->floatingBase());
  EXPECT_EQ(dynamics->baseName(), "q/trunk");
  ASSERT_EQ(dynamics->dofCount(), 9);
  EXPECT_EQ(dynamics->jointNames().size(), 3u);
  const BodyView trunk = world.body(world.findBody("q/trunk"));
  EXPECT_GT((dynamics->baseOrigin() - trunk.position()).norm(), 0.04) << "the frame's origin, not the centre of mass";

  // M ν: the robot's momentum, and its angular momentum about the base origin.
  const Eigen::VectorXd generalized = dynamics->massMatrix() * dynamics->velocities();
  Vec3 momentum = Vec3::Zero(), angular = Vec3::Zero(), weight = Vec3::Zero(), moment = Vec3::Zero();
  double mass = 0.0;
  for (const std::string& name : dynamics->bodyNames()) {
    const BodyView body = world.body(world.findBody(name));
    const Vec3 r = body.position() - dynamics->baseOrigin();
    momentum += body.linearMomentum();
    angular += body.angularMomentum() + r.cross(body.linearMomentum());
    weight += body.mass() * world.settings().gravity;
    moment += r.cross(body.mass() * world.settings().gravity);
    mass += body.mass();
  }
  EXPECT_EQ(dynamics->bodyNames().size(), 4u);
  EXPECT_LT((generalized.head<3>() - momentum).norm(), 1e-9 * momentum.norm()) << generalized.head<3>().transpose();
  EXPECT_LT((generalized.segment<3>(3) - angular).norm(), 1e-9 * angular.norm());
  EXPECT_LT((dynamics->massMatrix().topLeftCorner<3, 3>() - mass * Mat3::Identity()).norm(), 1e-12);
  // g's base rows: the wrench that holds the whole robot up.
  const Eigen::VectorXd gravity = dynamics->gravityTorques();
  EXPECT_LT((gravity.head<3>() + weight).norm(), 1e-9 * weight.norm());
  EXPECT_LT((gravity.segment<3>(3) + moment).norm(), 1e-9 * (1 + moment.norm()));
  // Symmetric positive definite, and the Jacobian gives each body's velocity.
  const Eigen::MatrixXd M = dynamics->massMatrix();
  EXPECT_LT((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(M.llt().info(), Eigen::Success);
  for (const std::string& name : dynamics->bodyNames()) {
    const BodyView body = world.body(world.findBody(name));
    const Vec3 point = body.bodyToWorld(Vec3(0.02, 0.03, -0.04));
    const Eigen::VectorXd twist = *dynamics->jacobian(name, point) * dynamics->velocities();
    EXPECT_LT((twist.head<3>() - body.velocityAtPoint(point)).norm(), 1e-9) << name;
    EXPECT_LT((twist.tail<3>() - body.angularVelocity()).norm(), 1e-9) << name;
  }
}

TEST(JointSpaceDynamics, AFloatingRobotFliesAsMNuDotPlusHEqualsTheJointEffortsSay) {
  // ν̇ = M⁻¹((0, τ) − h) against the simulation's velocity change over one
  // step, to the step's first order.
  const Eigen::Vector3d tau(2.0, -5.0, 1.0);
  double errors[2], largest[2];
  int k = 0;
  for (const double dt : {1e-3, 5e-4}) {
    World world = floatingRobot(dt);
    const Expected<JointSpaceDynamics> before = JointSpaceDynamics::ofRobot(world, "q/");
    ASSERT_TRUE(before.ok()) << before.error().message;
    Eigen::VectorXd applied = Eigen::VectorXd::Zero(9);
    applied.tail<3>() = tau;
    const Eigen::VectorXd predicted = before->massMatrix().llt().solve(applied - before->biasForces());
    for (int j = 0; j < 3; ++j)
      ASSERT_TRUE(world.setJointEffort(world.findJoint(before->jointNames()[static_cast<std::size_t>(j)]), tau[j]).ok());
    world.step();
    const Expected<JointSpaceDynamics> after = JointSpaceDynamics::ofRobot(world, "q/");
    ASSERT_TRUE(after.ok());
    // The base origin's velocity: of the material point that was the origin.
    Eigen::VectorXd measured = (after->velocities() - before->velocities()) / dt;
    const BodyView trunk = world.body(world.findBody("q/trunk"));
    measured.head<3>() = (trunk.velocityAtPoint(after->baseOrigin()) - before->velocities().head<3>()) / dt;
    largest[k] = predicted.cwiseAbs().maxCoeff();
    errors[k++] = (measured - predicted).cwiseAbs().maxCoeff();
    EXPECT_GT(predicted.tail<3>().cwiseAbs().maxCoeff(), 1.0) << "the efforts accelerate the joints";
  }
  std::printf("floating base: worst acceleration error %.4g at 1 ms, %.4g at 0.5 ms, of accelerations up to %.4g\n",
              errors[0], errors[1], largest[0]);
  EXPECT_LT(errors[0], 0.01 * largest[0]) << "0.34 % measured";
  EXPECT_GT(errors[1], 0.4 * errors[0]) << "first order";
  EXPECT_LT(errors[1], 0.6 * errors[0]) << "first order";
}

TEST(JointSpaceDynamics, RefusesWhatIsNotATree) {
  WorldSettings settings;
  World world(settings);
  EXPECT_NE(JointSpaceDynamics::ofRobot(world, "r/").error().message.find("the world has no joint named so"),
            std::string::npos);
  const BodyId trunk = addBody(world, "f/trunk", BoxShape{Vec3(0.2, 0.1, 0.1)}, 5.0, Vec3(0, 0, 1));
  const BodyId leg = addBody(world, "f/leg", BoxShape{Vec3(0.05, 0.05, 0.2)}, 1.0, Vec3(0, 0, 0.7));
  addJoint(world, hinge("f/hip", trunk, leg, Vec3(0, 0, 0.9), Vec3::UnitY()));
  EXPECT_TRUE(JointSpaceDynamics::ofRobot(world, "f/").ok()) << "a free trunk: a floating base";
  addJoint(world, hinge("tether", BodyId{}, trunk, Vec3(0, 0, 1.1), Vec3::UnitX()));
  EXPECT_NE(JointSpaceDynamics::ofRobot(world, "f/").error().message.find("a floating base must be free"),
            std::string::npos);
  const BodyId arm = addBody(world, "f/arm", BoxShape{Vec3(0.05, 0.05, 0.2)}, 1.0, Vec3(1, 0, 0.7));
  addJoint(world, hinge("f/shoulder", BodyId{}, arm, Vec3(1, 0, 0.9), Vec3::UnitY()));
  EXPECT_NE(JointSpaceDynamics::ofRobot(world, "f/").error().message.find("two bases"), std::string::npos);
  JointDef ball;
  ball.name = "b/ball";
  ball.type = JointType::Spherical;
  ball.bodyB = addBody(world, "b/bob", SphereShape{0.1}, 1.0, Vec3(3, 0, 0));
  ball.anchor = Vec3(3, 0, 1);
  addJoint(world, ball);
  EXPECT_NE(JointSpaceDynamics::ofRobot(world, "b/").error().message.find("is spherical"), std::string::npos);
}

}  // namespace
}  // namespace rbsim
