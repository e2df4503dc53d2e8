// Joints on the wire: joint_command_t checked and scheduled, joints_t and
// world_t's joints built from the world, against the World's own numbers
// and closed forms.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <limits>
#include <vector>

#include <rbsim/joint_command_t.hpp>

#include "bridge/command_handler.h"
#include "bridge/message_decode.h"
#include "bridge/wire_convert.h"
#include "handler_test_messages.h"

namespace rbsim {
namespace {

using test::encoded;

// A wheel on a hinge to the world along z (no gravity), a ball on a ball
// joint, and a slider with limits.
World jointWorld() {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  World world(settings);
  BodyDef wheel;
  wheel.name = "wheel";
  wheel.shape = CylinderShape{0.2, 0.05};
  wheel.mass = 2.0;
  wheel.position = Vec3(0, 0, 1);
  const BodyId wheelId = *world.createBody(wheel);
  BodyDef ball;
  ball.name = "ball";
  ball.shape = SphereShape{0.1};
  ball.mass = 1.0;
  ball.position = Vec3(3, 0, 1);
  const BodyId ballId = *world.createBody(ball);
  BodyDef carriage;
  carriage.name = "carriage";
  carriage.shape = BoxShape{Vec3(0.1, 0.1, 0.1)};
  carriage.mass = 3.0;
  carriage.position = Vec3(-3, 0, 1);
  const BodyId carriageId = *world.createBody(carriage);

  JointDef axle;
  axle.name = "axle";
  axle.type = JointType::Revolute;
  axle.bodyB = wheelId;
  axle.anchor = Vec3(0, 0, 1);
  axle.axis = Vec3::UnitZ();
  EXPECT_TRUE(world.createJoint(axle).ok());
  JointDef socket;
  socket.name = "socket";
  socket.type = JointType::Spherical;
  socket.bodyB = ballId;
  socket.anchor = Vec3(3, 0, 1.5);
  EXPECT_TRUE(world.createJoint(socket).ok());
  JointDef lift;
  lift.name = "lift";
  lift.type = JointType::Prismatic;
  lift.bodyB = carriageId;
  lift.anchor = Vec3(-3, 0, 1);
  lift.axis = Vec3::UnitX();
  lift.limit = {true, -0.5, 0.25};
  EXPECT_TRUE(world.createJoint(lift).ok());
  return world;
}

rbsim::joint_command_t jointCommand(const std::string& joint, int8_t mode, double target) {
  rbsim::joint_command_t c{};
  c.client = "test";
  c.seq = 3;
  c.joint = joint;
  c.mode = mode;
  c.target = target;
  c.apply_at_step = -1;
  return c;
}

CommandOutcome send(CommandHandler& handler, const rbsim::joint_command_t& message) {
  const auto bytes = encoded(message);
  return handler.handleJointCommand(bytes.data(), bytes.size(), 0);
}

const JointDef& definition(const World& world, const std::string& name) {
  for (int i = 0; i < world.jointCount(); ++i)
    if (world.jointDefinitionAt(i).name == name) return world.jointDefinitionAt(i);
  throw std::invalid_argument(name);
}

TEST(JointWire, RejectsBadJointCommandsNamingTheField) {
  const World world = jointWorld();
  const auto reason = [&](const rbsim::joint_command_t& c) {
    const auto r = jointCommandRequestFrom(c, world, 11, WrenchLimits{});
    return r.ok() ? std::string("accepted") : r.error().message;
  };
  const auto velocity = [] {
    auto c = jointCommand("axle", rbsim::joint_command_t::MODE_VELOCITY, 2.0);
    c.max_effort = 1.0;
    return c;
  };
  EXPECT_EQ(reason(velocity()), "accepted");
  auto c = velocity();
  c.joint = "nothing";
  EXPECT_EQ(reason(c), "joint: unknown joint 'nothing'");
  c.joint = "Axel";
  EXPECT_EQ(reason(c), "joint: unknown joint 'Axel' (did you mean 'axle'?)");
  c = velocity();
  c.joint = "socket";
  EXPECT_NE(reason(c).find("joint: 'socket' is a spherical joint, which has no axis"), std::string::npos);
  c = velocity();
  c.mode = 9;
  EXPECT_EQ(reason(c).rfind("mode: unknown mode 9", 0), 0u) << reason(c);
  c = velocity();
  c.target = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(reason(c), "target must be finite");
  c = velocity();
  c.max_effort = -1.0;
  EXPECT_EQ(reason(c).rfind("max_effort must be finite", 0), 0u) << reason(c);
  c = velocity();
  c.max_effort = std::numeric_limits<double>::infinity();
  EXPECT_EQ(reason(c).rfind("max_effort must be finite", 0), 0u) << reason(c);
  c = velocity();
  c.max_effort = 2e6;
  EXPECT_NE(reason(c).find("limits.max_torque"), std::string::npos) << reason(c);
  c = velocity();
  c.apply_at_step = 10;
  EXPECT_NE(reason(c).find("apply_at_step 10 is in the past"), std::string::npos);
  c = jointCommand("lift", rbsim::joint_command_t::MODE_EFFORT, -2e6);
  EXPECT_NE(reason(c).find("limits.max_force"), std::string::npos) << reason(c);
  c = jointCommand("lift", rbsim::joint_command_t::MODE_POSITION, 0.1);
  EXPECT_EQ(reason(c).rfind("stiffness and damping are both 0", 0), 0u) << reason(c);
  c.stiffness = -1.0;
  EXPECT_EQ(reason(c), "stiffness must be finite and >= 0");
  c.stiffness = 10.0;
  c.damping = std::numeric_limits<double>::infinity();
  EXPECT_EQ(reason(c), "damping must be finite and >= 0");
  c.damping = 1.0;
  c.max_effort = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(reason(c).rfind("max_effort must be a number", 0), 0u) << reason(c);
  c.max_effort = 0.0;
  EXPECT_EQ(reason(c), "accepted");
  // OFF needs no numbers, but still an axis.
  c = jointCommand("lift", rbsim::joint_command_t::MODE_OFF, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(reason(c), "accepted");
  c.joint = "socket";
  EXPECT_NE(reason(c).find("no axis"), std::string::npos);
}

// A velocity motor without max_effort would do nothing: it takes the joint's
// effort limit (within max_torque / max_force), or is refused saying so.
TEST(JointWire, AVelocityCommandWithoutMaxEffortTakesTheJointsEffortLimit) {
  World world = jointWorld();
  BodyDef rotor;
  rotor.name = "rotor";
  rotor.shape = CylinderShape{0.2, 0.05};
  rotor.mass = 2.0;
  rotor.position = Vec3(0, 3, 1);
  JointDef servo;
  servo.name = "servo";
  servo.type = JointType::Revolute;
  servo.bodyB = *world.createBody(rotor);
  servo.anchor = Vec3(0, 3, 1);
  servo.actuatorLimits.effort = 12.5;
  ASSERT_TRUE(world.createJoint(servo).ok());

  auto c = jointCommand("servo", rbsim::joint_command_t::MODE_VELOCITY, 0.5);
  auto request = jointCommandRequestFrom(c, world, 1, WrenchLimits{});
  ASSERT_TRUE(request.ok()) << request.error().message;
  EXPECT_EQ(request->maxEffort, 12.5);
  // A cap given is kept, even one under the joint's.
  c.max_effort = 3.0;
  request = jointCommandRequestFrom(c, world, 1, WrenchLimits{});
  ASSERT_TRUE(request.ok()) << request.error().message;
  EXPECT_EQ(request->maxEffort, 3.0);
  // A joint stronger than a client may command gets the client's most.
  c.max_effort = 0.0;
  WrenchLimits tight;
  tight.maxTorque = 10.0;
  request = jointCommandRequestFrom(c, world, 1, tight);
  ASSERT_TRUE(request.ok()) << request.error().message;
  EXPECT_EQ(request->maxEffort, 10.0);

  // The axle has no effort limit: 0 is refused, naming the joint and the fix.
  c.joint = "axle";
  request = jointCommandRequestFrom(c, world, 1, WrenchLimits{});
  ASSERT_FALSE(request.ok());
  EXPECT_EQ(request.error().message.rfind("max_effort: give --max-effort (max_effort > 0): joint 'axle' has no "
                                          "effort limit",
                                          0),
            0u)
      << request.error().message;
  // A position drive without a cap is not a no-op: it is uncapped, and the
  // solver still holds it to the joint's effort limit.
  c = jointCommand("axle", rbsim::joint_command_t::MODE_POSITION, 0.5);
  c.stiffness = 10.0;
  request = jointCommandRequestFrom(c, world, 1, WrenchLimits{});
  ASSERT_TRUE(request.ok()) << request.error().message;
  EXPECT_EQ(request->maxEffort, std::numeric_limits<double>::infinity());
}

// Each mode sets all three actuators; the ack says when.
TEST(JointWire, ModesAreExclusiveAndTakeEffectAtTheAckedStep) {
  Session session(jointWorld());
  CommandHandler handler(session, ServerSettings{}, ".");
  session.step();
  auto velocity = jointCommand("lift", rbsim::joint_command_t::MODE_VELOCITY, 0.5);
  velocity.max_effort = 4.0;
  CommandOutcome outcome = send(handler, velocity);
  ASSERT_TRUE(outcome.ack.accepted) << outcome.ack.reason;
  EXPECT_EQ(outcome.ack.kind, rbsim::ack_t::KIND_JOINT_COMMAND);
  EXPECT_EQ(outcome.ack.request, rbsim::joint_command_t::MODE_VELOCITY);
  EXPECT_EQ(outcome.ack.client, "test");
  EXPECT_EQ(outcome.ack.seq, 3);
  EXPECT_EQ(outcome.ack.effective_step, 2);
  EXPECT_FALSE(definition(session.world(), "lift").motor.enabled);  // not before its step
  session.step();
  const JointDef* lift = &definition(session.world(), "lift");
  EXPECT_TRUE(lift->motor.enabled);
  EXPECT_EQ(lift->motor.targetRate, 0.5);
  EXPECT_EQ(lift->motor.maxEffort, 4.0);
  EXPECT_FALSE(lift->drive.enabled);
  EXPECT_EQ(lift->effort, 0.0);

  auto position = jointCommand("lift", rbsim::joint_command_t::MODE_POSITION, 0.1);
  position.stiffness = 100.0;
  position.damping = 5.0;
  position.max_effort = -1.0;  // uncapped
  position.apply_at_step = 5;
  outcome = send(handler, position);
  ASSERT_TRUE(outcome.ack.accepted) << outcome.ack.reason;
  EXPECT_EQ(outcome.ack.effective_step, 5);
  session.step();  // step 3
  session.step();  // step 4
  EXPECT_TRUE(definition(session.world(), "lift").motor.enabled);
  session.step();  // step 5
  lift = &definition(session.world(), "lift");
  EXPECT_FALSE(lift->motor.enabled);
  EXPECT_TRUE(lift->drive.enabled);
  EXPECT_EQ(lift->drive.target, 0.1);
  EXPECT_EQ(lift->drive.stiffness, 100.0);
  EXPECT_EQ(lift->drive.damping, 5.0);
  EXPECT_EQ(lift->drive.frequency, 0.0);
  EXPECT_EQ(lift->drive.maxEffort, std::numeric_limits<double>::infinity());

  ASSERT_TRUE(send(handler, jointCommand("lift", rbsim::joint_command_t::MODE_EFFORT, -3.0)).ack.accepted);
  session.step();
  lift = &definition(session.world(), "lift");
  EXPECT_FALSE(lift->motor.enabled);
  EXPECT_FALSE(lift->drive.enabled);
  EXPECT_EQ(lift->effort, -3.0);

  ASSERT_TRUE(send(handler, jointCommand("lift", rbsim::joint_command_t::MODE_OFF, 0.0)).ack.accepted);
  session.step();
  lift = &definition(session.world(), "lift");
  EXPECT_FALSE(lift->motor.enabled);
  EXPECT_FALSE(lift->drive.enabled);
  EXPECT_EQ(lift->effort, 0.0);

  // A rejection changes nothing and schedules nothing.
  outcome = send(handler, jointCommand("socket", rbsim::joint_command_t::MODE_EFFORT, 1.0));
  EXPECT_FALSE(outcome.ack.accepted);
  EXPECT_EQ(outcome.ack.effective_step, -1);
  EXPECT_EQ(session.jointCommands().pendingCount(), 0);
  // RESET drops what is scheduled.
  position.apply_at_step = 100;
  ASSERT_TRUE(send(handler, position).ack.accepted);
  session.resetToInitialWorld();
  EXPECT_EQ(session.jointCommands().pendingCount(), 0);
}

// A command scheduled ahead for a joint whose body is removed before its
// step is dropped; the other joints' commands still apply.
// A distance joint made with a spring takes MODE_POSITION (its rest
// length and gains) and nothing else; a rope (a distance joint without a
// spring) no command.
TEST(JointWire, ASpringTakesARestLengthAndGainsAndNothingElse) {
  World world;
  BodyDef bob;
  bob.name = "bob";
  bob.shape = SphereShape{0.05};
  bob.mass = 1.0;
  bob.position = Vec3(0, 0, -1);
  const BodyId bobId = *world.createBody(bob);
  bob.name = "lamp";
  bob.position = Vec3(2, 0, -1);
  const BodyId lampId = *world.createBody(bob);
  JointDef spring;
  spring.name = "spring";
  spring.type = JointType::Distance;
  spring.bodyB = bobId;
  spring.anchor = Vec3::Zero();
  spring.anchorB = Vec3(0, 0, -1);
  spring.drive = {true, 1.0, 50.0, 2.0};
  ASSERT_TRUE(world.createJoint(spring).ok());
  JointDef rope;
  rope.name = "rope";
  rope.type = JointType::Distance;
  rope.bodyB = lampId;
  rope.anchor = Vec3(2, 0, 0);
  rope.anchorB = Vec3(2, 0, -1);
  rope.limit = {true, 0.0, 1.2};
  ASSERT_TRUE(world.createJoint(rope).ok());
  const auto reason = [&](const rbsim::joint_command_t& c) {
    const auto r = jointCommandRequestFrom(c, world, 1, WrenchLimits{});
    return r.ok() ? std::string("accepted") : r.error().message;
  };
  auto c = jointCommand("spring", rbsim::joint_command_t::MODE_POSITION, 0.7);
  c.stiffness = 80.0;
  c.damping = 4.0;
  c.max_effort = 30.0;
  EXPECT_EQ(reason(c), "accepted");
  const auto request = jointCommandRequestFrom(c, world, 1, WrenchLimits{});
  ASSERT_TRUE(request.ok());
  ASSERT_TRUE(applyJointCommand(world, world.findJoint("spring"), *request).ok());
  const JointDef& set = definition(world, "spring");
  EXPECT_TRUE(set.drive.enabled);
  EXPECT_EQ(set.drive.target, 0.7);
  EXPECT_EQ(set.drive.stiffness, 80.0);
  EXPECT_EQ(set.drive.damping, 4.0);
  EXPECT_EQ(set.drive.maxEffort, 30.0);
  EXPECT_EQ(set.length, 0.7);
  c.target = -0.1;
  EXPECT_EQ(reason(c), "target (the spring's rest length) must be >= 0 m (got -0.100000)");
  for (const int8_t mode : {rbsim::joint_command_t::MODE_OFF, rbsim::joint_command_t::MODE_VELOCITY,
                            rbsim::joint_command_t::MODE_EFFORT}) {
    c = jointCommand("spring", mode, 0.5);
    c.max_effort = 1.0;
    EXPECT_EQ(reason(c).rfind("mode: 'spring' is a distance spring, which takes only MODE_POSITION", 0), 0u)
        << reason(c);
  }
  c = jointCommand("rope", rbsim::joint_command_t::MODE_POSITION, 0.5);
  c.stiffness = 10.0;
  EXPECT_NE(reason(c).find("joint: 'rope' is a distance joint, which has no axis"), std::string::npos) << reason(c);
}

TEST(JointWire, ACommandForARemovedJointIsDropped) {
  Session session(jointWorld());
  CommandHandler handler(session, ServerSettings{}, ".");
  auto axle = jointCommand("axle", rbsim::joint_command_t::MODE_EFFORT, 1.0);
  axle.apply_at_step = 3;
  auto lift = jointCommand("lift", rbsim::joint_command_t::MODE_EFFORT, 2.0);
  lift.apply_at_step = 3;
  ASSERT_TRUE(send(handler, axle).ack.accepted);
  ASSERT_TRUE(send(handler, lift).ack.accepted);
  ASSERT_TRUE(session.world().removeBody(session.world().findBody("wheel")));
  for (int i = 0; i < 3; ++i) session.step();
  EXPECT_EQ(session.jointCommands().pendingCount(), 0);
  EXPECT_EQ(session.world().findJoint("axle"), JointId{});
  EXPECT_EQ(definition(session.world(), "lift").effort, 2.0);
}

TEST(JointWire, GarbageOnTheJointCommandChannelIsRejected) {
  Session session(jointWorld());
  CommandHandler handler(session, ServerSettings{}, ".");
  const uint8_t garbage[] = {1, 2, 3, 4, 5};
  const auto outcome = handler.handle("RBSIM_JOINT_COMMAND", garbage, sizeof garbage, 0);
  ASSERT_TRUE(outcome.has_value());
  EXPECT_FALSE(outcome->ack.accepted);
  EXPECT_EQ(outcome->ack.kind, rbsim::ack_t::KIND_JOINT_COMMAND);
  EXPECT_EQ(outcome->ack.reason, "undecodable joint_command_t message (5 bytes)");
}

// The decoders of the joint types are hardened as the others are
// (lcmtypes/harden_decoders.cmake): a joint name whose length prefix is 0,
// negative or INT32_MIN, or an embedded NUL, is refused, not thrown on.
TEST(JointWire, MalformedJointNamesAreRefusedByTheDecoder) {
  auto message = jointCommand("axle", rbsim::joint_command_t::MODE_OFF, 0.0);
  const std::vector<uint8_t> good = encoded(message);
  // hash (8), utime (8), client length (4) and characters with NUL, seq (8).
  const std::size_t jointLength = 8 + 8 + 4 + message.client.size() + 1 + 8;
  for (const int32_t length : {0, -1, INT32_MIN}) {
    std::vector<uint8_t> bytes = good;
    const auto u = static_cast<uint32_t>(length);
    for (int i = 0; i < 4; ++i) bytes[jointLength + static_cast<std::size_t>(i)] = static_cast<uint8_t>(u >> (24 - 8 * i));
    rbsim::joint_command_t decoded;
    EXPECT_FALSE(decodeWholeMessage(decoded, bytes.data(), bytes.size())) << length;
  }
  std::vector<uint8_t> nul = good;
  nul[jointLength + 4 + 1] = 0;  // "a\0le"
  rbsim::joint_command_t decoded;
  EXPECT_FALSE(decodeWholeMessage(decoded, nul.data(), nul.size()));
  EXPECT_TRUE(decodeWholeMessage(decoded, good.data(), good.size()));
}

// Joint commands go through the same admission as wrenches and commands.
TEST(JointWire, ReadOnlyAndTheRateLimitCoverJointCommands) {
  ServerSettings readOnly;
  readOnly.readOnly = true;
  Session session(jointWorld());
  CommandHandler locked(session, readOnly, ".");
  const auto effort = jointCommand("axle", rbsim::joint_command_t::MODE_EFFORT, 1.0);
  EXPECT_NE(send(locked, effort).ack.reason.find("read-only"), std::string::npos);

  ServerSettings limited;
  limited.clientRate = 1.0;
  limited.clientBurst = 2;
  CommandHandler handler(session, limited, ".");
  EXPECT_TRUE(send(handler, effort).ack.accepted);
  EXPECT_TRUE(send(handler, effort).ack.accepted);
  const CommandOutcome third = send(handler, effort);
  EXPECT_FALSE(third.ack.accepted);
  EXPECT_NE(third.ack.reason.find("rate limit"), std::string::npos) << third.ack.reason;
  EXPECT_EQ(session.jointCommands().pendingCount(), 2);
}

// A constant torque tau on a free hinge: rate = tau t / I about the axis,
// I = m r^2 / 2 for the cylinder about its own axis.
TEST(JointWire, AnEffortCommandSpinsAFreeWheelAtTauOverI) {
  Session session(jointWorld());
  CommandHandler handler(session, ServerSettings{}, ".");
  const double tau = 0.2, inertia = 0.5 * 2.0 * 0.2 * 0.2;
  ASSERT_TRUE(send(handler, jointCommand("axle", rbsim::joint_command_t::MODE_EFFORT, tau)).ack.accepted);
  const int steps = 100;
  for (int i = 0; i < steps; ++i) session.step();
  const double t = steps * session.world().settings().dt;
  const auto pages = jointStatePages(session.world(), 0, 1);
  ASSERT_EQ(pages.size(), 1u);
  const rbsim::joint_state_t& axle = pages[0].joints[0];
  EXPECT_EQ(axle.name, "axle");
  EXPECT_NEAR(axle.rate, tau * t / inertia, 1e-9);
  // The joint step is velocity Verlet (RATTLE): exact for a constant
  // acceleration, angle = alpha t^2 / 2.
  EXPECT_NEAR(axle.position, 0.5 * tau / inertia * t * t, 1e-9);
  EXPECT_NEAR(axle.effort, tau, 1e-12);
  const auto wheel = session.world().body(session.world().findBody("wheel"));
  EXPECT_NEAR(wheel.angularVelocity().z(), axle.rate, 1e-12);
}

TEST(JointWire, JointStatesCarryTheWorldsNumbers) {
  Session session(jointWorld());
  for (int i = 0; i < 3; ++i) session.step();
  const World& world = session.world();
  const auto pages = jointStatePages(world, 42, 7);
  ASSERT_EQ(pages.size(), 1u);
  const rbsim::joints_t& page = pages[0];
  EXPECT_EQ(page.utime, 42);
  EXPECT_EQ(page.step, 3);
  EXPECT_EQ(page.world_revision, 7);
  EXPECT_EQ(page.page, 0);
  EXPECT_EQ(page.num_pages, 1);
  EXPECT_EQ(page.total_joints, 3);
  EXPECT_EQ(page.first_joint_index, 0);
  ASSERT_EQ(page.num_joints, 3);
  for (int i = 0; i < 3; ++i) {
    const JointState state = world.jointStateAt(i);
    const rbsim::joint_state_t& out = page.joints[static_cast<std::size_t>(i)];
    EXPECT_EQ(out.name, state.name);
    EXPECT_EQ(out.position, state.position);
    EXPECT_EQ(out.rate, state.rate);
    EXPECT_EQ(out.rotation[0], state.rotation.w);
    EXPECT_EQ(out.rotation[3], state.rotation.z);
    EXPECT_EQ(out.force[2], state.force.z());
    EXPECT_EQ(out.torque[1], state.torque.y());
    EXPECT_EQ(out.effort, state.axisEffort);
    EXPECT_EQ(out.at_limit, state.atLimit);
    EXPECT_EQ(out.error, state.error);
    EXPECT_TRUE(out.active);
  }
}

TEST(JointWire, TheWorldDescriptionListsTheJoints) {
  const World world = jointWorld();
  const auto pages = worldDescriptionPages(world, 0, 1);
  ASSERT_EQ(pages.size(), 1u);
  const rbsim::world_t& page = pages[0];
  EXPECT_EQ(page.total_joints, 3);
  EXPECT_EQ(page.first_joint_index, 0);
  ASSERT_EQ(page.num_joints, 3);
  EXPECT_EQ(page.num_bodies, 3);
  const rbsim::joint_description_t& axle = page.joints[0];
  EXPECT_EQ(axle.name, "axle");
  EXPECT_EQ(axle.type, "revolute");
  EXPECT_EQ(axle.body_a, "world");
  EXPECT_EQ(axle.body_b, "wheel");
  EXPECT_NEAR(axle.anchor_a[2], 1.0, 1e-15);
  EXPECT_NEAR(axle.anchor_b[2], 1.0, 1e-15);
  EXPECT_NEAR(axle.axis[2], 1.0, 1e-15);
  EXPECT_FALSE(axle.limit_enabled);
  EXPECT_EQ(page.joints[1].type, "spherical");
  const rbsim::joint_description_t& lift = page.joints[2];
  EXPECT_EQ(lift.type, "prismatic");
  EXPECT_TRUE(lift.limit_enabled);
  EXPECT_EQ(lift.lower_limit, -0.5);
  EXPECT_EQ(lift.upper_limit, 0.25);
  EXPECT_NEAR(lift.axis[0], 1.0, 1e-15);
}

// What a viewer or a robot client reads beyond the geometry: where an
// axis's coordinate counts from, its actuator's limits and its own losses
// (0 where unset or, for these, meaningless), and a body that collides
// with nothing.
TEST(JointWire, TheWorldDescriptionCarriesAnAxisJointsZeroLimitsAndLosses) {
  World world = jointWorld();
  BodyDef sensor;
  sensor.name = "sensor";
  sensor.shape = SphereShape{0.02};
  sensor.mass = 0.1;
  sensor.position = Vec3(0, 3, 1);
  sensor.collides = false;
  const BodyId sensorId = *world.createBody(sensor);
  JointDef pan;
  pan.name = "pan";
  pan.type = JointType::Revolute;
  pan.bodyB = sensorId;
  pan.anchor = Vec3(0, 3, 1.2);
  pan.axis = Vec3::UnitZ();
  pan.limit = {true, -1.0, 1.0};
  pan.position = 0.25;
  pan.actuatorLimits.effort = 3.5;
  pan.actuatorLimits.rate = 2.0;
  pan.damping = 0.3;
  pan.friction = 0.05;
  ASSERT_TRUE(world.createJoint(pan).ok());

  const auto pages = worldDescriptionPages(world, 0, 1);
  ASSERT_EQ(pages.size(), 1u);
  std::vector<uint8_t> bytes(static_cast<std::size_t>(pages[0].getEncodedSize()));
  ASSERT_EQ(pages[0].encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  rbsim::world_t page;
  ASSERT_EQ(page.decode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  ASSERT_EQ(page.num_bodies, 4);
  EXPECT_TRUE(page.bodies[0].collides);
  EXPECT_FALSE(page.bodies[3].collides);
  ASSERT_EQ(page.num_joints, 4);
  const rbsim::joint_description_t& out = page.joints[3];
  EXPECT_EQ(out.name, "pan");
  EXPECT_EQ(out.initial_position, 0.25);
  EXPECT_EQ(out.effort_limit, 3.5);
  EXPECT_EQ(out.rate_limit, 2.0);
  EXPECT_EQ(out.damping, 0.3);
  EXPECT_EQ(out.friction, 0.05);
  // The axle has no actuator limits (infinite in JointDef): 0 on the wire.
  // The ball joint has no axis: 0 for all of them.
  for (int i : {0, 1}) {
    const rbsim::joint_description_t& other = page.joints[static_cast<std::size_t>(i)];
    EXPECT_EQ(other.initial_position, 0.0) << other.name;
    EXPECT_EQ(other.effort_limit, 0.0) << other.name;
    EXPECT_EQ(other.rate_limit, 0.0) << other.name;
    EXPECT_EQ(other.damping, 0.0) << other.name;
    EXPECT_EQ(other.friction, 0.0) << other.name;
  }
}

// Many joints with long names: every page fits a datagram, indices are
// contiguous, and the joints follow the bodies in the description.
TEST(JointWire, ManyJointsArePagedInOrder) {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  World world(settings);
  const int count = 600;
  const std::string padding(120, 'x');
  for (int i = 0; i < count; ++i) {
    BodyDef body;
    body.name = "link_" + std::to_string(i) + padding;
    body.shape = SphereShape{0.1};
    body.position = Vec3(3.0 * i, 0, 0);
    const BodyId id = *world.createBody(body);
    JointDef joint;
    joint.name = "pin_" + std::to_string(i) + padding;
    joint.type = JointType::Revolute;
    joint.bodyB = id;
    joint.anchor = Vec3(3.0 * i, 0, 0.5);
    joint.axis = Vec3::UnitY();
    ASSERT_TRUE(world.createJoint(joint).ok());
  }
  const auto states = jointStatePages(world, 0, 1);
  ASSERT_GT(states.size(), 1u);
  int next = 0;
  for (std::size_t p = 0; p < states.size(); ++p) {
    EXPECT_LE(static_cast<std::size_t>(states[p].getEncodedSize()), kMaxPagePayloadBytes);
    EXPECT_EQ(states[p].page, static_cast<int32_t>(p));
    EXPECT_EQ(states[p].num_pages, static_cast<int32_t>(states.size()));
    EXPECT_EQ(states[p].total_joints, count);
    EXPECT_EQ(states[p].first_joint_index, next);
    for (const auto& joint : states[p].joints) EXPECT_EQ(joint.name, "pin_" + std::to_string(next++) + padding);
  }
  EXPECT_EQ(next, count);

  const auto description = worldDescriptionPages(world, 0, 1);
  ASSERT_GT(description.size(), 1u);
  int nextBody = 0, nextJoint = 0;
  for (std::size_t p = 0; p < description.size(); ++p) {
    const rbsim::world_t& page = description[p];
    EXPECT_LE(static_cast<std::size_t>(page.getEncodedSize()), kMaxPagePayloadBytes);
    EXPECT_EQ(page.page, static_cast<int32_t>(p));
    EXPECT_EQ(page.num_pages, static_cast<int32_t>(description.size()));
    EXPECT_EQ(page.total_bodies, count);
    EXPECT_EQ(page.total_joints, count);
    EXPECT_EQ(page.first_body_index, nextBody);
    EXPECT_EQ(page.first_joint_index, nextJoint);
    // A page with joints holds the last bodies, or none.
    if (page.num_joints > 0 && page.num_bodies > 0) {
      EXPECT_EQ(nextBody + page.num_bodies, count);
    }
    nextBody += page.num_bodies;
    nextJoint += page.num_joints;
    if (page.num_joints > 0) {
      EXPECT_EQ(page.joints.back().name, "pin_" + std::to_string(nextJoint - 1) + padding);
    }
  }
  EXPECT_EQ(nextBody, count);
  EXPECT_EQ(nextJoint, count);
}

}  // namespace
}  // namespace rbsim
