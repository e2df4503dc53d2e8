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
  double maxDrift;       // m: the top box's largest sideways displacement
  double maxDepth;       // m: the deepest contact seen
  double finalEnergy;    // J
  int sleeping;
};

StackResult standStack(int count, bool sleeping) {
  WorldSettings settings = contactSettings(0.0, 0.5);
  settings.contact.sleeping = sleeping;
  World world(settings);
  addGround(world);
  BodyId top;
  for (int k = 0; k < count; ++k)
    top = addBox(world, "box" + std::to_string(k), Vec3::Constant(0.1), Vec3(0, 0, 0.1 + 0.2 * k));
  StackResult r{0.0, 0.0, 0.0, 0};
  for (int i = 0; i < 10000; ++i) {  // 10 s
    world.step();
    const Vec3 x = world.body(top).position();
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

TEST(Stacking, StacksOfFiveAndTenStandForTenSeconds) {
  for (int count : {5, 10}) {
    const StackResult r = standStack(count, true);
    EXPECT_LT(r.maxDrift, 1e-3) << count << " boxes";
    EXPECT_LT(r.maxDepth, 1e-3) << count << " boxes";
    EXPECT_EQ(r.sleeping, count) << "the stack comes to rest and sleeps";
  }
}

TEST(Stacking, StacksComeToRestWithoutSleeping) {
  for (int count : {5, 10, 20}) {
    const StackResult r = standStack(count, false);
    EXPECT_LT(r.finalEnergy, 1e-9) << count << " boxes";
    EXPECT_LT(r.maxDepth, 1e-3) << count << " boxes";
    EXPECT_LT(r.maxDrift, count <= 10 ? 1e-3 : 1e-2) << count << " boxes";
  }
}

}  // namespace
}  // namespace rbsim
