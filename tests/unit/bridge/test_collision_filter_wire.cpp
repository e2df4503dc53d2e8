// Collision filters over LCM: world_t carries every body's group and mask
// (body_description_t.collision_group, collision_mask; the defaults for a
// body that sets none), and SPAWN takes them in spawn_yaml, validated at
// spawn_yaml:line:column, as it takes a robot's self_collision and
// disable_collisions. A spawned body then collides as its filter says.
#include <gtest/gtest.h>

#include <string>

#include "bridge/command_handler.h"
#include "bridge/wire_convert.h"
#include "persist/session_checkpoint.h"
#include "handler_test_messages.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

using test::commandMessage;
using test::send;

// A weightless world with one box at the origin (group 1, mask all).
World boxWorld() {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  settings.threads = 1;
  World world(settings);
  BodyDef box;
  box.name = "box";
  box.shape = BoxShape{Vec3::Constant(0.5)};
  EXPECT_TRUE(world.createBody(box).ok());
  return world;
}

struct Fixture {
  Fixture() : session(boxWorld()), handler(session, ServerSettings{}, std::string(test_support::kTestDataDir) + "/urdf") {}
  CommandOutcome spawn(const std::string& yaml) {
    auto message = commandMessage("c", ++seq, rbsim::command_t::SPAWN);
    message.spawn_yaml = yaml;
    return send(handler, message);
  }
  World& world() { return session.world(); }
  bool touching(const std::string& a, const std::string& b) {
    const int32_t serialA = world().body(world().findBody(a)).serial();
    const int32_t serialB = world().body(world().findBody(b)).serial();
    for (const SolvedManifold& m : world().contacts())
      if ((m.serialA == serialA && m.serialB == serialB) || (m.serialA == serialB && m.serialB == serialA))
        return true;
    return false;
  }
  Session session;
  CommandHandler handler;
  int64_t seq = 0;
};

