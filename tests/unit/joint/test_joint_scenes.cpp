// Whole mechanisms in contact with the ground and each other.
//  - A ragdoll (15 bodies: ball joints with cones at the waist, neck,
//    shoulders and hips, hinges with limits at the elbows, wrists, knees
//    and ankles; the skeleton of bench/joints/joint_scenes.h) dropped on
//    the ground comes to rest (asleep) with no joint error above 1 cm —
//    here, above 1e-9 m or rad — on the way.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "joint/busy_jointed_world.h"
#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::makeBusyJointedWorld;
using testing::makeRagdollWorld;

TEST(JointScenes, ADroppedRagdollComesToRestWithItsJointsClosed) {
  std::vector<BodyId> bodies;
  World world = makeRagdollWorld(bodies);
  const double dt = world.settings().dt;
  double worstError = 0.0;
  int steps = 0;
  for (; steps < 8000 && world.sleepingBodyCount() < static_cast<int>(bodies.size()); ++steps) {
    world.step();
    for (int j = 0; j < world.jointCount(); ++j) worstError = std::max(worstError, world.jointStateAt(j).error);
  }
  double fastest = 0.0;
  for (const BodyId body : bodies) fastest = std::max(fastest, world.body(body).linearVelocity().norm());
  std::printf("ragdoll dropped from 1 m: asleep after %.2f s, largest joint error on the way %.1e m or rad, fastest body %.2e m/s\n",
              steps * dt, worstError, fastest);
  EXPECT_EQ(world.sleepingBodyCount(), static_cast<int>(bodies.size())) << "at rest within 8 s";
  EXPECT_LT(worstError, 1e-9);
  for (const BodyId body : bodies) EXPECT_GT(world.body(body).position().z(), 0.0) << "above the ground";
}

TEST(JointDeterminism, AJointedWorldRunTwiceIsBitIdentical) {
  World a = makeBusyJointedWorld(), b = makeBusyJointedWorld();
  for (int i = 0; i < 2000; ++i) {
    a.step();
    b.step();
    ASSERT_EQ(a.stateHash(), b.stateHash()) << "step " << i;
  }
  EXPECT_GT(a.contactPointCount(), 10) << "the ragdoll is on the ground";
}

TEST(JointDeterminism, GoldenHash) {
  World world = makeBusyJointedWorld();
  for (int i = 0; i < 2000; ++i) world.step();
  const uint64_t hash = world.stateHash();
  std::printf("golden: joints 0x%016llx\n", static_cast<unsigned long long>(hash));
  EXPECT_EQ(hash, 0x364add33e42a0f8cull);
}

}  // namespace
}  // namespace rbsim
