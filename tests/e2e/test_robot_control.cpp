// One robot commanded and read whole over LCM (issue 37) against
// config/worlds/robot_arm.yaml, through rbsim::client::Robot: computed-torque
// tracking in lock step at 1 kHz (the acceptance test, and the C++
// example that does it), a command refused whole, a command acting from its
// apply_at_step, robot_state_t against joints_t of the same step, the state
// at its own rate, and the dynamics it carries against the physics library's
// JointSpaceDynamics at the same state. AckStore (no server) beside them.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <rbsim/ack_t.hpp>
#include <rbsim/joints_t.hpp>
#include <rbsim/robot_command_t.hpp>
#include <rbsim/robot_state_t.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/config_loader.h"
#include "e2e_paths.h"
#include "rbsim/client/ack_store.h"
#include "rbsim/client/robot.h"
#include "rbsim/physics/joint_space_dynamics.h"
#include "rbsim/physics/world.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

const std::string kArmWorld = std::string(kConfigWorldsDir) + "/robot_arm.yaml";
constexpr int kJoints = 7;

class RobotControl : public ServerTest {
 protected:
  // rbserver on the arm (paused unless `arguments` say otherwise), every
  // robot_state_t and joints_t kept by step, and a Robot commanding "arm".
  void start(const std::vector<std::string>& arguments = {"--paused"}) {
    startServer(kArmWorld, arguments);
    client()
        .lcm()
        .subscribe(client().channel("ROBOT_STATE"), &RobotControl::onRobotState, this)
        ->setQueueCapacity(100000);
    client().onJoints([this](const rbsim::joints_t& joints) { m_joints[joints.step] = joints; });
    client::ClientOptions options;
    options.url = kUrl;
    options.clientId = "e2e-robot";
    m_robot = std::make_unique<client::Robot>("arm", options);
    if (!m_robot->waitForState(kAnswerTimeout)) throw std::runtime_error(m_robot->lastError());
    ASSERT_EQ(m_robot->numJoints(), kJoints);
  }

  client::Robot& arm() { return *m_robot; }

  // The arm's robot_state_t of `step`, as the test's own client received it.
  const rbsim::robot_state_t& robotStateAt(int64_t step) {
    waitFor("the robot state of step " + std::to_string(step),
            [&] { return m_robotStates.count(step) > 0; });
    return m_robotStates.at(step);
  }
  const rbsim::joints_t& jointsAt(int64_t step) {
    waitFor("the joints of step " + std::to_string(step), [&] { return m_joints.count(step) > 0; });
    return m_joints.at(step);
  }

  void stepSync(int32_t steps = 1) {
    if (!arm().stepSync(steps, kAnswerTimeout)) throw std::runtime_error(arm().lastError());
  }

  // The robot states received, by step (a state republished while paused
  // replaces its step's copy), and their arrival order.
  std::map<int64_t, rbsim::robot_state_t> m_robotStates;
  std::vector<int64_t> m_robotStateSteps;

 private:
  void onRobotState(const lcm::ReceiveBuffer*, const std::string&,
                    const rbsim::robot_state_t* state) {
    if (state->robot != "arm") return;
    m_robotStates[state->step] = *state;
    m_robotStateSteps.push_back(state->step);
  }

  std::unique_ptr<client::Robot> m_robot;
  std::map<int64_t, rbsim::joints_t> m_joints;
};

// The joint's value in a joints_t by name.
const rbsim::joint_state_t& jointIn(const rbsim::joints_t& joints, const std::string& name) {
  for (const auto& joint : joints.joints)
    if (joint.name == name) return joint;
  throw std::runtime_error("no joint '" + name + "' in the joints of step " +
                           std::to_string(joints.step));
}

