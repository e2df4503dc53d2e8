// Sleeping never eats a push: a wrench wakes its island before the step in
// which it first acts, a pushed body never falls asleep, and falling asleep
// never throws away momentum given in that step. A push of F for T then
// changes the velocity by exactly F T / m, whenever it comes.
#include <gtest/gtest.h>

#include <cmath>

#include "rbsim/physics/world.h"

namespace rbsim {
namespace {

constexpr double kDt = 1e-3;  // s

// A free box at rest in zero gravity, sleeping on (it falls asleep after the
// sleep time at rest), optionally resting on a frictionless ground in gravity
// instead, so that the push must also wake a contact island.
struct Scene {
  World world;
  BodyId box;
};

Scene makeScene(bool onGround) {
  WorldSettings settings;
  settings.dt = kDt;
  settings.gravity = onGround ? Vec3(0, 0, -9.81) : Vec3::Zero();
  settings.contact.defaultMaterial.friction = 0.0;
  settings.contact.defaultMaterial.staticFriction = 0.0;
  Scene scene{World(settings), {}};
  if (onGround) {
    BodyDef ground;
    ground.name = "ground";
    ground.shape = PlaneShape{};
    ground.isStatic = true;
    EXPECT_TRUE(scene.world.createBody(ground).ok());
  }
  BodyDef box;
  box.name = "box";
  box.shape = BoxShape{Vec3(0.1, 0.2, 0.15)};
  box.mass = 2.0;
  box.position = Vec3(0, 0, onGround ? 0.15 : 1.0);
  scene.box = *scene.world.createBody(box);
  return scene;
}

// The step (1-based, as stepCount() after it) in which the untouched box
// falls asleep.
int64_t sleepStep(bool onGround) {
  Scene scene = makeScene(onGround);
  while (!scene.world.body(scene.box).isSleeping()) {
    scene.world.step();
    if (scene.world.stepCount() > 5000) return -1;
  }
  return scene.world.stepCount();
}

// Pushes the box horizontally with F for `steps` steps from step `first`
// (the step taken from state first − 1) and returns its x velocity after the
// last of them; fails the test if a state shows a velocity taken back.
double pushedVelocity(bool onGround, int64_t first, int64_t steps, double force) {
  Scene scene = makeScene(onGround);
  double previous = 0.0;
  while (scene.world.stepCount() < first + steps - 1) {
    const bool pushing = scene.world.stepCount() + 1 >= first;
    if (pushing)
      scene.world.applyWrench(scene.box, {Vec3(force, 0, 0), Vec3::Zero(), scene.world.body(scene.box).position(), Wrench::Frame::World});
    scene.world.step();
    const double v = scene.world.body(scene.box).linearVelocity().x();
    if (pushing) {
      EXPECT_FALSE(scene.world.body(scene.box).isSleeping())
          << "asleep under the force at step " << scene.world.stepCount();
      EXPECT_GT(v, previous) << "a velocity taken back at step " << scene.world.stepCount();
    }
    previous = v;
  }
  return previous;
}

TEST(SleepAndWrenches, APushAtAnyMomentAroundTheSleepTimeGivesFTOverM) {
  for (bool onGround : {false, true}) {
    const int64_t asleep = sleepStep(onGround);
    ASSERT_GT(asleep, 400) << "the box falls asleep after about the sleep time";
    const double mass = 2.0;
    // 0.25 s at 4 N (well above the sleep velocity), and 0.05 s at 0.1 N
    // (2.5 mm/s: below it, so that the body would pass for resting).
    for (const auto& [steps, force] : {std::pair{250, 4.0}, std::pair{50, 0.1}}) {
      for (int64_t first = asleep - 25; first <= asleep + 5; ++first) {
        const double v = pushedVelocity(onGround, first, steps, force);
        const double expected = force * steps * kDt / mass;
        EXPECT_NEAR(v, expected, 1e-12 * expected)
            << (onGround ? "on the ground" : "free") << ", " << steps << " steps of " << force
            << " N from step " << first << " (sleep at " << asleep << ")";
      }
    }
  }
}

TEST(SleepAndWrenches, APersistentlyPushedBodyNeverFallsAsleep) {
  // A force too small to move it past the sleep velocity in 2 s (1 mm/s).
  Scene scene = makeScene(false);
  for (int i = 0; i < 2000; ++i) {
    scene.world.applyWrench(scene.box, {Vec3(1e-3, 0, 0), Vec3::Zero(), scene.world.body(scene.box).position(),
                                        Wrench::Frame::World});
    scene.world.step();
    ASSERT_FALSE(scene.world.body(scene.box).isSleeping()) << "step " << scene.world.stepCount();
  }
  EXPECT_NEAR(scene.world.body(scene.box).linearVelocity().x(), 1e-3 * 2.0 / 2.0, 1e-15);
}

}  // namespace
}  // namespace rbsim
