// What the command path refuses for safety's sake: spawned bodies whose mesh
// lies outside the spawn mesh directory, and wrenches on frozen bodies.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

#include "bridge/command_handler.h"
#include "handler_test_messages.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

using test::commandMessage;
using test::send;
using test::wrenchMessage;

const std::string kConfigData = std::string(rbsim::test_support::kTestDataDir) + "/config";

World oneBallWorld() {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  World world(settings);
  BodyDef def;
  def.name = "ball";
  def.shape = SphereShape{0.1};
  EXPECT_TRUE(world.createBody(def).ok());
  return world;
}

rbsim::command_t spawnOf(int64_t seq, const std::string& name, const std::string& file) {
  auto spawn = commandMessage("c", seq, rbsim::command_t::SPAWN);
  spawn.spawn_yaml = "{name: " + name + ", shape: {type: mesh, file: '" + file + "'}}";
  return spawn;
}

TEST(HandlerGuards, SpawnedMeshesMustLieInsideTheSpawnMeshDirectory) {
  Session session(oneBallWorld());
  CommandHandler handler(session, ServerSettings{}, kConfigData);

  const CommandOutcome inside = send(handler, spawnOf(1, "inside", "meshes/tetra.obj"));
  EXPECT_TRUE(inside.ack.accepted) << inside.ack.reason;

  const std::string absolute = std::filesystem::absolute(kConfigData + "/meshes/tetra.obj").string();
  const CommandOutcome byAbsolutePath = send(handler, spawnOf(2, "absolute", absolute));
  EXPECT_FALSE(byAbsolutePath.ack.accepted);
  EXPECT_NE(byAbsolutePath.ack.reason.find("absolute paths are not allowed"), std::string::npos)
      << byAbsolutePath.ack.reason;

  const CommandOutcome escaping = send(handler, spawnOf(3, "escaping", "../meshes/cube.obj"));
  EXPECT_FALSE(escaping.ack.accepted);
  EXPECT_NE(escaping.ack.reason.find("'..' is not allowed"), std::string::npos) << escaping.ack.reason;

  EXPECT_EQ(session.world().bodyCount(), 2);  // the ball and "inside"
  EXPECT_TRUE(session.world().findBody("absolute").isNull());
}

TEST(HandlerGuards, WrenchesOnAFrozenBodyAreRejectedAndClearIsNot) {
  Session session(oneBallWorld());
  CommandHandler handler(session, ServerSettings{}, ".");
  ASSERT_TRUE(send(handler, wrenchMessage("c", 1, "ball")).ack.accepted);
  ASSERT_TRUE(session.world().freezeBody(session.world().findBody("ball"), FreezeReason::NonFiniteState));

  const CommandOutcome pushed = send(handler, wrenchMessage("c", 2, "ball"));
  EXPECT_FALSE(pushed.ack.accepted);
  EXPECT_NE(pushed.ack.reason.find("is frozen (non-finite state); RESET or REMOVE it"),
            std::string::npos)
      << pushed.ack.reason;

  auto clear = wrenchMessage("c", 3, "ball");
  clear.mode = rbsim::wrench_t::MODE_CLEAR;
  EXPECT_TRUE(send(handler, clear).ack.accepted);

  // RESET brings back the initial world, where the ball was never frozen.
  EXPECT_TRUE(send(handler, commandMessage("c", 4, rbsim::command_t::RESET)).ack.accepted);
  EXPECT_TRUE(send(handler, wrenchMessage("c", 5, "ball")).ack.accepted);
}

}  // namespace
}  // namespace rbsim