// The acceptance test: every joint tracks q0 + 0.3 sin(2π 0.5 t)
// for 2 s under τ = M (q̈_d + Kp e + Kd ė) + h + b q̇_d + f sign(q̇_d), with
// M and h from each state, one robot_command_t (efforts, steps = 1) and one
// robot_state_t a step at dt = 1 ms. The joints' damping b and friction f
// (world_t) are not in h; without them the wrist's error is 1e-2 rad at
// these gains (its small inertia). The arm starts at rest and the sine at
// 0.94 rad/s: a 0.2 s lead-in eases each joint's rate up from 0 (a quartic
// in position with no jump in acceleration) to arrive at q0 on the sine.
// What is left is the efforts' one-step delay: 2e-5 rad when the same loop
// steps the world in-process (no LCM).
TEST_F(RobotControl, ComputedTorqueTracksASineWithinAMilliradianAt1kHz) {
  start();
  ASSERT_DOUBLE_EQ(client().world()->dt, 0.001);
  Eigen::VectorXd b(kJoints), f(kJoints);
  for (int i = 0; i < kJoints; ++i) {
    const auto* joint = client().jointDescription(arm().jointNames()[i]);
    ASSERT_NE(joint, nullptr) << arm().jointNames()[i];
    b[i] = joint->damping;
    f[i] = joint->friction;
  }
  EXPECT_GT(f.minCoeff(), 0.0) << "the URDF's joints have friction";
  arm().setDynamics(true);
  stepSync();
  ASSERT_TRUE(arm().hasDynamics()) << arm().dynamicsNote();
  const Eigen::VectorXd start = arm().q();
  const double a = 0.3, w = std::numbers::pi, v = a * w, lead = 0.2;  // rad, rad/s, rad/s, s
  const double omega = 2.0 * std::numbers::pi * 20.0, kp = omega * omega, kd = 2.0 * omega;
  const double t0 = arm().simTime() + lead;
  double tracking = 0.0, reach = 0.0;
  int64_t step = arm().step();
  for (int cycle = -200; cycle <= 2000; ++cycle) {
    const double t = arm().simTime() - t0, x = (t + lead) / lead;
    ASSERT_NEAR(t, cycle * 0.001, 1e-9) << "a state per step";
    // The reference's offset from `start`: the lead-in, then v lead / 2 + the sine.
    const bool in = cycle < 0;
    const double r = in ? v * lead * x * x * x * (1 - x / 2) : v * lead / 2 + a * std::sin(w * t);
    const double rDot = in ? v * x * x * (3 - 2 * x) : v * std::cos(w * t);
    const double rDdot = in ? 6 * v * x * (1 - x) / lead : -a * w * w * std::sin(w * t);
    const Eigen::VectorXd e = (start.array() + r - arm().q().array()).matrix();
    const Eigen::VectorXd eDot = (rDot - arm().qd().array()).matrix();
    if (!in) {
      tracking = std::max(tracking, e.cwiseAbs().maxCoeff());
      reach = std::max(reach, (arm().q() - start).cwiseAbs().minCoeff());
    }
    if (cycle == 2000) break;
    const Eigen::VectorXd accel = (rDdot + (kp * e + kd * eDot).array()).matrix();
    const double sign = rDot > 0 ? 1.0 : rDot < 0 ? -1.0 : 0.0;
    const Eigen::VectorXd tau = arm().massMatrix() * accel + arm().bias() + b * rDot + f * sign;
    ASSERT_TRUE(arm().commandEffort(tau)) << arm().lastError();
    stepSync();
    ASSERT_EQ(arm().step(), ++step);
  }
  std::printf("computed torque at 1 kHz over LCM: max tracking error %.3g rad over 2 s\n",
              tracking);
  RecordProperty("max_tracking_error_rad", std::to_string(tracking));
  EXPECT_LT(tracking, 1e-3) << "rad";
  // The sine's top is v lead / 2 + a = 0.394 rad from the start.
  EXPECT_GT(reach, 0.39) << "rad: every joint went through the sine's amplitude";
}

// The example does the same as a program (clients/cpp/examples/computed_torque.cpp).
TEST_F(RobotControl, TheComputedTorqueExampleTracksTheArm) {
  start();
  const ProcessResult result =
      runProcess({kComputedTorqueExample, "--url", kUrl, "--tolerance", "1e-3"},
                 scratchPath("computed_torque.log"), 60s);
  ASSERT_TRUE(result.status.has_value()) << "did not end: " << result.output;
  EXPECT_EQ(*result.status, 0) << result.output;
  EXPECT_NE(result.output.find("max tracking error"), std::string::npos) << result.output;
  std::printf("%s", result.output.c_str());
  // It stepped the server 2.2 s (one step to turn the dynamics on, the
  // lead-in's 200, the sine's 2000).
  waitForStep(2201);
}

