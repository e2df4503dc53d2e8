// SPAWN and REMOVE with joints: a spawn of bodies and joints is added whole
// or not at all, its joints may hold the world's bodies, and REMOVE takes a
// joint (or a body with its joints) and the commands waiting for it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <rbsim/joint_command_t.hpp>

#include "bridge/command_handler.h"
#include "bridge/wire_convert.h"
#include "handler_test_messages.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

using test::commandMessage;
using test::encoded;
using test::send;

constexpr double kGravity = 9.81;

// A static post and one free box on the default gravity (the spawns hang
// things from them).
World postWorld() {
  WorldSettings settings;
  settings.gravity = Vec3(0, 0, -kGravity);
  World world(settings);
  BodyDef post;
  post.name = "post";
  post.shape = BoxShape{Vec3(0.05, 0.05, 1.0)};
  post.isStatic = true;
  post.position = Vec3(0, 0, 1);
  EXPECT_TRUE(world.createBody(post).ok());
  BodyDef box;
  box.name = "box";
  box.shape = BoxShape{Vec3(0.1, 0.1, 0.1)};
  box.mass = 1.0;
  box.position = Vec3(5, 0, 3);
  EXPECT_TRUE(world.createBody(box).ok());
  return world;
}

struct Fixture {
  explicit Fixture(ServerSettings settings = {}) : session(postWorld()), handler(session, settings, ".") {}
  CommandOutcome spawn(const std::string& yaml) {
    auto message = commandMessage("c", ++seq, rbsim::command_t::SPAWN);
    message.spawn_yaml = yaml;
    return send(handler, message);
  }
  CommandOutcome remove(const std::string& body, const std::string& joint) {
    auto message = commandMessage("c", ++seq, rbsim::command_t::REMOVE);
    message.body = body;
    message.joint = joint;
    return send(handler, message);
  }
  CommandOutcome jointCommand(const std::string& joint, double effort, int64_t atStep) {
    rbsim::joint_command_t c{};
    c.client = "c";
    c.seq = ++seq;
    c.joint = joint;
    c.mode = rbsim::joint_command_t::MODE_EFFORT;
    c.target = effort;
    c.apply_at_step = atStep;
    const auto bytes = encoded(c);
    return handler.handleJointCommand(bytes.data(), bytes.size(), 0);
  }
  World& world() { return session.world(); }
  Session session;
  CommandHandler handler;
  int64_t seq = 0;
};

// A pendulum hung from the post: a bob on a rod (a distance joint) to the
// post's top, and a second bob hinged to the first.
const char* const kPendulum = R"(
bodies:
  - {name: bob, shape: {type: sphere, radius: 0.05}, mass: 2.0, position: [1.0, 0, 2.0]}
  - {name: bob2, shape: {type: sphere, radius: 0.05}, mass: 1.0, position: [2.0, 0, 2.0]}
joints:
  - {name: rod, type: distance, body_a: post, body_b: bob, anchor: [0, 0, 2.0], anchor_b: [1.0, 0, 2.0]}
  - {name: elbow, type: revolute, body_a: bob, body_b: bob2, anchor: [1.0, 0, 2.0], axis: [0, 1, 0]}
)";

TEST(SpawnJoints, ASpawnAddsBodiesAndJointsThatHoldAtOnce) {
  Fixture f;
  const CommandOutcome outcome = f.spawn(kPendulum);
  ASSERT_TRUE(outcome.ack.accepted) << outcome.ack.reason;
  EXPECT_TRUE(outcome.publishWorld);
  EXPECT_EQ(f.world().bodyCount(), 4);
  ASSERT_EQ(f.world().jointCount(), 2);
  const JointDef& rod = f.world().jointDefinitionAt(0);
  EXPECT_EQ(rod.name, "rod");
  EXPECT_EQ(rod.type, JointType::Distance);
  EXPECT_EQ(rod.length, 1.0);  // the anchors' distance when it was spawned
  EXPECT_EQ(f.world().jointDefinitionAt(1).name, "elbow");

  // It swings: the rod keeps its length to the joint solver's precision and
  // the bob falls below the post's top.
  for (int i = 0; i < 500; ++i) f.session.step();
  const Vec3 bob = f.world().body(f.world().findBody("bob")).position();
  EXPECT_NEAR((bob - Vec3(0, 0, 2.0)).norm(), 1.0, 1e-9);
  EXPECT_LT(bob.z(), 1.5);
  EXPECT_LT(f.world().jointState(f.world().findJoint("elbow")).error, 1e-9);

  // The description carries the rod's length for viewers.
  const auto pages = worldDescriptionPages(f.world(), 0, 2);
  ASSERT_EQ(pages.size(), 1u);
  ASSERT_EQ(pages[0].num_joints, 2);
  EXPECT_EQ(pages[0].joints[0].length, 1.0);
  EXPECT_EQ(pages[0].joints[0].body_a, "post");
  EXPECT_EQ(pages[0].joints[1].length, 0.0);
}

