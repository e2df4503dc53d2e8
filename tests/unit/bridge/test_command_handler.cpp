// The command path without LCM: bytes in, acks and session changes out.
#include <gtest/gtest.h>

#include <cmath>

#include "bridge/command_handler.h"
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
  const BodyView a = f.session.world().body(f.session.world().findBody("a"));
  EXPECT_GT(a.linearMomentum().x(), 0.0);
}

// The motivating case: one run leaves a persistent wrench, the next run is a
// new client id. Its CLEAR clears nothing and says so; a CLEAR under the
// first run's id, or MODE_CLEAR_ALL_CLIENTS, clears it and says 1.
TEST(CommandHandler, ClearAcksSayHowManyWrenchesTheyCleared) {
  Fixture f;
  auto persistent = wrenchMessage("run-1", 1, "a");
  persistent.mode = rbsim::wrench_t::MODE_PERSISTENT;
  ASSERT_TRUE(send(f.handler, persistent).ack.accepted);
  f.session.step();
  auto clear = wrenchMessage("run-2", 1, "a");
  clear.mode = rbsim::wrench_t::MODE_CLEAR;
  const CommandOutcome notMine = send(f.handler, clear);
  EXPECT_TRUE(notMine.ack.accepted);
  EXPECT_EQ(notMine.ack.wrenches_cleared, 0);
  f.session.step();
  EXPECT_EQ(f.session.wrenches().activeCount(), 1);

  clear.client = "run-1";
  clear.seq = 2;
  EXPECT_EQ(send(f.handler, clear).ack.wrenches_cleared, 1);
  f.session.step();
  EXPECT_EQ(f.session.wrenches().activeCount(), 0);

  persistent.seq = 3;
  ASSERT_TRUE(send(f.handler, persistent).ack.accepted);
  auto clearAll = wrenchMessage("run-3", 1, "a");
  clearAll.mode = rbsim::wrench_t::MODE_CLEAR_ALL_CLIENTS;
  const CommandOutcome everyone = send(f.handler, clearAll);  // before it even started
  EXPECT_TRUE(everyone.ack.accepted) << everyone.ack.reason;
  EXPECT_EQ(everyone.ack.wrenches_cleared, 1);
  EXPECT_EQ(everyone.ack.request, rbsim::wrench_t::MODE_CLEAR_ALL_CLIENTS);
  f.session.step();
  EXPECT_EQ(f.session.wrenches().activeCount(), 0);
  EXPECT_EQ(send(f.handler, wrenchMessage("c", 9, "a")).ack.wrenches_cleared, 0);
}

