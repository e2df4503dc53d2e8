// RBSIM_ROBOT_COMMAND as the server receives it: the bytes of one LCM
// message are decoded as robot_command_t and validated against a world with
// a robot (robotCommandRequestFrom); an accepted request is scheduled and
// stepped, so that whatever passes validation also has to be safe to apply,
// and the robot's state, with and without its dynamics, to read out.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include <rbsim/robot_command_t.hpp>

#include "bridge/message_decode.h"
#include "bridge/robot_messages.h"
#include "session/joint_command_scheduler.h"

namespace {

using namespace rbsim;

// Robot "bot": a hinge, a slider with limits, a weld, a follower of the
// hinge (mimic) and a ball joint; and a hinge "door" of no robot. Coarse
// steps, as the other message fuzzers.
World buildRobotWorld() {
  WorldSettings settings;
  settings.dt = 0.01;
  World world(settings);
  const auto add = [&](const char* name, const Vec3& position) {
    BodyDef def;
    def.name = name;
    def.shape = BoxShape{Vec3(0.05, 0.05, 0.2)};
    def.position = position;
    const auto id = world.createBody(def);
    if (!id) {
      std::fprintf(stderr, "rbsim fuzz: the robot world cannot create '%s'\n", name);
      std::abort();
    }
    return *id;
  };
  const BodyId upper = add("bot/upper", Vec3(0, 0, 0.6));
  const BodyId fore = add("bot/fore", Vec3(0.1, 0, 1.0));
  const BodyId tool = add("bot/tool", Vec3(0.1, 0, 1.4));
  const BodyId finger = add("bot/finger", Vec3(0.2, 0, 1.4));
  const BodyId ball = add("bot/ball", Vec3(0.1, 0, 1.8));
  const BodyId door = add("door_leaf", Vec3(3, 0, 1));
  const auto join = [&](const char* name, JointType type, BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis,
                        const char* leader = nullptr) {
    JointDef def;
    def.name = name;
    def.type = type;
    def.bodyA = a;
    def.bodyB = b;
    def.anchor = anchor;
    def.axis = axis;
    if (type == JointType::Prismatic) def.limit = {true, -0.2, 0.2};
    if (type == JointType::Revolute) def.actuatorLimits.effort = 80.0;
    if (leader != nullptr) def.mimic = {true, leader, -0.5, 0.1};
    if (!world.createJoint(def)) {
      std::fprintf(stderr, "rbsim fuzz: the robot world cannot create joint '%s'\n", name);
      std::abort();
    }
  };
  join("bot/shoulder", JointType::Revolute, BodyId{}, upper, Vec3(0, 0, 0.4), Vec3::UnitY());
  join("bot/slide", JointType::Prismatic, upper, fore, Vec3(0.1, 0, 0.8), Vec3::UnitZ());
  join("bot/weld", JointType::Fixed, fore, tool, Vec3(0.1, 0, 1.2), Vec3::UnitZ());
  join("bot/finger", JointType::Revolute, tool, finger, Vec3(0.15, 0, 1.4), Vec3::UnitX(), "bot/shoulder");
  join("bot/socket", JointType::Spherical, tool, ball, Vec3(0.1, 0, 1.6), Vec3::UnitZ());
  join("door", JointType::Revolute, BodyId{}, door, Vec3(3, 0, 1), Vec3::UnitZ());
  return world;
}

const World& robotWorld() {
  static const World world = buildRobotWorld();
  return world;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rbsim::robot_command_t message;
  if (!decodeWholeMessage(message, data, size)) return 0;

  World world = robotWorld();
  const auto request = robotCommandRequestFrom(message, world, world.stepCount() + 1, WrenchLimits{});
  if (!request) return 0;
  JointCommandScheduler scheduler;
  for (const JointCommandRequest& joint : request->joints) scheduler.add(joint);
  // Enough steps for apply_at_step a little ahead.
  for (int i = 0; i < 4; ++i) {
    scheduler.applyForStep(world, world.stepCount() + 1);
    world.step();
  }
  for (const std::string& robot : robotNames(world)) {
    (void)robotStateMessage(world, robot, false, 0, 1);
    (void)robotStateMessage(world, robot, true, 0, 1);
  }
  return 0;
}
