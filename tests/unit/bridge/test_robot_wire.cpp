// Robots on the wire: robot_command_t checked whole and scheduled as one
// joint request per entry, applied before one step; robot_state_t built
// from the world, against the World's own joint states and the library's
// JointSpaceDynamics.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <rbsim/robot_command_t.hpp>
#include <rbsim/robot_state_t.hpp>

#include "bridge/command_handler.h"
#include "bridge/robot_messages.h"
#include "handler_test_messages.h"
#include "rbsim/physics/joint_space_dynamics.h"

namespace rbsim {
namespace {

using test::encoded;

BodyId addBox(World& world, const std::string& name, const Vec3& position, bool isStatic = false) {
  BodyDef def;
  def.name = name;
  def.shape = BoxShape{Vec3(0.05, 0.05, 0.2)};
  def.mass = 1.5;
  def.isStatic = isStatic;
  def.position = position;
  def.collides = false;
  const Expected<BodyId> id = world.createBody(def);
  EXPECT_TRUE(id.ok()) << id.error().message;
  return id.ok() ? *id : BodyId{};
}

JointDef axisJoint(const std::string& name, JointType type, BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis) {
  JointDef def;
  def.name = name;
  def.type = type;
  def.bodyA = a;
  def.bodyB = b;
  def.anchor = anchor;
  def.axis = axis;
  if (type != JointType::Fixed) def.actuatorLimits.effort = 50.0;
  return def;
}

// Robot "bot": a static base, a hinge (bot/shoulder), a slider
// (bot/slide), a welded tool (bot/weld) and a hinge that follows the
// shoulder (bot/finger, mimic ×0.5). Beside it a hinge "door" that belongs
// to no robot.
World robotWorld() {
  WorldSettings settings;
  settings.dt = 1e-3;
  settings.gravity = Vec3(0, 0, -9.81);
  settings.contact.sleeping = false;
  World world(settings);
  const BodyId base = addBox(world, "bot/base", Vec3(0, 0, 0.2), true);
  const BodyId upper = addBox(world, "bot/upper", Vec3(0, 0, 0.6));
  const BodyId fore = addBox(world, "bot/fore", Vec3(0.1, 0, 1.0));
  const BodyId tool = addBox(world, "bot/tool", Vec3(0.1, 0, 1.4));
  const BodyId finger = addBox(world, "bot/finger", Vec3(0.2, 0, 1.4));
  const BodyId door = addBox(world, "door_leaf", Vec3(3, 0, 1));
  EXPECT_TRUE(world.createJoint(axisJoint("bot/shoulder", JointType::Revolute, base, upper, Vec3(0, 0, 0.4),
                                          Vec3::UnitY())).ok());
  EXPECT_TRUE(world.createJoint(axisJoint("door", JointType::Revolute, BodyId{}, door, Vec3(3, 0, 1),
                                          Vec3::UnitZ())).ok());
  EXPECT_TRUE(world.createJoint(axisJoint("bot/slide", JointType::Prismatic, upper, fore, Vec3(0.1, 0, 0.8),
                                          Vec3::UnitZ())).ok());
  const auto weld = world.createJoint(axisJoint("bot/weld", JointType::Fixed, fore, tool, Vec3(0.1, 0, 1.2),
                                                Vec3::UnitZ()));
  EXPECT_TRUE(weld.ok()) << weld.error().message;
  JointDef follower = axisJoint("bot/finger", JointType::Revolute, tool, finger, Vec3(0.15, 0, 1.4), Vec3::UnitX());
  follower.mimic = {true, "bot/shoulder", 0.5, 0.0};
  EXPECT_TRUE(world.createJoint(follower).ok());
  return world;
}

// A command for robot "bot" in its joint order: shoulder, slide, finger.
rbsim::robot_command_t orderCommand() {
  rbsim::robot_command_t m{};
  m.client = "ctl";
  m.seq = 1;
  m.robot = "bot";
  m.apply_at_step = -1;
  m.num_joints = 3;
  m.num_names = 0;
  m.mode = {rbsim::robot_command_t::MODE_POSITION, rbsim::robot_command_t::MODE_EFFORT,
            rbsim::robot_command_t::MODE_KEEP};
  m.position = {0.4, 0.0, 0.0};
  m.velocity = {0.3, 0.0, 0.0};
  m.effort = {1.25, -7.0, 0.0};
  m.stiffness = {300.0, 0.0, 0.0};
  m.damping = {20.0, 0.0, 0.0};
  m.max_effort = {0.0, 0.0, 0.0};
  m.state_rate = 0.0;
  m.state_dynamics = -1;
  m.steps = 0;
  return m;
}

std::string refusal(const rbsim::robot_command_t& message, const World& world) {
  const auto request = robotCommandRequestFrom(message, world, world.stepCount() + 1, WrenchLimits{});
  return request ? std::string() : request.error().message;
}

TEST(RobotWire, ARobotIsTheJointsOfItsNamesPrefix) {
  const World world = robotWorld();
  EXPECT_EQ(robotNames(world), std::vector<std::string>{"bot"}) << "'door' has no prefix: no robot";
  std::vector<std::string> names;
  for (const JointId id : robotJoints(world, "bot")) names.push_back(world.jointDefinition(id).name);
  EXPECT_EQ(names, (std::vector<std::string>{"bot/shoulder", "bot/slide", "bot/finger"}))
      << "revolute and prismatic joints in creation order; the weld has no coordinate";
  EXPECT_TRUE(robotJoints(world, "bo").empty());
}

TEST(RobotWire, ACommandInJointOrderIsOneRequestPerEntryAtOneStep) {
  const World world = robotWorld();
  const auto request = robotCommandRequestFrom(orderCommand(), world, 1, WrenchLimits{});
  ASSERT_TRUE(request.ok()) << request.error().message;
  ASSERT_EQ(request->joints.size(), 2u) << "the follower's MODE_KEEP entry is left out";
  const JointCommandRequest& shoulder = request->joints[0];
  EXPECT_EQ(shoulder.joint, "bot/shoulder");
  EXPECT_EQ(shoulder.mode, JointCommandMode::Position);
  EXPECT_EQ(shoulder.target, 0.4);
  EXPECT_EQ(shoulder.targetRate, 0.3);
  EXPECT_EQ(shoulder.feedForward, 1.25);
  EXPECT_EQ(shoulder.stiffness, 300.0);
  EXPECT_EQ(shoulder.damping, 20.0);
  EXPECT_EQ(shoulder.maxEffort, std::numeric_limits<double>::infinity()) << "0: uncapped, as joint_command_t";
  const JointCommandRequest& slide = request->joints[1];
  EXPECT_EQ(slide.mode, JointCommandMode::Effort);
  EXPECT_EQ(slide.target, -7.0);
  EXPECT_EQ(shoulder.firstStep, 1);
  EXPECT_EQ(slide.firstStep, 1);

  // The actuation an entry sets: the drive with its target rate, and the
  // feed-forward as the direct effort.
  const JointActuation actuation = actuationOf(shoulder);
  EXPECT_TRUE(actuation.drive.enabled);
  EXPECT_EQ(actuation.drive.targetRate, 0.3);
  EXPECT_EQ(actuation.effort, 1.25);
  EXPECT_FALSE(actuation.motor.enabled);
}

TEST(RobotWire, NamedEntriesTakeFullOrShortNames) {
  const World world = robotWorld();
  rbsim::robot_command_t m = orderCommand();
  m.num_joints = m.num_names = 2;
  m.joint_names = {"slide", "bot/shoulder"};
  m.mode = {rbsim::robot_command_t::MODE_VELOCITY, rbsim::robot_command_t::MODE_OFF};
  m.position = m.velocity = m.effort = m.stiffness = m.damping = m.max_effort = {0.0, 0.0};
  m.velocity[0] = 0.2;
  m.effort[0] = 3.0;
  const auto request = robotCommandRequestFrom(m, world, 5, WrenchLimits{});
  ASSERT_TRUE(request.ok()) << request.error().message;
  ASSERT_EQ(request->joints.size(), 2u);
  EXPECT_EQ(request->joints[0].joint, "bot/slide");
  EXPECT_EQ(request->joints[0].mode, JointCommandMode::Velocity);
  EXPECT_EQ(request->joints[0].target, 0.2);
  EXPECT_EQ(request->joints[0].maxEffort, 50.0) << "max_effort 0: the joint's effort limit";
  EXPECT_EQ(request->joints[0].feedForward, 3.0);
  EXPECT_EQ(request->joints[1].joint, "bot/shoulder");
  EXPECT_EQ(request->joints[1].mode, JointCommandMode::Off);
}

TEST(RobotWire, OneWrongEntryRefusesTheWholeCommandSayingWhich) {
  const World world = robotWorld();
  const auto refusedWith = [&](const rbsim::robot_command_t& m, const std::string& words) {
    const std::string reason = refusal(m, world);
    EXPECT_NE(reason.find(words), std::string::npos) << "reason: '" << reason << "', expected '" << words << "'";
  };
  rbsim::robot_command_t m = orderCommand();
  m.robot = "boot";
  refusedWith(m, "unknown robot 'boot' (did you mean 'bot'?)");

  m = orderCommand();
  m.mode[2] = rbsim::robot_command_t::MODE_POSITION;
  m.stiffness[2] = 10.0;
  refusedWith(m, "entry 2 (bot/finger): follows joint 'bot/shoulder' (mimic)");

  m = orderCommand();
  m.num_joints = 2;
  m.mode.resize(2);
  for (auto* field : {&m.position, &m.velocity, &m.effort, &m.stiffness, &m.damping, &m.max_effort}) field->resize(2);
  refusedWith(m, "robot 'bot' has 3 joints");

  m = orderCommand();
  m.num_joints = m.num_names = 1;
  m.joint_names = {"sholder"};
  m.mode = {rbsim::robot_command_t::MODE_EFFORT};
  m.position = m.velocity = m.effort = m.stiffness = m.damping = m.max_effort = {0.0};
  refusedWith(m, "has no joint 'sholder' (did you mean 'bot/shoulder'?)");

  m.num_joints = m.num_names = 2;
  m.joint_names = {"slide", "bot/slide"};
  m.mode = {rbsim::robot_command_t::MODE_EFFORT, rbsim::robot_command_t::MODE_EFFORT};
  m.position = m.velocity = m.effort = m.stiffness = m.damping = m.max_effort = {0.0, 0.0};
  refusedWith(m, "joint 'bot/slide' is given twice");

  m = orderCommand();
  m.mode[0] = 7;
  refusedWith(m, "entry 0 (bot/shoulder): mode: unknown mode 7");
  m = orderCommand();
  m.velocity[0] = std::numeric_limits<double>::quiet_NaN();
  refusedWith(m, "entry 0 (bot/shoulder): velocity must be finite");
  m = orderCommand();
  m.effort[0] = 2e6;
  refusedWith(m, "entry 0 (bot/shoulder): effort 2000000.000000 exceeds the limit");
  m = orderCommand();
  m.stiffness[0] = m.damping[0] = 0.0;
  refusedWith(m, "entry 0 (bot/shoulder): stiffness and damping are both 0");
  m = orderCommand();
  m.effort[1] = std::numeric_limits<double>::infinity();
  refusedWith(m, "entry 1 (bot/slide): target must be finite");
  m = orderCommand();
  m.state_rate = -2.0;
  refusedWith(m, "state_rate must be");
  m = orderCommand();
  m.state_dynamics = 2;
  refusedWith(m, "state_dynamics must be");
  m = orderCommand();
  m.steps = -1;
  refusedWith(m, "steps must be >= 0");
  m = orderCommand();
  m.apply_at_step = 0;
  refusedWith(m, "apply_at_step 0 is in the past");
}

TEST(RobotWire, TheHandlerAppliesAllOfItOrNothingAndStepsOnlyWhenPaused) {
  Session session(robotWorld());
  CommandHandler handler(session, ServerSettings{}, "");
  const auto send = [&](const rbsim::robot_command_t& m) {
    const auto bytes = encoded(m);
    return handler.handle("RBSIM_ROBOT_COMMAND", bytes.data(), bytes.size(), 0).value();
  };

  rbsim::robot_command_t bad = orderCommand();
  bad.effort[1] = std::numeric_limits<double>::quiet_NaN();
  const CommandOutcome refused = send(bad);
  EXPECT_FALSE(refused.ack.accepted);
  EXPECT_EQ(refused.ack.kind, rbsim::ack_t::KIND_ROBOT_COMMAND);
  EXPECT_EQ(refused.ack.client, "ctl");
  EXPECT_EQ(session.jointCommands().pendingCount(), 0) << "the good entry before it is not applied either";

  rbsim::robot_command_t stepping = orderCommand();
  stepping.steps = 3;
  EXPECT_NE(send(stepping).ack.reason.find("steps needs the server to be paused"), std::string::npos);
  EXPECT_EQ(session.jointCommands().pendingCount(), 0);

  session.pause();
  stepping.state_rate = 1000.0;
  stepping.state_dynamics = 1;
  const CommandOutcome outcome = send(stepping);
  ASSERT_TRUE(outcome.ack.accepted) << outcome.ack.reason;
  EXPECT_EQ(outcome.ack.effective_step, 1);
  EXPECT_TRUE(outcome.paceChanged);
  EXPECT_EQ(session.stepsRequested(), 3);
  EXPECT_EQ(session.jointCommands().pendingCount(), 2);
  EXPECT_EQ(session.robotPublishing().at("bot").stateRate, 1000.0);
  EXPECT_TRUE(session.robotPublishing().at("bot").dynamics);

  // Both entries act from the same step.
  ASSERT_TRUE(session.takeRequestedStep());
  session.step();
  const World& world = session.world();
  const JointDef& shoulder = world.jointDefinition(world.findJoint("bot/shoulder"));
  EXPECT_TRUE(shoulder.drive.enabled);
  EXPECT_EQ(shoulder.drive.target, 0.4);
  EXPECT_EQ(shoulder.drive.targetRate, 0.3);
  EXPECT_EQ(shoulder.effort, 1.25);
  EXPECT_EQ(world.jointDefinition(world.findJoint("bot/slide")).effort, -7.0);
  EXPECT_EQ(session.jointCommands().pendingCount(), 0);

  // Rate and dynamics alone (no entries); -1 takes the world state's rate back.
  rbsim::robot_command_t settings = orderCommand();
  settings.num_joints = 0;
  settings.mode.clear();
  for (auto* field : {&settings.position, &settings.velocity, &settings.effort, &settings.stiffness,
                      &settings.damping, &settings.max_effort})
    field->clear();
  settings.state_rate = -1.0;
  settings.state_dynamics = 0;
  ASSERT_TRUE(send(settings).ack.accepted);
  EXPECT_EQ(session.robotPublishing().at("bot").stateRate, 0.0);
  EXPECT_FALSE(session.robotPublishing().at("bot").dynamics);
}

TEST(RobotWire, TheStateIsTheJointsBaseAndDynamicsOfTheWorld) {
  World world = robotWorld();
  // Moving, so that the bias forces have their velocity terms.
  ASSERT_TRUE(world.setJointEffort(world.findJoint("bot/shoulder"), 4.0).ok());
  ASSERT_TRUE(world.setJointEffort(world.findJoint("bot/slide"), 30.0).ok());
  for (int k = 0; k < 50; ++k) world.step();

  const rbsim::robot_state_t plain = robotStateMessage(world, "bot", false, 7, 3);
  EXPECT_EQ(plain.step, 50);
  EXPECT_EQ(plain.world_revision, 3);
  ASSERT_EQ(plain.num_joints, 3);
  EXPECT_EQ(plain.joint_names, (std::vector<std::string>{"bot/shoulder", "bot/slide", "bot/finger"}));
  EXPECT_EQ(plain.leader, (std::vector<int32_t>{-1, -1, 0}));
  for (int i = 0; i < 3; ++i) {
    const JointState state = world.jointState(world.findJoint(plain.joint_names[static_cast<std::size_t>(i)]));
    EXPECT_EQ(plain.position[static_cast<std::size_t>(i)], state.position);
    EXPECT_EQ(plain.velocity[static_cast<std::size_t>(i)], state.rate);
    EXPECT_EQ(plain.effort[static_cast<std::size_t>(i)], state.axisEffort);
  }
  EXPECT_NE(plain.velocity[0], 0.0);
  EXPECT_EQ(plain.effort[1], 30.0);
  EXPECT_EQ(plain.base, "bot/base");
  EXPECT_TRUE(plain.base_fixed);
  EXPECT_DOUBLE_EQ(plain.base_position[2], 0.2);
  EXPECT_EQ(plain.num_dofs, 0);
  EXPECT_EQ(plain.num_links, 0);

  const rbsim::robot_state_t full = robotStateMessage(world, "bot", true, 7, 3);
  const auto model = JointSpaceDynamics::ofRobot(world, "bot/");
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(full.num_dofs, 3) << full.dynamics_note;
  const Eigen::MatrixXd mass = model->massMatrix();
  const Eigen::VectorXd bias = model->biasForces(), gravity = model->gravityTorques();
  for (int r = 0; r < 3; ++r) {
    EXPECT_EQ(full.bias[static_cast<std::size_t>(r)], bias[r]);
    EXPECT_EQ(full.gravity[static_cast<std::size_t>(r)], gravity[r]);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(full.mass_matrix[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)], mass(r, c));
  }
  EXPECT_NE(bias[0], gravity[0]) << "moving: Coriolis and centrifugal terms";
  ASSERT_EQ(full.num_links, 4);
  EXPECT_EQ(full.link_names, (std::vector<std::string>{"bot/upper", "bot/fore", "bot/tool", "bot/finger"}));
  // The frame's origin moves as the Jacobian says: J q̇ is the body's own
  // velocity at that point and its angular velocity.
  for (int l = 0; l < full.num_links; ++l) {
    const auto link = static_cast<std::size_t>(l);
    const BodyView body = world.body(world.findBody(full.link_names[link]));
    const Vec3 origin(full.link_position[link][0], full.link_position[link][1], full.link_position[link][2]);
    const Vec3 expected = body.velocityAtPoint(origin);
    Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
    for (int c = 0; c < 3; ++c) {
      const double rate = full.velocity[static_cast<std::size_t>(c)];
      for (int r = 0; r < 3; ++r) {
        linear[r] += full.link_jacobian[link][static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] * rate;
        angular[r] += full.link_jacobian[link][static_cast<std::size_t>(r + 3)][static_cast<std::size_t>(c)] * rate;
      }
    }
    EXPECT_LT((linear - expected).norm(), 1e-9) << full.link_names[link];
    EXPECT_LT((angular - body.angularVelocity()).norm(), 1e-9) << full.link_names[link];
  }
}

TEST(RobotWire, DynamicsThatCannotBeGivenSayWhy) {
  World world = robotWorld();
  const BodyId ball = addBox(world, "bot/ball", Vec3(0.1, 0, 1.8));
  JointDef socket;
  socket.name = "bot/socket";
  socket.type = JointType::Spherical;
  socket.bodyA = world.findBody("bot/tool");
  socket.bodyB = ball;
  socket.anchor = Vec3(0.1, 0, 1.6);
  ASSERT_TRUE(world.createJoint(socket).ok());
  const rbsim::robot_state_t state = robotStateMessage(world, "bot", true, 0, 1);
  EXPECT_EQ(state.num_dofs, 0);
  EXPECT_EQ(state.num_links, 0);
  EXPECT_NE(state.dynamics_note.find("spherical"), std::string::npos) << state.dynamics_note;
  EXPECT_EQ(state.num_joints, 3) << "the joints are still there";
}

}  // namespace
}  // namespace rbsim