TEST(SpawnJoints, AJointAloneMayJoinTheWorldsBodies) {
  Fixture f;
  const CommandOutcome outcome = f.spawn(
      "joints:\n  - {name: pin, type: spherical, body_a: world, body_b: box, anchor: [5, 0, 3.5]}\n");
  ASSERT_TRUE(outcome.ack.accepted) << outcome.ack.reason;
  EXPECT_EQ(f.world().bodyCount(), 2);
  ASSERT_EQ(f.world().jointCount(), 1);
  // The box hangs from the pin instead of falling.
  for (int i = 0; i < 1000; ++i) f.session.step();
  const Vec3 box = f.world().body(f.world().findBody("box")).position();
  EXPECT_NEAR((box - Vec3(5, 0, 3.5)).norm(), 0.5, 1e-9);
}

// A viewer draws a shoulder's cone and a spring from the description.
TEST(SpawnJoints, TheDescriptionCarriesAConesAngleAndASpring) {
  Fixture f;
  ASSERT_TRUE(f.spawn("joints:\n  - {name: shoulder, type: spherical, body_a: post, body_b: box, anchor: [5, 0, 3.5], "
                      "axis: [0, 0, -1], cone_limit: 0.7}\n"
                      "  - {name: bungee, type: distance, body_a: world, body_b: box, anchor: [5, 0, 4], "
                      "anchor_b: [5, 0, 3], spring: {stiffness: 50}, length: 0.75}\n")
                  .ack.accepted);
  const auto pages = worldDescriptionPages(f.world(), 0, 2);
  ASSERT_EQ(pages[0].num_joints, 2);
  EXPECT_EQ(pages[0].joints[0].cone_angle, 0.7);
  EXPECT_NEAR(pages[0].joints[0].axis[2], -1.0, 1e-15);
  EXPECT_EQ(pages[0].joints[0].length, 0.0);
  EXPECT_FALSE(pages[0].joints[0].spring);
  EXPECT_TRUE(pages[0].joints[1].spring);
  EXPECT_EQ(pages[0].joints[1].length, 0.75) << "its rest length";
  EXPECT_FALSE(pages[0].joints[1].limit_enabled);
}

TEST(SpawnJoints, OneBodyIsStillASpawnAsBefore) {
  Fixture f;
  const CommandOutcome outcome =
      f.spawn("{name: probe, shape: {type: sphere, radius: 0.1}, mass: 1, position: [0, 3, 1]}");
  ASSERT_TRUE(outcome.ack.accepted) << outcome.ack.reason;
  EXPECT_EQ(f.world().bodyCount(), 3);
  EXPECT_EQ(f.world().jointCount(), 0);
}

