// Determinism with contact: a pile run twice is bit-identical, and its hash
// is golden (checked in Release and Debug by scripts/run_tests.sh).
#include <gtest/gtest.h>

#include <cstdio>

#include "unit/solver/contact_test_worlds.h"
#include "scenes/scene_random.h"

namespace rbsim {
namespace {

World makePile() {
  World world(testing::contactSettings(0.2, 0.5));
  testing::addGround(world);
  scenes::SceneRandom random(0x9113u);
  for (int i = 0; i < 60; ++i) {
    const int layer = i / 16, column = i % 16;
    BodyDef def;
    def.name = "box" + std::to_string(i);
    def.shape = i % 3 == 0 ? Shape{SphereShape{0.1}} : Shape{BoxShape{Vec3::Constant(0.1)}};
    def.position = Vec3((column % 4 - 1.5) * 0.25 + random.uniform(-0.01, 0.01),
                        (column / 4 - 1.5) * 0.25 + random.uniform(-0.01, 0.01), 0.15 + 0.25 * layer);
    def.orientation = Quaternion::fromAxisAngle(Vec3(random.uniform(-1, 1), random.uniform(-1, 1), 1.0),
                                                random.uniform(-0.1, 0.1));
    EXPECT_TRUE(world.createBody(def).ok());
  }
  return world;
}

uint64_t runPile(int steps) {
  World world = makePile();
  for (int i = 0; i < steps; ++i) world.step();
  return world.stateHash();
}

TEST(ContactDeterminism, APileRunTwiceIsBitIdentical) {
  World a = makePile(), b = makePile();
  for (int i = 0; i < 1500; ++i) {
    a.step();
    b.step();
    ASSERT_EQ(a.stateHash(), b.stateHash()) << "step " << i;
  }
  EXPECT_GT(a.contactPointCount(), 50) << "the pile is in contact";
}

// (0x7a4debe64701f31f before a flat patch's four contact points chosen by where they are, not by micrometre depth differences.)
TEST(ContactDeterminism, GoldenHash) {
  const uint64_t hash = runPile(1500);
  std::printf("golden: pile 0x%016llx\n", static_cast<unsigned long long>(hash));
  EXPECT_EQ(hash, 0xd062a0f4719642bcull);
}

}  // namespace
}  // namespace rbsim