// One bad entry refuses the whole command, naming the joint: an unknown
// joint among named entries, a negative stiffness among ordered ones. The
// arm then moves exactly as if nothing had been sent: the steps after the
// refusals equal, bit for bit, those after a RESET without them.
TEST_F(RobotControl, ACommandWithOneBadJointIsRefusedWholeAndChangesNothing) {
  start();
  rbsim::robot_command_t named;
  named.num_joints = 7;
  named.num_names = 7;
  for (int i = 1; i <= 6; ++i) named.joint_names.push_back("joint" + std::to_string(i));
  named.joint_names.push_back("arm/joint99");
  named.mode.assign(7, rbsim::robot_command_t::MODE_EFFORT);
  named.effort.assign(7, 20.0);  // N·m: would swing the arm far in 50 ms
  for (auto* field :
       {&named.position, &named.velocity, &named.stiffness, &named.damping, &named.max_effort})
    field->assign(7, 0.0);
  arm().commandRaw(named);
  const auto unknown = arm().waitForAck(arm().send(), kAnswerTimeout);
  ASSERT_TRUE(unknown.has_value());
  EXPECT_FALSE(unknown->accepted);
  EXPECT_EQ(unknown->kind, rbsim::ack_t::KIND_ROBOT_COMMAND);
  EXPECT_EQ(unknown->request, 0);
  EXPECT_EQ(unknown->effective_step, -1);
  EXPECT_NE(unknown->reason.find("joint99"), std::string::npos) << unknown->reason;

  Eigen::VectorXd q = arm().q(), kp = Eigen::VectorXd::Constant(kJoints, 500.0);
  kp[4] = -1.0;  // arm/joint5
  ASSERT_TRUE(arm().command(q.array() + 0.5, Eigen::VectorXd::Zero(kJoints),
                            Eigen::VectorXd::Constant(kJoints, 20.0), kp,
                            Eigen::VectorXd::Zero(kJoints)));
  const auto negative = arm().waitForAck(arm().send(), kAnswerTimeout);
  ASSERT_TRUE(negative.has_value());
  EXPECT_FALSE(negative->accepted);
  EXPECT_NE(negative->reason.find("joint5"), std::string::npos) << negative->reason;

  stepSync(50);
  const rbsim::robot_state_t afterRefusals = arm().state().value();
  expectAccepted(client().reset());
  stepSync(50);
  const rbsim::robot_state_t untouched = arm().state().value();
  ASSERT_EQ(afterRefusals.step, 50);
  ASSERT_EQ(untouched.step, 50);
  for (int i = 0; i < kJoints; ++i) {
    EXPECT_EQ(afterRefusals.position[i], untouched.position[i]) << afterRefusals.joint_names[i];
    EXPECT_EQ(afterRefusals.velocity[i], untouched.velocity[i]) << afterRefusals.joint_names[i];
    EXPECT_EQ(afterRefusals.effort[i], untouched.effort[i]) << afterRefusals.joint_names[i];
  }
}

// A command for step s + 5 acts from there: the state of step s + 4 still
// shows the world file's drives, the state of step s + 5 (== the ack's
// effective_step) is the first with the commanded efforts.
TEST_F(RobotControl, ACommandActsFromItsApplyAtStep) {
  start();
  const int64_t s = arm().step();
  const double tau = 3.0;  // N·m, far from what the drives apply to hold the arm
  ASSERT_TRUE(arm().commandEffort(Eigen::VectorXd::Constant(kJoints, tau)));
  const auto ack = arm().waitForAck(arm().send(s + 5), kAnswerTimeout);
  ASSERT_TRUE(ack.has_value());
  ASSERT_TRUE(ack->accepted) << ack->reason;
  EXPECT_EQ(ack->effective_step, s + 5);
  for (int i = 0; i < 8; ++i) stepSync();
  const auto offBy = [&](int64_t step) {
    const auto& state = robotStateAt(step);
    double most = 0.0;
    for (double effort : state.effort) most = std::max(most, std::abs(effort - tau));
    return most;
  };
  EXPECT_GT(offBy(s + 4), 0.1) << "N·m: before its step the drives act";
  EXPECT_LT(offBy(s + 5), 1e-12) << "N·m: the state of effective_step shows it";
  EXPECT_LT(offBy(s + 8), 1e-12) << "N·m: and it stays";
}

