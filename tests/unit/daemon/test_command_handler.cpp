// The command path without LCM: bytes in, acks and session changes out.
#include <gtest/gtest.h>

#include "daemon/command_handler.h"
#include "handler_test_messages.h"

namespace rbsim {
namespace {

using test::commandMessage;
using test::send;
using test::wrenchMessage;

World twoBallWorld() {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  World world(settings);
  for (const char* name : {"a", "b"}) {
    BodyDef def;
    def.name = name;
    def.shape = SphereShape{0.1};
    def.mass = 1.0;
    def.position = Vec3(name[0] == 'a' ? 0.0 : 5.0, 0.0, 0.0);
    EXPECT_TRUE(world.createBody(def).ok());
  }
  return world;
}

struct Fixture {
  explicit Fixture(ServerSettings settings = {}) : session(twoBallWorld()), handler(session, settings, ".") {}
  Session session;
  CommandHandler handler;
};

TEST(CommandHandler, AcceptedWrenchIsScheduledForTheNextStep) {
  Fixture f;
  f.session.step();
  const CommandOutcome outcome = send(f.handler, wrenchMessage("c", 7, "a"));
  EXPECT_TRUE(outcome.ack.accepted) << outcome.ack.reason;
  EXPECT_EQ(outcome.ack.client, "c");
  EXPECT_EQ(outcome.ack.seq, 7);
  EXPECT_EQ(outcome.ack.kind, rbsim::ack_t::KIND_WRENCH);
  EXPECT_EQ(outcome.ack.effective_step, 2);
  EXPECT_EQ(f.session.wrenches().pendingCount(), 1);
  f.session.step();
  const Body& a = f.session.world().body(f.session.world().findBody("a"));
  EXPECT_GT(a.linearMomentum().x(), 0.0);
}

TEST(CommandHandler, GarbageIsRejectedWithoutChangingAnything) {
  Fixture f;
  const uint8_t garbage[5] = {1, 2, 3, 4, 5};
  for (const auto& outcome : {f.handler.handleWrench(garbage, sizeof garbage, 0),
                              f.handler.handleCommand(garbage, sizeof garbage, 0)}) {
    EXPECT_FALSE(outcome.ack.accepted);
    EXPECT_EQ(outcome.ack.seq, -1);
    EXPECT_EQ(outcome.ack.effective_step, -1);
    EXPECT_NE(outcome.ack.reason.find("undecodable"), std::string::npos);
  }
  EXPECT_EQ(f.session.wrenches().pendingCount(), 0);
}

TEST(CommandHandler, OnlyItsOwnChannelsAreAnswered) {
  Fixture f;
  const auto bytes = test::encoded(wrenchMessage("c", 1, "a"));
  EXPECT_FALSE(f.handler.handle("RBSIM_STATE", bytes.data(), bytes.size(), 0).has_value());
  const auto outcome = f.handler.handle("RBSIM_WRENCH", bytes.data(), bytes.size(), 0);
  ASSERT_TRUE(outcome.has_value());
  EXPECT_TRUE(outcome->ack.accepted);
}

TEST(CommandHandler, PauseStepResumeDriveTheSessionState) {
  Fixture f;
  EXPECT_FALSE(send(f.handler, [] {
                 auto c = commandMessage("c", 1, rbsim::command_t::STEP);
                 c.num_steps = 3;
                 return c;
               }()).ack.accepted);
  const CommandOutcome pause = send(f.handler, commandMessage("c", 2, rbsim::command_t::PAUSE));
  EXPECT_TRUE(pause.ack.accepted);
  EXPECT_TRUE(pause.paceChanged);
  EXPECT_TRUE(f.session.paused());
  auto step = commandMessage("c", 3, rbsim::command_t::STEP);
  step.num_steps = 3;
  EXPECT_EQ(send(f.handler, step).ack.effective_step, 1);
  step.seq = 4;
  EXPECT_EQ(send(f.handler, step).ack.effective_step, 4) << "queued after the first three";
  EXPECT_EQ(f.session.stepsRequested(), 6);
  EXPECT_TRUE(send(f.handler, commandMessage("c", 5, rbsim::command_t::RESUME)).ack.accepted);
  EXPECT_FALSE(f.session.paused());
  EXPECT_EQ(f.session.stepsRequested(), 0);
}

TEST(CommandHandler, SpawnRemoveAndResetChangeTheRevision) {
  Fixture f;
  auto spawn = commandMessage("c", 1, rbsim::command_t::SPAWN);
  spawn.spawn_yaml = "{name: new_ball, shape: {type: sphere, radius: 0.2}, position: [0, 3, 0]}";
  const CommandOutcome spawned = send(f.handler, spawn);
  EXPECT_TRUE(spawned.ack.accepted) << spawned.ack.reason;
  EXPECT_TRUE(spawned.publishWorld);
  EXPECT_EQ(f.session.world().bodyCount(), 3);
  EXPECT_EQ(f.session.worldRevision(), 2);

  auto remove = commandMessage("c", 2, rbsim::command_t::REMOVE);
  remove.body = "a";
  EXPECT_TRUE(send(f.handler, remove).ack.accepted);
  EXPECT_EQ(f.session.world().bodyCount(), 2);
  remove.seq = 3;
  EXPECT_FALSE(send(f.handler, remove).ack.accepted) << "already gone";

  f.session.step();
  const CommandOutcome reset = send(f.handler, commandMessage("c", 4, rbsim::command_t::RESET));
  EXPECT_TRUE(reset.ack.accepted);
  EXPECT_EQ(reset.ack.effective_step, 2);
  EXPECT_TRUE(reset.publishState);
  EXPECT_EQ(f.session.world().stepCount(), 0);
  EXPECT_EQ(f.session.world().bodyCount(), 2);
  EXPECT_EQ(f.session.world().lastSerial(), 3) << "serials stay taken across RESET";
  EXPECT_EQ(f.session.worldRevision(), 4);
}

TEST(CommandHandler, RealTimeFactorIsPassedToTheCaller) {
  Fixture f;
  auto rate = commandMessage("c", 1, rbsim::command_t::SET_REAL_TIME_FACTOR);
  rate.real_time_factor = 2.5;
  const CommandOutcome outcome = send(f.handler, rate);
  ASSERT_TRUE(outcome.realTimeFactor.has_value());
  EXPECT_EQ(*outcome.realTimeFactor, 2.5);
  rate.real_time_factor = -1.0;
  EXPECT_FALSE(send(f.handler, rate).ack.accepted);
  EXPECT_FALSE(send(f.handler, commandMessage("c", 2, 0)).ack.accepted) << "0 is not a command";
}

}  // namespace
}  // namespace rbsim