// POINT_FRAME_CENTER_OF_MASS puts the force at the centre of mass even where
// the shape frame's origin is elsewhere (given mass properties here), so it
// turns nothing; the same force at the shape origin does.
TEST(CommandHandler, CenterOfMassPointFramePushesWithoutTurning) {
  Fixture f;
  auto spawn = commandMessage("c", 1, rbsim::command_t::SPAWN);
  spawn.spawn_yaml =
      "{name: plate, shape: {type: box, half_extents: [0.3, 0.2, 0.01]}, position: [0, 3, 0],\n"
      " mass: 2, center_of_mass: [0.1, 0, 0], inertia: [0.01, 0.02, 0.03]}";
  ASSERT_TRUE(send(f.handler, spawn).ack.accepted);
  auto push = wrenchMessage("c", 2, "plate");
  push.force[0] = 0.0;
  push.force[1] = 1.0;
  push.point_frame = rbsim::wrench_t::POINT_FRAME_CENTER_OF_MASS;
  push.point[0] = std::nan("");  // ignored
  const CommandOutcome atCentre = send(f.handler, push);
  ASSERT_TRUE(atCentre.ack.accepted) << atCentre.ack.reason;
  f.session.step();
  const World& world = f.session.world();
  const BodyView plate = world.body(world.findBody("plate"));
  EXPECT_EQ(plate.angularMomentum(), Vec3::Zero());
  EXPECT_GT(plate.linearMomentum().y(), 0.0);

  push.seq = 3;
  push.point_frame = rbsim::wrench_t::FRAME_BODY;
  push.point[0] = 0.0;  // the shape frame's origin, 0.1 m from the centre of mass
  ASSERT_TRUE(send(f.handler, push).ack.accepted);
  f.session.step();
  EXPECT_GT(plate.angularMomentum().norm(), 0.0);

  push.seq = 4;
  push.point_frame = 3;
  EXPECT_FALSE(send(f.handler, push).ack.accepted);
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

TEST(CommandHandler, SpawnWithGivenInertia) {
  Fixture f;
  auto spawn = commandMessage("c", 1, rbsim::command_t::SPAWN);
  spawn.spawn_yaml =
      "{name: plate, shape: {type: box, half_extents: [0.3, 0.2, 0.01]}, position: [0, 3, 0],\n"
      " mass: 2, center_of_mass: [0.1, 0, 0], inertia: [0.01, 0.02, 0.03]}";
  const CommandOutcome spawned = send(f.handler, spawn);
  ASSERT_TRUE(spawned.ack.accepted) << spawned.ack.reason;
  const BodyView plate = f.session.world().body(f.session.world().findBody("plate"));
  EXPECT_TRUE(plate.description().massPropertiesGiven);
  EXPECT_EQ(plate.mass(), 2.0);
  EXPECT_EQ(plate.dynamics().inertiaBody, Vec3(0.01, 0.02, 0.03));
  EXPECT_EQ(plate.position(), Vec3(0.1, 3.0, 0.0));  // the centre of mass, world frame

  spawn.seq = 2;
  spawn.spawn_yaml =
      "{name: bad, shape: {type: sphere, radius: 0.1}, mass: 1,\n inertia: [0.01, 0.01, 0.03]}";
  const CommandOutcome rejected = send(f.handler, spawn);
  EXPECT_FALSE(rejected.ack.accepted);
  EXPECT_NE(rejected.ack.reason.find(
                "spawn_yaml:2:11: inertia: no rigid body has these principal moments"),
            std::string::npos)
      << rejected.ack.reason;
  spawn.seq = 3;
  spawn.spawn_yaml = "{name: bad, shape: {type: sphere, radius: 0.1}, inertia: [0.01, 0.01, 0.01]}";
  const CommandOutcome noMass = send(f.handler, spawn);
  EXPECT_FALSE(noMass.ack.accepted);
  EXPECT_NE(noMass.ack.reason.find("spawn_yaml:1:49: inertia: inertia needs the body's mass"),
            std::string::npos)
      << noMass.ack.reason;
  EXPECT_EQ(f.session.world().bodyCount(), 3);
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

TEST(CommandHandlerLimits, ReadOnlyRejectsEveryWrenchAndCommand) {
  ServerSettings settings;
  settings.readOnly = true;
  Fixture f(settings);
  const CommandOutcome wrench = send(f.handler, wrenchMessage("c", 1, "a"));
  EXPECT_FALSE(wrench.ack.accepted);
  EXPECT_NE(wrench.ack.reason.find("read-only"), std::string::npos) << wrench.ack.reason;
  for (const int8_t command : {rbsim::command_t::PAUSE, rbsim::command_t::RESET, rbsim::command_t::PUBLISH_WORLD}) {
    const CommandOutcome outcome = send(f.handler, commandMessage("c", 2, command));
    EXPECT_FALSE(outcome.ack.accepted);
    EXPECT_FALSE(outcome.publishWorld);
  }
  EXPECT_FALSE(f.session.paused());
  EXPECT_EQ(f.session.wrenches().pendingCount(), 0);
}

TEST(CommandHandlerLimits, OnlyListedBodiesAcceptWrenches) {
  ServerSettings settings;
  settings.wrenchBodies = std::vector<std::string>{"b"};
  Fixture f(settings);
  const CommandOutcome onA = send(f.handler, wrenchMessage("c", 1, "a"));
  EXPECT_FALSE(onA.ack.accepted);
  EXPECT_NE(onA.ack.reason.find("'a' does not accept external wrenches"), std::string::npos) << onA.ack.reason;
  EXPECT_TRUE(send(f.handler, wrenchMessage("c", 2, "b")).ack.accepted);
  auto clearAll = wrenchMessage("c", 3, "");
  clearAll.mode = rbsim::wrench_t::MODE_CLEAR;
  EXPECT_TRUE(send(f.handler, clearAll).ack.accepted) << "clearing one's own wrenches is always allowed";
}

TEST(CommandHandlerLimits, RateIsLimitedPerClientWithoutQueueing) {
  ServerSettings settings;
  settings.clientRate = 10.0;  // messages/s
  settings.clientBurst = 3.0;
  Fixture f(settings);
  constexpr int64_t kSecond = 1000000000;
  int64_t now = 5 * kSecond;
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(send(f.handler, wrenchMessage("fast", i, "a"), now).ack.accepted);
  const CommandOutcome excess = send(f.handler, commandMessage("fast", 3, rbsim::command_t::PAUSE), now);
  EXPECT_FALSE(excess.ack.accepted);
  EXPECT_NE(excess.ack.reason.find("rate limit"), std::string::npos) << excess.ack.reason;
  EXPECT_FALSE(f.session.paused());
  EXPECT_TRUE(send(f.handler, wrenchMessage("other", 0, "a"), now).ack.accepted) << "per client";
  now += kSecond / 10;  // one token back
  EXPECT_TRUE(send(f.handler, wrenchMessage("fast", 4, "a"), now).ack.accepted);
  EXPECT_FALSE(send(f.handler, wrenchMessage("fast", 5, "a"), now).ack.accepted);
  EXPECT_EQ(f.session.wrenches().pendingCount(), 5) << "rejected messages leave nothing behind";
}

TEST(CommandHandlerLimits, RateLimiterForgetsClientsBeyondItsTable) {
  ClientRateLimiter limiter(1.0, 1.0);
  for (std::size_t i = 0; i < ClientRateLimiter::kMaxClients + 100; ++i)
    EXPECT_TRUE(limiter.allow("client" + std::to_string(i), static_cast<int64_t>(i)));
  EXPECT_LE(limiter.trackedClients(), ClientRateLimiter::kMaxClients);
}

TEST(CommandHandlerLimits, OversizedMessagesAreRejectedUndecoded) {
  ServerSettings settings;
  settings.maxMessageBytes = 200;
  Fixture f(settings);
  auto spawn = commandMessage("c", 1, rbsim::command_t::SPAWN);
  spawn.spawn_yaml = "{name: big, shape: {type: sphere, radius: 0.1}}" + std::string(300, ' ');
  const CommandOutcome outcome = send(f.handler, spawn);
  EXPECT_FALSE(outcome.ack.accepted);
  EXPECT_NE(outcome.ack.reason.find("max_message_bytes"), std::string::npos) << outcome.ack.reason;
  EXPECT_EQ(f.session.world().bodyCount(), 2);
}

TEST(CommandHandlerLimits, SpawnStopsAtTheMaximumNumberOfBodies) {
  ServerSettings settings;
  settings.maxBodies = 3;
  Fixture f(settings);
  auto spawn = commandMessage("c", 1, rbsim::command_t::SPAWN);
  spawn.spawn_yaml = "{name: third, shape: {type: sphere, radius: 0.1}, position: [0, 9, 0]}";
  EXPECT_TRUE(send(f.handler, spawn).ack.accepted);
  spawn.seq = 2;
  spawn.spawn_yaml = "{name: fourth, shape: {type: sphere, radius: 0.1}, position: [0, -9, 0]}";
  const CommandOutcome outcome = send(f.handler, spawn);
  EXPECT_FALSE(outcome.ack.accepted);
  EXPECT_NE(outcome.ack.reason.find("max_bodies"), std::string::npos) << outcome.ack.reason;
  EXPECT_EQ(f.session.world().bodyCount(), 3);
}

}  // namespace
}  // namespace rbsim