// robot_state_t and joints_t of the same step say the same of the arm's
// joints, bit for bit; the base is the fixed base_link at the origin.
TEST_F(RobotControl, TheRobotStateHoldsTheJointsOfItsStep) {
  start();
  // Moving, so that rates and efforts are not all zero.
  ASSERT_TRUE(arm().commandEffort(Eigen::VectorXd::Constant(kJoints, 2.0)));
  stepSync(20);
  const int64_t first = arm().step();
  for (int64_t step = first; step < first + 3; ++step) {
    if (step > first) stepSync();
    const rbsim::robot_state_t& robot = robotStateAt(step);
    const rbsim::joints_t& joints = jointsAt(step);
    ASSERT_EQ(robot.num_joints, kJoints);
    EXPECT_EQ(robot.world_revision, joints.world_revision);
    EXPECT_EQ(robot.sim_time, history().at(step).sim_time);
    std::vector<std::string> armJoints;  // joints_t's order is the world's creation order
    for (const auto& joint : joints.joints)
      if (joint.name.starts_with("arm/")) armJoints.push_back(joint.name);
    EXPECT_EQ(robot.joint_names, armJoints);
    for (int i = 0; i < kJoints; ++i) {
      const auto& joint = jointIn(joints, robot.joint_names[i]);
      EXPECT_EQ(robot.position[i], joint.position) << joint.name;
      EXPECT_EQ(robot.velocity[i], joint.rate) << joint.name;
      EXPECT_EQ(robot.effort[i], joint.effort) << joint.name;
      EXPECT_EQ(robot.leader[i], -1) << joint.name;
    }
    EXPECT_GT(std::abs(robot.velocity[1]), 1e-3) << "rad/s: it moves";
    EXPECT_EQ(robot.base, "arm/base_link");
    EXPECT_TRUE(robot.base_fixed);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(robot.base_position[k], 0.0);
    EXPECT_EQ(robot.base_orientation[0], 1.0);
    EXPECT_EQ(robot.num_dofs, 0) << "no dynamics unless asked for";
  }
}

// Running at dt = 1 ms with world states at 100 Hz: state_rate 1000 Hz
// gives a robot state every step, 250 Hz every fourth, −1 the world
// state's rate again (every tenth); world states stay at 100 Hz throughout.
TEST_F(RobotControl, TheStateComesAtItsOwnRate) {
  start({});
  const auto stepsBetween = [&](double rate) {
    arm().setStateRate(rate);
    const auto ack = arm().waitForAck(arm().send(), kAnswerTimeout);
    if (!ack || !ack->accepted)
      throw std::runtime_error("state_rate " + std::to_string(rate) + " not accepted");
    // From a few steps after it took effect, for 0.3 s.
    waitFor("step " + std::to_string(ack->effective_step + 20),
            [&] { return history().lastStep() >= ack->effective_step + 20; });
    const std::size_t from = m_robotStateSteps.size();
    spinFor(300ms);
    std::vector<int64_t> steps(m_robotStateSteps.begin() + static_cast<std::ptrdiff_t>(from),
                               m_robotStateSteps.end());
    std::map<int64_t, int> gaps;  // step difference between consecutive states -> count
    for (std::size_t i = 1; i < steps.size(); ++i) ++gaps[steps[i] - steps[i - 1]];
    return gaps;
  };
  const auto every = [](const std::map<int64_t, int>& gaps) {
    std::string text;
    for (const auto& [gap, count] : gaps)
      text += std::to_string(gap) + ":" + std::to_string(count) + " ";
    return text;
  };
  const auto perStep = stepsBetween(1000.0);
  EXPECT_EQ(perStep.size(), 1u) << every(perStep);
  EXPECT_GT(perStep.count(1) ? perStep.at(1) : 0, 100) << every(perStep);
  const int64_t worldFrom = history().lastStep();
  const auto fourth = stepsBetween(250.0);
  EXPECT_EQ(fourth.size(), 1u) << every(fourth);
  EXPECT_GT(fourth.count(4) ? fourth.at(4) : 0, 25) << every(fourth);
  const auto tenth = stepsBetween(-1.0);
  EXPECT_EQ(tenth.size(), 1u) << every(tenth);
  EXPECT_GT(tenth.count(10) ? tenth.at(10) : 0, 10) << every(tenth);
  // The world's states kept their own 100 Hz meanwhile: one every ten steps.
  const int64_t worldTo = history().lastStep();
  int64_t worldStates = 0;
  for (int64_t step = worldFrom + 1; step <= worldTo; ++step)
    worldStates += history().has(step) ? 1 : 0;
  EXPECT_NEAR(static_cast<double>(worldStates), (worldTo - worldFrom) / 10.0, 1.0);
}

