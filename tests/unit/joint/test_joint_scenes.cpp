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

}  // namespace
}  // namespace rbsim