// Each refusal names where in spawn_yaml it is, and the world is as before.
TEST(SpawnJoints, ARefusedSpawnAddsNothingAndSaysWhere) {
  Fixture f;
  const auto refused = [&](const std::string& yaml) {
    const CommandOutcome outcome = f.spawn(yaml);
    EXPECT_FALSE(outcome.ack.accepted) << yaml;
    EXPECT_EQ(f.world().bodyCount(), 2) << yaml;
    EXPECT_EQ(f.world().jointCount(), 0) << yaml;
    EXPECT_EQ(outcome.ack.effective_step, -1);
    return outcome.ack.reason;
  };
  EXPECT_EQ(refused("joints:\n  - {name: j, type: spherical, body_a: world, body_b: ghost, anchor: [0, 0, 0]}\n"),
            "spawn_yaml:2:55: joints[0].body_b: no body named \"ghost\" (a body's name, or world) (did you mean "
            "'post'?)");
  // A name close to one of the world's or the spawn's own bodies: said.
  EXPECT_EQ(refused("bodies:\n  - {name: lid, shape: {type: sphere, radius: 0.1}, mass: 1}\njoints:\n"
                    "  - {name: j, type: spherical, body_a: Boxx, body_b: lidd, anchor: [0, 0, 0]}\n"),
            "spawn_yaml:4:40: joints[0].body_a: no body named \"Boxx\" (a body's name, or world) (did you mean 'box'?)");
  EXPECT_NE(refused("bodies:\n  - {name: lid, shape: {type: sphere, radius: 0.1}, mass: 1}\njoints:\n"
                    "  - {name: j, type: spherical, body_a: box, body_b: lidd, anchor: [0, 0, 0]}\n")
                .find("no body named \"lidd\" (a body's name, or world) (did you mean 'lid'?)"),
            std::string::npos);
  EXPECT_EQ(refused("bodies:\n  - {name: box, shape: {type: sphere, radius: 0.1}, mass: 1}\n"),
            "spawn_yaml:2:12: bodies[0].name: the world already has a body named \"box\"");
  EXPECT_EQ(refused("{name: box, shape: {type: sphere, radius: 0.1}, mass: 1}"),
            "spawn_yaml:1:8: name: the world already has a body named \"box\"");
  EXPECT_EQ(refused("{name: world, shape: {type: sphere, radius: 0.1}, mass: 1}"),
            "spawn_yaml:1:8: name: \"world\" is reserved: joints name the world itself so; give the body another name");
  EXPECT_EQ(refused("bodies: []\nworld: {dt: 0.001}\n"),
            "spawn_yaml:2:1: world: unknown key; a spawn of bodies, robots and joints has: bodies, robots, joints");
  EXPECT_EQ(refused("joints:\n  - {name: j, type: revolute, body_a: world, body_b: post, anchor: [0, 0, 0], "
                    "axis: [0, 0, 1]}\n"),
            "spawn_yaml:2:54: joints[0].body_b: neither side moves (both are the world or static bodies)");
  // Found only by the World, after the bodies were added: they are taken out
  // again. A rod shorter than the World's 1e-9 m has no length.
  const std::string reason = refused(
      "bodies:\n  - {name: bead, shape: {type: sphere, radius: 0.05}, mass: 1, position: [0, 0, 2]}\n"
      "joints:\n  - {name: zero, type: distance, body_a: post, body_b: bead, anchor: [0, 0, 2], "
      "anchor_b: [0, 0, 2], length: 1e-12}\n");
  EXPECT_EQ(reason.rfind("spawn_yaml:4:5: joints[0]: joint 'zero': the length must be positive", 0), 0u) << reason;
  EXPECT_TRUE(f.world().findBody("bead").isNull());
  // A joint name the world already has.
  ASSERT_TRUE(f.spawn("joints:\n  - {name: pin, type: spherical, body_a: world, body_b: box, anchor: [5, 0, 3.5]}\n")
                  .ack.accepted);
  const CommandOutcome again =
      f.spawn("bodies:\n  - {name: bead, shape: {type: sphere, radius: 0.05}, mass: 1, position: [0, 0, 2]}\n"
              "joints:\n  - {name: pin, type: spherical, body_a: post, body_b: bead, anchor: [0, 0, 2]}\n");
  EXPECT_FALSE(again.ack.accepted);
  EXPECT_EQ(again.ack.reason, "spawn_yaml:4:5: joints[0]: joint 'pin': the name is taken by another joint");
  EXPECT_TRUE(f.world().findBody("bead").isNull());
  EXPECT_EQ(f.world().jointCount(), 1);
}

TEST(SpawnJoints, TheLimitsCountTheWholeSpawn) {
  ServerSettings settings;
  settings.maxBodies = 3;
  settings.maxJoints = 1;
  Fixture f(settings);
  CommandOutcome outcome = f.spawn(kPendulum);  // 2 bodies and 2 joints: 4 bodies
  EXPECT_FALSE(outcome.ack.accepted);
  EXPECT_EQ(outcome.ack.reason, "the world has 2 bodies; 2 more would exceed limits.max_bodies (3)");
  settings.maxBodies = 10;
  Fixture g(settings);
  outcome = g.spawn(kPendulum);
  EXPECT_FALSE(outcome.ack.accepted);
  EXPECT_EQ(outcome.ack.reason, "the world has 0 joints; 2 more would exceed limits.max_joints (1)");
  EXPECT_EQ(g.world().bodyCount(), 2);
}