// The dynamics a state carries are the library's (JointSpaceDynamics) at
// that state: the test loads the same world file and steps it as the
// server does, at step 0 and after 30 steps of the drives (moving a
// little, so that h has Coriolis terms). M symmetric positive definite;
// each link's Jacobian is the library's at the link frame's origin, and
// Robot::jacobian(link, p) the library's at p.
TEST_F(RobotControl, TheDynamicsAreTheLibrarysAtTheSameState) {
  start();
  Expected<WorldDef> def = loadWorldConfig(kArmWorld);
  ASSERT_TRUE(def.ok()) << def.error().message;
  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;

  arm().setDynamics(true);
  const auto ack = arm().waitForAck(arm().send(), kAnswerTimeout);
  ASSERT_TRUE(ack && ack->accepted);
  ASSERT_TRUE(arm().waitForState(kAnswerTimeout, true)) << arm().lastError();
  for (const int64_t step : {int64_t{0}, int64_t{30}}) {
    if (step > 0) {
      for (int i = 0; i < step; ++i) world->step();
      stepSync(static_cast<int32_t>(step));
    }
    SCOPED_TRACE("step " + std::to_string(step));
    ASSERT_EQ(arm().step(), step);
    ASSERT_TRUE(arm().hasDynamics()) << arm().dynamicsNote();
    EXPECT_EQ(arm().state()->num_dofs, kJoints);
    const Expected<JointSpaceDynamics> library = JointSpaceDynamics::ofRobot(*world, "arm/");
    ASSERT_TRUE(library.ok()) << library.error().message;
    // The same state, or the comparison says nothing.
    ASSERT_LT((library->positions() - arm().q()).cwiseAbs().maxCoeff(), 1e-12);
    ASSERT_LT((library->velocities() - arm().qd()).cwiseAbs().maxCoeff(), 1e-12);
    if (step > 0) {
      EXPECT_GT(arm().qd().cwiseAbs().maxCoeff(), 1e-4) << "rad/s: it moves";
    }
    EXPECT_EQ(library->jointNames(), arm().jointNames());

    const Eigen::MatrixXd m = arm().massMatrix(), expected = library->massMatrix();
    const double scale = expected.cwiseAbs().maxCoeff();
    EXPECT_LT((m - m.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale);
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(m).info(), Eigen::Success) << "positive definite";
    EXPECT_LT((m - expected).cwiseAbs().maxCoeff(), 1e-9 * scale) << "M\n"
                                                                  << m << "\nlibrary\n"
                                                                  << expected;
    const Eigen::VectorXd h = library->biasForces(), g = library->gravityTorques();
    EXPECT_LT((arm().bias() - h).cwiseAbs().maxCoeff(), 1e-9 * h.cwiseAbs().maxCoeff());
    EXPECT_LT((arm().gravity() - g).cwiseAbs().maxCoeff(), 1e-9 * g.cwiseAbs().maxCoeff());
    if (step > 0) {
      EXPECT_GT((h - g).cwiseAbs().maxCoeff(), 0.0) << "Coriolis terms in h";
    }

    EXPECT_EQ(arm().linkNames(), library->bodyNames());
    for (const std::string& link : arm().linkNames()) {
      const auto pose = arm().linkPose(link);
      ASSERT_TRUE(pose.has_value()) << link;
      const auto jacobian = arm().jacobian(link);
      const auto at = library->jacobian(link, pose->position);
      ASSERT_TRUE(jacobian.has_value() && at.ok()) << link;
      EXPECT_LT((*jacobian - *at).cwiseAbs().maxCoeff(), 1e-9) << link;
      const Eigen::Vector3d point = pose->position + Eigen::Vector3d(0.1, -0.05, 0.2);
      const auto atPoint = library->jacobian(link, point);
      ASSERT_TRUE(atPoint.ok()) << link;
      EXPECT_LT((*arm().jacobian(link, point) - *atPoint).cwiseAbs().maxCoeff(), 1e-9) << link;
    }
    EXPECT_FALSE(arm().jacobian("no_such_link").has_value());
    EXPECT_TRUE(arm().jacobian("link7").has_value()) << "the robot's own link name";
  }
}

// Acks are dropped oldest first by arrival, whatever their kind: a STEP ack
// (kind 2) that comes after thousands of joint-command acks (kind 3) stays.
TEST(AckStore, KeepsTheNewestAcksWhateverTheirKind) {
  client::AckStore store(8);
  rbsim::ack_t ack;
  for (int64_t seq = 1; seq <= 100; ++seq) {
    ack.seq = seq;
    ack.kind = seq % 8 == 0 ? rbsim::ack_t::KIND_COMMAND : rbsim::ack_t::KIND_JOINT_COMMAND;
    store.add(ack);
    ASSERT_NE(store.find({ack.kind, seq}), nullptr) << seq;
  }
  EXPECT_NE(store.find({rbsim::ack_t::KIND_COMMAND, 96}), nullptr);
  EXPECT_NE(store.find({rbsim::ack_t::KIND_JOINT_COMMAND, 93}), nullptr);
  EXPECT_EQ(store.find({rbsim::ack_t::KIND_JOINT_COMMAND, 92}), nullptr)
      << "the ninth newest is gone";
  EXPECT_EQ(store.find({rbsim::ack_t::KIND_COMMAND, 88}), nullptr);
}

}  // namespace
}  // namespace rbsim::e2e