rbsim::world_t decodedDescription(const World& world) {
  const auto pages = worldDescriptionPages(world, 0, 1);
  EXPECT_EQ(pages.size(), 1u);
  const std::vector<uint8_t> bytes = test::encoded(pages[0]);
  rbsim::world_t decoded;
  EXPECT_EQ(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  return decoded;
}

TEST(CollisionFilterWire, WorldDescriptionCarriesEveryBodysGroupAndMask) {
  World world = boxWorld();
  BodyDef tray;
  tray.name = "tray";
  tray.shape = SphereShape{0.1};
  tray.position = Vec3(3, 0, 0);
  tray.collisionFilter = {0x80000000u, 0xFFFFFFFEu};  // the top bit: beyond int32_t
  ASSERT_TRUE(world.createBody(tray).ok());
  const rbsim::world_t decoded = decodedDescription(world);
  ASSERT_EQ(decoded.num_bodies, 2);
  EXPECT_EQ(decoded.bodies[0].collision_group, 1);
  EXPECT_EQ(decoded.bodies[0].collision_mask, 4294967295LL);
  EXPECT_EQ(decoded.bodies[1].collision_group, 2147483648LL);
  EXPECT_EQ(decoded.bodies[1].collision_mask, 4294967294LL);
}

TEST(CollisionFilterWire, SpawnTakesAGroupAndMaskTheBodyThenRespects) {
  Fixture f;
  // Overlapping the box; its mask leaves out the box's group 1.
  const CommandOutcome apart =
      f.spawn("{name: ghost, shape: {type: box, half_extents: [0.5, 0.5, 0.5]}, position: [0, 0, 0.9],\n"
              " collision_group: 2, collision_mask: 0xFFFFFFFE}");
  ASSERT_TRUE(apart.ack.accepted) << apart.ack.reason;
  // Overlapping the box with the defaults.
  const CommandOutcome plain =
      f.spawn("{name: solid, shape: {type: box, half_extents: [0.5, 0.5, 0.5]}, position: [0, 0, -0.9]}");
  ASSERT_TRUE(plain.ack.accepted) << plain.ack.reason;
  EXPECT_EQ(f.world().body(f.world().findBody("ghost")).description().collisionFilter,
            (CollisionFilter{2, 0xFFFFFFFEu}));
  EXPECT_EQ(f.world().body(f.world().findBody("solid")).description().collisionFilter, CollisionFilter{});
  f.session.step();
  EXPECT_FALSE(f.touching("box", "ghost"));
  EXPECT_TRUE(f.touching("box", "solid"));
  const rbsim::world_t decoded = decodedDescription(f.world());
  ASSERT_EQ(decoded.num_bodies, 3);
  EXPECT_EQ(decoded.bodies[1].name, "ghost");
  EXPECT_EQ(decoded.bodies[1].collision_group, 2);
  EXPECT_EQ(decoded.bodies[1].collision_mask, 4294967294LL);
}

TEST(CollisionFilterWire, SpawnRefusesABadGroupAtItsLineAndColumn) {
  Fixture f;
  const CommandOutcome refused =
      f.spawn("{name: ghost, shape: {type: sphere, radius: 0.1},\n collision_group: -2}");
  ASSERT_FALSE(refused.ack.accepted);
  EXPECT_NE(refused.ack.reason.find("spawn_yaml:2:19: collision_group: expected a whole number from 0 to "
                                    "4294967295"),
            std::string::npos)
      << refused.ack.reason;
  EXPECT_TRUE(f.world().findBody("ghost").isNull());
}

TEST(CollisionFilterWire, ASpawnedRobotsLinksFollowItsSelfCollisionSettings) {
  Fixture f;
  const CommandOutcome off = f.spawn("robots:\n  - {name: off, urdf: folded_arm.urdf, fixed_base: true, position: [5, 0, 0]}");
  ASSERT_TRUE(off.ack.accepted) << off.ack.reason;
  const CommandOutcome on = f.spawn(
      "robots:\n  - {name: on, urdf: folded_arm.urdf, fixed_base: true, position: [-5, 0, 0],\n"
      "     self_collision: true, disable_collisions: [[base, tool]]}");
  ASSERT_TRUE(on.ack.accepted) << on.ack.reason;
  World& world = f.world();
  const auto canCollide = [&](const std::string& a, const std::string& b) {
    return world.canCollide(world.findBody(a), world.findBody(b));
  };
  EXPECT_FALSE(canCollide("off/base", "off/fore"));
  EXPECT_FALSE(canCollide("off/base", "off/tool"));
  EXPECT_TRUE(canCollide("on/base", "on/fore"));
  EXPECT_FALSE(canCollide("on/base", "on/tool"));
  EXPECT_FALSE(canCollide("on/base", "on/upper"));  // joined
  f.session.step();
  EXPECT_FALSE(f.touching("off/base", "off/fore"));
  EXPECT_TRUE(f.touching("on/base", "on/fore"));
  EXPECT_FALSE(f.touching("on/base", "on/tool"));
  // An unknown link is refused, named with the nearest, at its line and column.
  const CommandOutcome typo =
      f.spawn("robots:\n  - {name: typo, urdf: folded_arm.urdf, disable_collisions: [[base, tol]]}");
  ASSERT_FALSE(typo.ack.accepted);
  EXPECT_NE(typo.ack.reason.find("spawn_yaml:2:69: robots[0].disable_collisions[0][1]: the robot has no link "
                                 "named \"tol\" (nearest: \"tool\")"),
            std::string::npos)
      << typo.ack.reason;
}

// A checkpoint of a session whose filters came over the wire keeps them:
// the restored world has the same groups, masks and excluded pairs, and
// steps on bit for bit.
TEST(CollisionFilterWire, ACheckpointKeepsSpawnedFiltersAndContinuesBitIdentically) {
  Fixture f;
  ASSERT_TRUE(f.spawn("robots:\n  - {name: arm, urdf: folded_arm.urdf, fixed_base: true, position: [0, 0, 2],\n"
                      "     self_collision: true, disable_collisions: [[base, tool]]}")
                  .ack.accepted);
  ASSERT_TRUE(f.spawn("{name: ghost, shape: {type: box, half_extents: [0.5, 0.5, 0.5]}, position: [0, 0, 0.9],\n"
                      " collision_group: 2, collision_mask: 0xFFFFFFFE}")
                  .ack.accepted);
  for (int i = 0; i < 50; ++i) f.session.step();
  const auto payload = encodeSessionCheckpoint(f.session);
  ASSERT_TRUE(payload.ok()) << payload.error().message;
  auto state = decodeSessionCheckpoint(*payload, f.world().settings());
  ASSERT_TRUE(state.ok()) << state.error().message;
  World& restored = state->world;
  EXPECT_EQ(restored.body(restored.findBody("ghost")).description().collisionFilter,
            (CollisionFilter{2, 0xFFFFFFFEu}));
  EXPECT_EQ(restored.excludedPairs().size(), f.world().excludedPairs().size());
  EXPECT_FALSE(restored.canCollide(restored.findBody("arm/base"), restored.findBody("arm/tool")));
  EXPECT_TRUE(restored.canCollide(restored.findBody("arm/base"), restored.findBody("arm/fore")));
  for (int i = 0; i < 200; ++i) {
    f.session.step();
    restored.step();
  }
  EXPECT_EQ(restored.stateHash(), f.world().stateHash());
}

}  // namespace
}  // namespace rbsim
