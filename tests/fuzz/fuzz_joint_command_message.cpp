// RBSIM_JOINT_COMMAND as the server receives it: the bytes of one LCM
// message are decoded as joint_command_t, validated against a world with
// joints of every kind and the limits (jointCommandRequestFrom), and an
// accepted request is scheduled and stepped, so that whatever passes
// validation also has to be safe to apply, and the joints' state and
// description to read out.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include <rbsim/joint_command_t.hpp>

#include "bridge/message_decode.h"
#include "bridge/wire_convert.h"
#include "session/joint_command_scheduler.h"

namespace {

using namespace rbsim;

// A drum on an axle, a slider with limits, a ball joint and a weld, all to
// the world or between bodies; coarse steps, as the other message fuzzers.
World buildJointWorld() {
  WorldSettings settings;
  settings.dt = 0.01;
  World world(settings);
  const auto add = [&](const char* name, Shape shape, const Vec3& position) {
    BodyDef def;
    def.name = name;
    def.shape = std::move(shape);
    def.position = position;
    const auto id = world.createBody(def);
    if (!id) {
      std::fprintf(stderr, "rbsim fuzz: the joint world cannot create '%s'\n", name);
      std::abort();
    }
    return *id;
  };
  const BodyId drum = add("drum", CylinderShape{0.1, 0.1}, Vec3(-1, 0, 1));
  const BodyId slider = add("slider", BoxShape{Vec3(0.1, 0.1, 0.1)}, Vec3(1, 0, 1));
  const BodyId ball = add("ball", SphereShape{0.1}, Vec3(0, 2, 1));
  const BodyId plate = add("plate", BoxShape{Vec3(0.2, 0.2, 0.02)}, Vec3(0, -2, 1));
  const auto join = [&](const char* name, JointType type, BodyId a, BodyId b, const Vec3& anchor,
                        const Vec3& axis) {
    JointDef def;
    def.name = name;
    def.type = type;
    def.bodyA = a;
    def.bodyB = b;
    def.anchor = anchor;
    def.axis = axis;
    if (type == JointType::Prismatic) def.limit = {true, -0.2, 0.2};
    if (!world.createJoint(def)) {
      std::fprintf(stderr, "rbsim fuzz: the joint world cannot create joint '%s'\n", name);
      std::abort();
    }
  };
  join("axle", JointType::Revolute, BodyId{}, drum, Vec3(-1, 0, 1), Vec3::UnitZ());
  join("rail", JointType::Prismatic, BodyId{}, slider, Vec3(1, 0, 1), Vec3::UnitX());
  join("socket", JointType::Spherical, BodyId{}, ball, Vec3(0, 2, 1.3), Vec3::UnitZ());
  join("weld", JointType::Fixed, drum, plate, Vec3(-0.5, -1, 1), Vec3::UnitZ());
  return world;
}

const World& jointWorld() {
  static const World world = buildJointWorld();
  return world;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rbsim::joint_command_t message;
  if (!decodeWholeMessage(message, data, size)) return 0;

  World world = jointWorld();
  const auto request = jointCommandRequestFrom(message, world, world.stepCount() + 1, WrenchLimits{});
  if (!request) return 0;
  JointCommandScheduler scheduler;
  scheduler.add(*request);
  // Enough steps for apply_at_step a little ahead.
  for (int i = 0; i < 4; ++i) {
    scheduler.applyForStep(world, world.stepCount() + 1);
    world.step();
  }
  (void)jointStatePages(world, 0, 1);
  (void)worldDescriptionPages(world, 0, 1);
  return 0;
}
