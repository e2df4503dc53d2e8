// Joints over LCM against config/worlds/joints.yaml: <prefix>JOINTS with
// every joint, consistent with the bodies' poses on <prefix>STATE; joint
// commands through the C++ client, their acks and their effect against
// closed forms; rejections with reasons; the joints in world_t; a recorded
// session with joint commands replayed bit for bit, and one with robot
// commands (config/worlds/robot_arm.yaml).

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <limits>
#include <map>
#include <stdexcept>
#include <thread>
#include <rbsim/ack_t.hpp>
#include <rbsim/joint_command_t.hpp>
#include <rbsim/robot_command_t.hpp>
#include <rbsim/robot_state_t.hpp>

#include "e2e_paths.h"
#include "event_log.h"
#include "log_files.h"
#include "rbsim/client/lookup.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

const std::string kJointsWorld = std::string(kConfigWorldsDir) + "/joints.yaml";

// The wheel of joints.yaml: a cylinder of 2 kg and radius 0.2 m on the axle
// (world z): I = m r^2 / 2 about the axle.
constexpr double kWheelInertia = 0.5 * 2.0 * 0.2 * 0.2;  // kg m^2

class Joints : public ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    startServer(kJointsWorld, {"--paused", "--state-rate", "0"});
    // Joint states of every step, to compare with the state of that step.
    client().onJoints([this](const rbsim::joints_t& joints) { m_joints[joints.step] = joints; });
  }

  // The joints of `step` (the server publishes them right after its state).
  const rbsim::joints_t& jointsAt(int64_t step) {
    waitFor("the joints of step " + std::to_string(step), [&] { return m_joints.count(step) > 0; });
    return m_joints.at(step);
  }

  static const rbsim::joint_state_t& joint(const rbsim::joints_t& joints, const std::string& name) {
    for (const auto& j : joints.joints)
      if (j.name == name) return j;
    throw std::runtime_error("no joint '" + name + "' in the joints of step " + std::to_string(joints.step));
  }

  client::JointCommand command(const std::string& name, client::JointMode mode, double target) {
    client::JointCommand c;
    c.joint = name;
    c.mode = mode;
    c.target = target;
    return c;
  }

  std::map<int64_t, rbsim::joints_t> m_joints;
};

