// Wrench modes over steps, against momenta computed by hand.
#include <gtest/gtest.h>

#include "daemon/wrench_scheduler.h"

namespace rbsim {
namespace {

constexpr double kDt = 0.001;

World makeWorld() {
  WorldSettings settings;
  settings.dt = kDt;
  settings.gravity = Vec3::Zero();
  World world(settings);
  for (const char* name : {"a", "b"}) {
    BodyDef def;
    def.name = name;
    def.shape = SphereShape{0.1};
    def.mass = 2.0;
    EXPECT_TRUE(world.createBody(def).ok());
  }
  return world;
}

WrenchRequest push(const std::string& client, const std::string& body, double fx, WrenchMode mode,
                   int64_t firstStep, int64_t durationSteps = 1) {
  WrenchRequest r;
  r.client = client;
  r.body = body;
  r.force = Vec3(fx, 0, 0);
  r.mode = mode;
  r.firstStep = firstStep;
  r.durationSteps = durationSteps;
  return r;
}

void run(World& world, WrenchScheduler& scheduler, int steps) {
  for (int i = 0; i < steps; ++i) {
    const int64_t step = world.stepCount() + 1;
    scheduler.applyForStep(world, step);
    world.step();
    scheduler.finishStep(step);
  }
}

double momentumX(const World& world, const char* name) {
  return world.body(world.findBody(name)).linearMomentum().x();
}

TEST(WrenchScheduler, OneStepActsOnceDurationActsItsSteps) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 10.0, WrenchMode::OneStep, 1));
  scheduler.add(push("c", "b", 10.0, WrenchMode::Duration, 1, 25));
  run(world, scheduler, 100);
  EXPECT_NEAR(momentumX(world, "a"), 10.0 * kDt, 1e-15);
  EXPECT_NEAR(momentumX(world, "b"), 10.0 * kDt * 25, 1e-13);
  EXPECT_EQ(scheduler.activeCount(), 0);
}

TEST(WrenchScheduler, ScheduledWrenchStartsAtItsStep) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 1.0, WrenchMode::OneStep, 5));
  run(world, scheduler, 4);
  EXPECT_EQ(momentumX(world, "a"), 0.0);
  run(world, scheduler, 1);  // step 5
  EXPECT_NEAR(momentumX(world, "a"), kDt, 1e-18);
}

TEST(WrenchScheduler, PersistentIsReplacedPerClientAndBodyAndCleared) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 1.0, WrenchMode::Persistent, 1));
  scheduler.add(push("other", "a", 0.5, WrenchMode::Persistent, 1));
  run(world, scheduler, 10);  // 1.5 N for 10 steps
  scheduler.add(push("c", "a", 3.0, WrenchMode::Persistent, 11));  // replaces c's 1 N
  run(world, scheduler, 10);  // 3.5 N for 10 steps
  EXPECT_EQ(scheduler.activeCount(), 2);
  WrenchRequest clear = push("c", "a", 0.0, WrenchMode::Clear, 21);
  scheduler.add(clear);
  run(world, scheduler, 10);  // only other's 0.5 N
  EXPECT_NEAR(momentumX(world, "a"), (1.5 * 10 + 3.5 * 10 + 0.5 * 10) * kDt, 1e-14);
  EXPECT_EQ(scheduler.activeCount(), 1);
  // Clear with an empty body clears the client on every body.
  scheduler.add(push("other", "b", 1.0, WrenchMode::Duration, 31, 1000));
  WrenchRequest clearAll = push("other", "", 0.0, WrenchMode::Clear, 31);
  scheduler.add(clearAll);
  run(world, scheduler, 1);
  EXPECT_EQ(scheduler.activeCount(), 0);
}

TEST(WrenchScheduler, WrenchOnRemovedBodyIsDropped) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 1.0, WrenchMode::Persistent, 1));
  run(world, scheduler, 2);
  world.removeBody(world.findBody("a"));
  run(world, scheduler, 1);
  EXPECT_EQ(scheduler.activeCount(), 0);
}

}  // namespace
}  // namespace rbsim