TEST(SpawnJoints, RemoveTakesAJointAndTheCommandsWaitingForIt) {
  Fixture f;
  ASSERT_TRUE(f.spawn(kPendulum).ack.accepted);
  ASSERT_TRUE(f.jointCommand("elbow", 0.5, 10).ack.accepted);
  ASSERT_EQ(f.session.jointCommands().pendingCount(), 1);

  CommandOutcome outcome = f.remove("", "elbow");
  ASSERT_TRUE(outcome.ack.accepted) << outcome.ack.reason;
  EXPECT_TRUE(outcome.publishWorld);
  EXPECT_TRUE(f.world().findJoint("elbow").isNull());
  EXPECT_EQ(f.world().bodyCount(), 4);  // the bodies stay
  EXPECT_EQ(f.session.jointCommands().pendingCount(), 0);

  // A new joint of the same name does not inherit the old one's command.
  ASSERT_TRUE(f.spawn("joints:\n  - {name: elbow, type: revolute, body_a: bob, body_b: bob2, anchor: [1.0, 0, 2.0], "
                      "axis: [0, 1, 0]}\n")
                  .ack.accepted);
  for (int i = 0; i < 12; ++i) f.session.step();
  EXPECT_EQ(f.world().jointDefinitionAt(f.world().jointCount() - 1).effort, 0.0);

  EXPECT_EQ(f.remove("", "elbow2").ack.reason, "unknown joint 'elbow2' (did you mean 'elbow'?)");
  EXPECT_EQ(f.remove("bob", "elbow").ack.reason, "REMOVE names a body (body) or a joint (joint), exactly one of the two");
  EXPECT_EQ(f.remove("", "").ack.reason, "REMOVE names a body (body) or a joint (joint), exactly one of the two");
}

TEST(SpawnJoints, RemovingABodyTakesItsJointsAndTheirCommands) {
  Fixture f;
  ASSERT_TRUE(f.spawn(kPendulum).ack.accepted);
  ASSERT_TRUE(f.jointCommand("elbow", 0.5, 10).ack.accepted);
  ASSERT_TRUE(f.remove("bob2", "").ack.accepted);
  EXPECT_TRUE(f.world().findJoint("elbow").isNull());
  EXPECT_FALSE(f.world().findJoint("rod").isNull());
  EXPECT_EQ(f.session.jointCommands().pendingCount(), 0);
  ASSERT_TRUE(f.remove("bob", "").ack.accepted);
  EXPECT_EQ(f.world().jointCount(), 0);
}

// A spawned robot's visuals come with it, their meshes under the spawn
// route (relative to the spawn directory), in the world's description; a
// plain body spawned later under one of its names is drawn as itself again.
TEST(SpawnJoints, ASpawnedRobotsVisualsAreInTheDescription) {
  Session session(postWorld());
  CommandHandler handler(session, ServerSettings{}, std::string(rbsim::test_support::kTestDataDir) + "/urdf");
  auto message = commandMessage("c", 1, rbsim::command_t::SPAWN);
  message.spawn_yaml =
      "robots:\n  - {name: v, urdf: visual_arm.urdf, fixed_base: true, package_paths: [packages]}\n";
  const CommandOutcome outcome = send(handler, message);
  ASSERT_TRUE(outcome.ack.accepted) << outcome.ack.reason;
  const auto pages = worldDescriptionPages(session.world(), 0, session.worldRevision(), &session.visuals());
  const rbsim::body_description_t* arm = nullptr;
  for (const auto& page : pages)
    for (const auto& body : page.bodies)
      if (body.name == "v/arm") arm = &body;
  ASSERT_NE(arm, nullptr);
  ASSERT_EQ(arm->num_visuals, 3);
  EXPECT_EQ(arm->visuals[0].kind, "mesh");
  EXPECT_EQ(arm->visuals[0].mesh_url, "spawn/packages/rbsim_test_parts/meshes/tetrahedron.stl");
  EXPECT_TRUE(arm->visuals[0].has_color);
  EXPECT_DOUBLE_EQ(arm->visuals[0].scale[2], 0.5);
  EXPECT_EQ(arm->visuals[1].kind, "cylinder");
  EXPECT_EQ(arm->visuals[2].kind, "sphere");
  EXPECT_EQ(arm->visuals[2].scale[0], 0.0);  // not a mesh's
  // The world's own bodies have none.
  EXPECT_EQ(pages[0].bodies[0].num_visuals, 0);

  auto remove = commandMessage("c", 2, rbsim::command_t::REMOVE);
  remove.body = "v/arm";
  ASSERT_TRUE(send(handler, remove).ack.accepted);
  auto plain = commandMessage("c", 3, rbsim::command_t::SPAWN);
  plain.spawn_yaml = "{name: v/arm, shape: {type: sphere, radius: 0.1}, position: [3, 0, 1]}";
  ASSERT_TRUE(send(handler, plain).ack.accepted);
  EXPECT_EQ(session.visuals().count("v/arm"), 0u);
  EXPECT_EQ(session.visuals().count("v/base"), 1u);
}

}  // namespace
}  // namespace rbsim