TEST_F(Joints, EveryJointIsPublishedConsistentWithTheBodiesPoses) {
  stepAndWait(50);
  const rbsim::joints_t& joints = jointsAt(50);
  const std::vector<std::string> names = {"door_hinge", "shoulder",  "elbow", "axle",        "lift",     "weld",
                                          "servo",      "lamp_rope", "hip",   "pinion_axle", "gear_axle"};
  ASSERT_EQ(joints.total_joints, 11);
  ASSERT_EQ(joints.joints.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(joints.joints[i].name, names[i]);
  EXPECT_EQ(joints.world_revision, client().latestState()->world_revision);

  const auto& state = history().at(50);
  // The door turns about world z through the hinge only: its angle is the
  // yaw of its orientation, 2 atan2(q_z, q_w).
  const auto* door = client::findBody(state, "door");
  ASSERT_NE(door, nullptr);
  const double yaw = 2.0 * std::atan2(door->orientation[3], door->orientation[0]);
  EXPECT_NEAR(joint(joints, "door_hinge").position, yaw, 1e-9);
  EXPECT_GT(joint(joints, "door_hinge").position, 0.01);  // it started turning
  // The carriage slides along world z from z = 1.5 m, without turning.
  const auto* carriage = client::findBody(state, "carriage");
  ASSERT_NE(carriage, nullptr);
  EXPECT_NEAR(joint(joints, "lift").position, carriage->position[2] - 1.5, 1e-9);
  EXPECT_NEAR(joint(joints, "lift").rate, carriage->linear_velocity[2], 1e-9);
  // The wheel's rate is its angular velocity about the axle.
  const auto* wheel = client::findBody(state, "wheel");
  EXPECT_NEAR(joint(joints, "axle").rate, wheel->angular_velocity[2], 1e-9);
  for (const auto& j : joints.joints) {
    EXPECT_TRUE(j.active) << j.name;
    EXPECT_LT(j.error, 1e-9) << j.name;
    const double norm = std::sqrt(j.rotation[0] * j.rotation[0] + j.rotation[1] * j.rotation[1] +
                                  j.rotation[2] * j.rotation[2] + j.rotation[3] * j.rotation[3]);
    EXPECT_NEAR(norm, 1.0, 1e-12) << j.name;
  }
}

// The capped motor accelerates the wheel at max_effort / I until the rate
// reaches the target, then holds it: the motor row is solved exactly with
// the joint's rows (docs/joints_design.md), so what is left is rounding
// (1e-9 rad/s is a thousand times the rounding of 400 steps).
TEST_F(Joints, AVelocityCommandSpinsTheWheelToItsTarget) {
  const double target = -3.0, maxEffort = 0.5;
  client::JointCommand velocity = command("axle", client::JointMode::Velocity, target);
  velocity.maxEffort = maxEffort;
  const rbsim::ack_t ack = expectAccepted(client().commandJoint(velocity));
  EXPECT_EQ(ack.kind, rbsim::ack_t::KIND_JOINT_COMMAND);
  EXPECT_EQ(ack.request, rbsim::joint_command_t::MODE_VELOCITY);
  EXPECT_EQ(ack.effective_step, 1);  // paused at step 0: the next step
  stepAndWait(400);
  const double alpha = maxEffort / kWheelInertia;  // 12.5 rad/s^2: the target after 0.24 s
  const double dt = client().world()->dt;
  const auto& during = joint(jointsAt(100), "axle");
  EXPECT_NEAR(during.rate, -alpha * 100 * dt, 1e-9);
  EXPECT_NEAR(during.effort, -maxEffort, 1e-9);
  const auto& after = joint(jointsAt(400), "axle");
  EXPECT_NEAR(after.rate, target, 1e-9);
  EXPECT_NEAR(after.effort, 0.0, 1e-9);  // no loss to make up for in free rotation
}

// EFFORT turns the world file's motor off: the wheel is a free hinge with a
// constant torque, rate = tau t / I and angle = tau t^2 / (2 I) (the joint
// step is velocity Verlet, exact for a constant acceleration). The command
// scheduled ahead takes effect at its step and not before.
TEST_F(Joints, AnEffortOnAFreeHingeAcceleratesItAtTauOverI) {
  const double tau = 0.2;
  client::JointCommand effort = command("axle", client::JointMode::Effort, tau);
  effort.applyAtStep = 11;
  EXPECT_EQ(expectAccepted(client().commandJoint(effort)).effective_step, 11);
  // Until then the world file's motor spins it up at 0.5 N m.
  stepAndWait(10);
  const double dt = client().world()->dt;
  const double spunUp = 0.5 / kWheelInertia * 10 * dt;
  EXPECT_NEAR(joint(jointsAt(10), "axle").rate, spunUp, 1e-9);
  stepAndWait(100);
  const auto& axle = joint(jointsAt(110), "axle");
  const double t = 100 * dt;
  EXPECT_NEAR(axle.rate, spunUp + tau / kWheelInertia * t, 1e-9);
  const double angleAt10 = joint(jointsAt(10), "axle").position;
  EXPECT_NEAR(axle.position, angleAt10 + spunUp * t + 0.5 * tau / kWheelInertia * t * t, 1e-9);
  EXPECT_NEAR(axle.effort, tau, 1e-12);
  // OFF: no torque any more, the rate stays.
  expectAccepted(client().commandJoint(command("axle", client::JointMode::Off, 0.0)));
  stepAndWait(20);
  EXPECT_NEAR(joint(jointsAt(130), "axle").rate, axle.rate, 1e-9);
  EXPECT_EQ(joint(jointsAt(130), "axle").effort, 0.0);
}

TEST_F(Joints, TheWorldDescriptionListsTheJoints) {
  const rbsim::world_t& world = *client().world();
  ASSERT_EQ(world.total_joints, 11);
  ASSERT_EQ(world.joints.size(), 11u);
  const auto* hinge = client().jointDescription("door_hinge");
  ASSERT_NE(hinge, nullptr);
  EXPECT_EQ(hinge->type, "revolute");
  EXPECT_EQ(hinge->body_a, "world");
  EXPECT_EQ(hinge->body_b, "door");
  EXPECT_EQ(hinge->anchor_a[2], 1.0);
  EXPECT_EQ(hinge->axis[2], 1.0);
  EXPECT_TRUE(hinge->limit_enabled);
  EXPECT_EQ(hinge->lower_limit, -1.57);
  EXPECT_EQ(hinge->upper_limit, 1.57);
  const auto* elbow = client().jointDescription("elbow");
  ASSERT_NE(elbow, nullptr);
  EXPECT_EQ(elbow->body_a, "upper_arm");
  EXPECT_EQ(elbow->body_b, "forearm");
  EXPECT_NEAR(elbow->axis[1], 1.0, 1e-15);
  EXPECT_FALSE(elbow->limit_enabled);
  const auto* lift = client().jointDescription("lift");
  ASSERT_NE(lift, nullptr);
  EXPECT_EQ(lift->type, "prismatic");
  EXPECT_EQ(lift->lower_limit, -0.5);
  const auto* weld = client().jointDescription("weld");
  ASSERT_NE(weld, nullptr);
  EXPECT_EQ(weld->type, "fixed");
  EXPECT_EQ(weld->anchor_b[0], 0.1);
}

TEST_F(Joints, BadJointCommandsAreRejectedWithReasons) {
  const auto reason = [&](const client::JointCommand& c) { return expectRejected(client().commandJoint(c)).reason; };
  EXPECT_EQ(reason(command("nosuch", client::JointMode::Effort, 1.0)), "joint: unknown joint 'nosuch'");
  EXPECT_EQ(reason(command("Axel", client::JointMode::Effort, 1.0)),
            "joint: unknown joint 'Axel' (did you mean 'axle'?)");
  // A motor with no effort cap and no joint limit to take would do nothing.
  EXPECT_EQ(reason(command("axle", client::JointMode::Velocity, 1.0)).rfind("max_effort: give --max-effort", 0), 0u);
  EXPECT_NE(reason(command("weld", client::JointMode::Velocity, 1.0)).find("'weld' is a fixed joint"),
            std::string::npos);
  EXPECT_EQ(reason(command("gear_axle", client::JointMode::Velocity, 1.0)),
            "joint: 'gear_axle' follows joint 'pinion_axle' (mimic): command its leader, which moves both");
  EXPECT_EQ(reason(command("axle", client::JointMode::Effort, std::nan(""))), "target must be finite");
  EXPECT_EQ(reason(command("axle", static_cast<client::JointMode>(7), 1.0)).rfind("mode: unknown mode 7", 0), 0u);
  client::JointCommand past = command("axle", client::JointMode::Effort, 1.0);
  stepAndWait(3);
  past.applyAtStep = 2;
  EXPECT_NE(reason(past).find("apply_at_step 2 is in the past"), std::string::npos);
  // Nothing changed: the wheel still spins up under the world file's motor.
  stepAndWait(1);
  EXPECT_NEAR(joint(jointsAt(4), "axle").effort, 0.5, 1e-9);
}

// The gear pair of joints.yaml: the gear follows the pinion × −0.5 (a
// mimic), so a velocity command to the pinion turns both, the gear half as
// fast the other way, at every published step.
TEST_F(Joints, AGearFollowsItsPinion) {
  client::JointCommand spin = command("pinion_axle", client::JointMode::Velocity, 4.0);
  spin.maxEffort = 0.2;
  expectAccepted(client().commandJoint(spin));
  stepAndWait(300);
  const auto& pinion = joint(jointsAt(300), "pinion_axle");
  const auto& gear = joint(jointsAt(300), "gear_axle");
  EXPECT_GT(pinion.rate, 1.0) << "spun up";
  EXPECT_NEAR(gear.rate, -0.5 * pinion.rate, 1e-9);
  EXPECT_NEAR(gear.position, -0.5 * pinion.position, 1e-9);
}

using BallJoint = ServerTest;

TEST_F(BallJoint, ASphericalJointTakesNoVelocityCommand) {
  startServer("ball_joint.yaml", {"--paused", "--state-rate", "0"});
  client::JointCommand velocity;
  velocity.joint = "socket";
  velocity.mode = client::JointMode::Velocity;
  velocity.target = 1.0;
  velocity.maxEffort = 1.0;
  const rbsim::ack_t ack = expectRejected(client().commandJoint(velocity));
  EXPECT_EQ(ack.kind, rbsim::ack_t::KIND_JOINT_COMMAND);
  EXPECT_EQ(ack.effective_step, -1);
  EXPECT_NE(ack.reason.find("joint: 'socket' is a spherical joint, which has no axis"), std::string::npos)
      << ack.reason;
  velocity.joint = "flap_hinge";
  expectAccepted(client().commandJoint(velocity));
  const auto* socket = client().jointDescription("socket");
  ASSERT_NE(socket, nullptr);
  EXPECT_EQ(socket->type, "spherical");
  EXPECT_EQ(socket->anchor_a[2], 1.5);
}

using JointReplay = ServerTest;

// Joint commands of every mode, some scheduled ahead, between steps of a
// recorded session: --replay --verify re-simulates it bit for bit, from the
// server's record and from lcm-logger's log of the bus (only the acks say
// when there).
TEST_F(JointReplay, ASessionWithJointCommandsReplaysBitIdentically) {
  const std::string record = scratchPath("joints.lcmlog");
  const std::string busLog = scratchPath("bus.lcmlog");
  constexpr const char* kLcmLogger = "/usr/bin/lcm-logger";
  std::unique_ptr<ChildProcess> logger;
  if (access(kLcmLogger, X_OK) == 0)
    logger = std::make_unique<ChildProcess>(
        std::vector<std::string>{kLcmLogger, "-f", std::string("--lcm-url=") + kUrl, busLog},
        scratchPath("logger.log"));
  if (logger) {
    // lcm-logger opens its file and then joins the bus; a command sent
    // before it listens is missing from its log with nothing to show it
    // (seen under a loaded ctest -j2). Wait for the file, then a little.
    for (int i = 0; i < 200 && access(busLog.c_str(), F_OK) != 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  startServer(kJointsWorld, {"--record", record, "--paused", "--state-rate", "0"});
  client::JointCommand c;
  c.joint = "axle";
  c.mode = client::JointMode::Velocity;
  c.target = -2.0;
  c.maxEffort = 0.3;
  expectAccepted(client().commandJoint(c));
  stepAndWait(30);
  c = {};
  c.joint = "lift";
  c.mode = client::JointMode::Position;
  c.target = 0.2;
  c.stiffness = 300.0;
  c.damping = 10.0;
  c.applyAtStep = currentStep() + 7;
  expectAccepted(client().commandJoint(c));
  c = {};
  c.joint = "door_hinge";
  c.mode = client::JointMode::Effort;
  c.target = -4.0;
  expectAccepted(client().commandJoint(c));
  stepAndWait(25);
  c = {};
  c.joint = "elbow";
  c.mode = client::JointMode::Position;
  c.target = 0.5;
  c.stiffness = 50.0;
  c.maxEffort = 2.0;
  expectAccepted(client().commandJoint(c));
  c = {};
  c.joint = "pinion_axle";  // the gear follows it (a mimic row in the replay)
  c.mode = client::JointMode::Velocity;
  c.target = 4.0;
  c.maxEffort = 0.2;
  expectAccepted(client().commandJoint(c));
  c = {};
  c.joint = "nosuch";
  expectRejected(client().commandJoint(c));
  expectAccepted(client().resume());
  spinFor(std::chrono::milliseconds(150));
  c = {};
  c.joint = "axle";
  c.mode = client::JointMode::Off;
  expectAccepted(client().commandJoint(c));
  spinFor(std::chrono::milliseconds(100));
  const auto status = stopServer(10s);
  ASSERT_TRUE(status.has_value());
  ASSERT_EQ(*status, 0);
  if (logger) {
    logger->signal(SIGINT);
    ASSERT_TRUE(logger->wait(5s).has_value()) << "lcm-logger did not stop";
  }

  const ProcessResult replay =
      runProcess({kRbserver, "--config", kJointsWorld, "--replay", record, "--verify"},
                 scratchPath("verify.log"), 60s);
  ASSERT_TRUE(replay.status.has_value());
  EXPECT_EQ(*replay.status, 0) << replay.output;
  EXPECT_NE(replay.output.find("replay identical"), std::string::npos) << replay.output;
  // The joints' pages were compared too, not only the bodies'.
  long long statePages = 0, jointPages = 0;
  const std::size_t at = replay.output.find("replay identical to the log: ");
  ASSERT_NE(at, std::string::npos) << replay.output;
  ASSERT_EQ(std::sscanf(replay.output.c_str() + at, "replay identical to the log: %lld state pages and %lld joint pages",
                        &statePages, &jointPages), 2)
      << replay.output;
  EXPECT_GT(jointPages, 0) << replay.output;
  EXPECT_GE(statePages, jointPages) << replay.output;
  // A bus log that lost the ack of an accepted joint command: the command
  // changes no world revision, so only the states parting from the log show
  // it; the replay must then blame the log (exit 3), not the physics.
  {
    std::vector<LoggedEvent> busLike;
    for (const LoggedEvent& event : readEventLog(record).events)
      if (event.channel != "RBSIM_HANDLED") busLike.push_back(event);
    const auto lostAck = std::find_if(busLike.begin(), busLike.end(), [](const LoggedEvent& event) {
      if (event.channel != "RBSIM_ACK") return false;
      const auto ack = decodeAs<rbsim::ack_t>(event);
      return ack && ack->accepted && ack->kind == rbsim::ack_t::KIND_JOINT_COMMAND;
    });
    ASSERT_NE(lostAck, busLike.end());
    busLike.erase(lostAck);
    const std::string lossy = scratchPath("joints_lost_ack.lcmlog");
    ASSERT_TRUE(writeEventLog(lossy, busLike));
    const ProcessResult fromLossy = runProcess({kRbserver, "--config", kJointsWorld, "--replay", lossy, "--verify"},
                                               scratchPath("verify_lost_ack.log"), 60s);
    ASSERT_TRUE(fromLossy.status.has_value());
    EXPECT_EQ(*fromLossy.status, 3) << fromLossy.output;
    EXPECT_NE(fromLossy.output.find("has no ack (lost by the logger?)"), std::string::npos) << fromLossy.output;

    // Lose a later joint command with its ack: only the gap in its
    // client's sequence numbers is left to show it.
    std::vector<LoggedEvent> bothLost;
    for (const LoggedEvent& event : readEventLog(record).events)
      if (event.channel != "RBSIM_HANDLED") bothLost.push_back(event);
    std::vector<int64_t> jointSeqs;
    for (const LoggedEvent& event : bothLost)
      if (event.channel == "RBSIM_JOINT_COMMAND")
        if (const auto command = decodeAs<rbsim::joint_command_t>(event)) jointSeqs.push_back(command->seq);
    ASSERT_GE(jointSeqs.size(), 3u);
    const int64_t lostSeq = jointSeqs[1];
    std::erase_if(bothLost, [&](const LoggedEvent& event) {
      if (event.channel == "RBSIM_JOINT_COMMAND") {
        const auto command = decodeAs<rbsim::joint_command_t>(event);
        return command && command->seq == lostSeq;
      }
      if (event.channel != "RBSIM_ACK") return false;
      const auto ack = decodeAs<rbsim::ack_t>(event);
      return ack && ack->kind == rbsim::ack_t::KIND_JOINT_COMMAND && ack->seq == lostSeq;
    });
    busLike = bothLost;
    const std::string lossier = scratchPath("joints_lost_message.lcmlog");
    ASSERT_TRUE(writeEventLog(lossier, busLike));
    const ProcessResult fromLossier = runProcess(
        {kRbserver, "--config", kJointsWorld, "--replay", lossier, "--verify"}, scratchPath("verify_lost_message.log"), 60s);
    ASSERT_TRUE(fromLossier.status.has_value());
    EXPECT_EQ(*fromLossier.status, 3) << fromLossier.output;
    EXPECT_NE(fromLossier.output.find("(lost by the logger?)"), std::string::npos) << fromLossier.output;
  }
  if (logger) {
    // UDP may drop a datagram on the way to the logger: the replay must then
    // say so (exit 3) rather than diverge.
    const ProcessResult fromBus =
        runProcess({kRbserver, "--config", kJointsWorld, "--replay", busLog, "--verify"},
                   scratchPath("verify_bus.log"), 60s);
    ASSERT_TRUE(fromBus.status.has_value());
    const bool lossReported = *fromBus.status == 3 && fromBus.output.find("lost by the logger") != std::string::npos;
    if (lossReported) std::printf("note: lcm-logger lost a message: %s", fromBus.output.c_str());
    EXPECT_TRUE(*fromBus.status == 0 || lossReported) << fromBus.output;
  }
}

using RobotReplay = ServerTest;

// Robot commands of every mode (in joint order and by name, scheduled
// ahead, lock-step 'steps' while paused, while running, one refused) in a
// recorded session of the seven-joint arm: --replay --verify re-simulates
// it bit for bit, robot states included in what the server recorded.
TEST_F(RobotReplay, ASessionWithRobotCommandsReplaysBitIdentically) {
  const std::string kArmWorld = std::string(kConfigWorldsDir) + "/robot_arm.yaml";
  const std::string record = scratchPath("robot.lcmlog");
  startServer(kArmWorld, {"--record", record, "--paused", "--state-rate", "0"});
  int64_t seq = 1000;
  const auto send = [&](rbsim::robot_command_t m) {
    m.client = client().clientId();
    m.seq = ++seq;
    m.robot = "arm";
    const auto entries = static_cast<std::size_t>(m.num_joints);
    m.mode.resize(entries, rbsim::robot_command_t::MODE_KEEP);
    for (auto* field : {&m.position, &m.velocity, &m.effort, &m.stiffness, &m.damping, &m.max_effort})
      field->resize(entries, 0.0);
    client().lcm().publish("RBSIM_ROBOT_COMMAND", &m);
    const auto ack = client().waitForAck(m.seq, static_cast<client::AckKind>(rbsim::ack_t::KIND_ROBOT_COMMAND), 5s);
    if (!ack) throw std::runtime_error("no ack for robot command " + std::to_string(m.seq));
    return *ack;
  };
  rbsim::robot_command_t hold{};
  hold.apply_at_step = -1;
  hold.state_dynamics = -1;
  hold.num_joints = 7;
  hold.mode.assign(7, rbsim::robot_command_t::MODE_POSITION);
  hold.position = {0.2, 0.7, -0.1, 1.1, 0.3, 0.6, -0.2};
  hold.velocity = {0.5, 0.0, -0.3, 0.0, 0.2, 0.0, 0.1};
  hold.effort = {0.0, -20.0, 0.0, -8.0, 0.0, -1.0, 0.0};
  hold.stiffness.assign(7, 800.0);
  hold.damping.assign(7, 40.0);
  hold.max_effort.assign(7, 0.0);
  hold.steps = 20;
  const rbsim::ack_t first = send(hold);
  ASSERT_TRUE(first.accepted) << first.reason;
  EXPECT_EQ(first.kind, rbsim::ack_t::KIND_ROBOT_COMMAND);
  waitForStep(first.effective_step + 19);

  rbsim::robot_command_t named{};
  named.apply_at_step = currentStep() + 5;
  named.state_dynamics = 1;
  named.num_joints = named.num_names = 2;
  named.joint_names = {"joint4", "arm/joint6"};
  named.mode = {rbsim::robot_command_t::MODE_EFFORT, rbsim::robot_command_t::MODE_VELOCITY};
  named.effort = {-5.0, 0.5};
  named.velocity = {0.0, -0.4};
  named.max_effort = {0.0, 30.0};
  ASSERT_TRUE(send(named).accepted);
  rbsim::robot_command_t wrong = named;
  wrong.apply_at_step = -1;
  wrong.joint_names = {"joint4", "joint9"};
  const rbsim::ack_t refused = send(wrong);
  EXPECT_FALSE(refused.accepted);
  EXPECT_NE(refused.reason.find("has no joint 'joint9'"), std::string::npos) << refused.reason;
  stepAndWait(30);
  expectAccepted(client().resume());
  spinFor(std::chrono::milliseconds(120));
  hold.steps = 0;
  hold.mode[2] = rbsim::robot_command_t::MODE_OFF;
  ASSERT_TRUE(send(hold).accepted);
  spinFor(std::chrono::milliseconds(100));
  const auto status = stopServer(10s);
  ASSERT_TRUE(status.has_value());
  ASSERT_EQ(*status, 0);

  // The record holds the robot states the server sent, with their dynamics
  // once asked for.
  int robotStates = 0, withDynamics = 0;
  for (const LoggedEvent& event : readEventLog(record).events) {
    if (event.channel != "RBSIM_ROBOT_STATE") continue;
    const auto state = decodeAs<rbsim::robot_state_t>(event);
    ASSERT_TRUE(state.has_value());
    ++robotStates;
    if (state->num_dofs == 7) ++withDynamics;
  }
  EXPECT_GT(robotStates, 50);
  EXPECT_GT(withDynamics, 20);

  const ProcessResult replay =
      runProcess({kRbserver, "--config", kArmWorld, "--replay", record, "--verify"}, scratchPath("verify.log"), 60s);
  ASSERT_TRUE(replay.status.has_value());
  EXPECT_EQ(*replay.status, 0) << replay.output;
  EXPECT_NE(replay.output.find("replay identical"), std::string::npos) << replay.output;
}

}  // namespace
}  // namespace rbsim::e2e
