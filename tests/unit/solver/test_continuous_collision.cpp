// Continuous collision in the world step: a small fast sphere and a thin wall.
#include <gtest/gtest.h>

#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

// A 1 cm sphere at 500 m/s (0.5 m per 1 ms step) towards a static wall
// 5 mm thick at x = 0.5 m, no gravity. Returns the largest x the sphere's
// centre reached and its final x velocity.
struct Shot {
  double farthest;
  double finalVelocity;
};
Shot shoot(bool continuous, ContactModel model = ContactModel::Impulse, bool collides = true) {
  WorldSettings settings = testing::contactSettings(0.0, 0.0);
  settings.gravity = Vec3::Zero();
  settings.contact.model = model;
  World world(settings);
  BodyDef wall;
  wall.name = "wall";
  wall.shape = BoxShape{Vec3(0.0025, 1.0, 1.0)};
  wall.position = Vec3(0.5, 0, 0);
  wall.isStatic = true;
  EXPECT_TRUE(world.createBody(wall).ok());
  BodyDef bullet;
  bullet.name = "bullet";
  bullet.shape = SphereShape{0.01};
  bullet.position = Vec3(0.2, 0, 0);
  bullet.linearVelocity = Vec3(500.0, 0, 0);
  bullet.continuousCollision = continuous;
  bullet.collides = collides;
  const BodyId id = *world.createBody(bullet);
  Shot shot{0.0, 0.0};
  for (int i = 0; i < 10; ++i) {
    world.step();
    shot.farthest = std::max(shot.farthest, world.body(id).position().x());
  }
  shot.finalVelocity = world.body(id).linearVelocity().x();
  return shot;
}

TEST(ContinuousCollision, WithoutItTheImpulseModelStillStopsTheSphereAtTheWall) {
  // A body's contacts reach as far as it can move in a step (its speed times
  // dt), so the wall is a contact in the step the sphere would pass it, and
  // its time of impact is found there: the flag is not needed for that.
  const Shot shot = shoot(false);
  EXPECT_LT(shot.farthest, 0.4875 + 1e-6);
  EXPECT_GT(shot.farthest, 0.4875 - 1e-3);
  EXPECT_NEAR(shot.finalVelocity, 0.0, 1e-6);
}

TEST(ContinuousCollision, APenaltyWorldTunnelsWithoutIt) {
  // The penalty model has no speculative reach: without the flag the sphere
  // goes through (with it, see below, it does not).
  EXPECT_GT(shoot(false, ContactModel::Penalty).farthest, 0.6);
}

TEST(ContinuousCollision, WithItTheSphereStopsAtTheWall) {
  const Shot shot = shoot(true);
  // The wall's face is at x = 0.4975; the sphere's centre never passes
  // x = 0.4875 by more than the time-of-impact tolerance (0.1 mm).
  EXPECT_LT(shot.farthest, 0.4875 + 1e-4);
  EXPECT_GT(shot.farthest, 0.4875 - 1e-3);
  EXPECT_NEAR(shot.finalVelocity, 0.0, 1e-6);  // restitution 0: it stays at the wall
}

TEST(ContinuousCollision, ABodyThatCollidesWithNothingIsNotSweptAndFliesThroughTheWall) {
  // Flagged for continuous collision but colliding with nothing
  // (BodyDef::collides false): neither the sweeps nor the speculative
  // contacts stop it, in either model; it flies on at 0.5 m a step.
  for (const ContactModel model : {ContactModel::Impulse, ContactModel::Penalty}) {
    const Shot shot = shoot(true, model, false);
    EXPECT_NEAR(shot.farthest, 0.2 + 10 * 0.5, 1e-12);
    EXPECT_EQ(shot.finalVelocity, 500.0);
  }
}

}  // namespace
}  // namespace rbsim
