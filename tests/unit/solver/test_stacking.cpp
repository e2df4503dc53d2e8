// Resting contact: bodies rest and stack without drift or jitter.
#include <gtest/gtest.h>

#include <cmath>

#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBox;
using testing::addGround;
using testing::contactSettings;
using testing::deepestContact;

struct StackResult {
  double maxDrift;       // m: the top box's largest sideways displacement from where it started
  double maxDepth;       // m: the deepest contact seen
  double finalEnergy;    // J
  int sleeping;
};

// A tower of `count` cubes (half-extent 0.1 m, 8 kg) exactly touching, as in
// the anchors' stack scene. `perturbed` shifts each box by up to 2 mm and
// turns it by up to 0.1 rad about the vertical, so that the box–box
// manifolds are irregular quadrilaterals instead of aligned squares.
StackResult standStack(int count, bool sleeping, bool perturbed = false) {
  WorldSettings settings = contactSettings(0.0, 0.5);
  settings.contact.sleeping = sleeping;
  World world(settings);
  addGround(world);
  BodyId top;
  for (int k = 0; k < count; ++k) {
    const Vec3 offset = perturbed ? Vec3(0.002 * std::sin(1.7 * k), 0.002 * std::cos(2.3 * k), 0.0)
                                  : Vec3::Zero();
    const double yaw = perturbed ? 0.1 * std::sin(0.9 * k) : 0.0;
    top = addBox(world, "box" + std::to_string(k), Vec3::Constant(0.1),
                 offset + Vec3(0, 0, 0.1 + 0.2 * k), Quaternion::fromAxisAngle(Vec3::UnitZ(), yaw));
  }
  const Vec3 start = world.body(top).position();
  StackResult r{0.0, 0.0, 0.0, 0};
  for (int i = 0; i < 10000; ++i) {  // 10 s
    world.step();
    const Vec3 x = world.body(top).position() - start;
    r.maxDrift = std::max(r.maxDrift, std::hypot(x.x(), x.y()));
    r.maxDepth = std::max(r.maxDepth, deepestContact(world));
  }
  r.finalEnergy = world.totalKineticEnergy();
  r.sleeping = world.sleepingBodyCount();
  return r;
}

TEST(Stacking, ABoxRestsWithoutDriftOrSinking) {
  const StackResult r = standStack(1, false);
  EXPECT_LT(r.maxDrift, 1e-6);
  EXPECT_LT(r.maxDepth, 1e-3);
  EXPECT_LT(r.finalEnergy, 1e-12);
}

TEST(Stacking, StacksOfFiveTenAndTwentyStandForTenSeconds) {
  for (int count : {5, 10, 20}) {
    const StackResult r = standStack(count, true);
    EXPECT_LT(r.maxDrift, 1e-3) << count << " boxes";
    EXPECT_LT(r.maxDepth, 1e-3) << count << " boxes";
    EXPECT_EQ(r.sleeping, count) << "the stack comes to rest and sleeps";
  }
}

TEST(Stacking, StacksStandWithoutSleeping) {
  for (int count : {5, 10, 20}) {
    const StackResult r = standStack(count, false);
    EXPECT_LT(r.finalEnergy, 1e-9) << count << " boxes";
    EXPECT_LT(r.maxDepth, 1e-3) << count << " boxes";
    EXPECT_LT(r.maxDrift, 1e-3) << count << " boxes";
  }
}

TEST(Stacking, IrregularTowerOfTwentyStandsWithoutSleeping) {
  const StackResult r = standStack(20, false, true);
  EXPECT_LT(r.finalEnergy, 1e-9);
  EXPECT_LT(r.maxDepth, 1e-3);
  EXPECT_LT(r.maxDrift, 1e-3);
}

}  // namespace
}  // namespace rbsim
