// The joint step makes no heap allocation in a steady scene (issue 39): its
// workspaces (the groups' rows, factors, orderings, the contact sweeps'
// projection) are kept by the world from step to step and only grow. The
// one exception is the position projection's Newton fallback, taken in a
// step whose start's rows converge too slowly: Eigen's sparse LU allocates
// at every factorisation, and it is counted apart (StepPart::JointNewton).
// Counted by tests/support/allocation_counter.h, which replaces malloc in
// this executable and tells the joint code's allocations (its scopes,
// physics/common/step_part.h) from the rest's. The scenes are
// bench/joints's, built by its rbsim_scene_world.h as its benchmark builds them.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "joint_scenes.h"
#include "rbsim_scene_world.h"
#include "physics/common/step_part.h"
#include "rbsim/physics/world.h"
#include "support/allocation_counter.h"

namespace rbsim {
namespace {

namespace jb = bench::joints;
using testing::AllocationCounts;
using testing::AllocationScope;

// The benchmark's world for the scene (bench/joints/rbsim_scene_world.h),
// stepped on one thread: every allocation of the step on this thread.
World makeSceneWorld(const std::string& name, int n) {
  jb::Scene s;
  EXPECT_TRUE(jb::makeScene(name, n, s));
  WorldSettings settings = jb::sceneWorldSettings(s);
  settings.threads = 1;
  World world(settings);
  if (s.ground) EXPECT_TRUE(world.createBody(jb::sceneGround()).ok());
  std::vector<BodyId> bodies;
  for (const jb::BodySpec& b : s.bodies) {
    const Expected<BodyId> id = world.createBody(jb::sceneBody(b, bodies.size()));
    EXPECT_TRUE(id.ok());
    bodies.push_back(id.ok() ? id.value() : BodyId{});
  }
  int count = 0;
  for (const jb::JointSpec& j : s.joints) EXPECT_TRUE(world.createJoint(jb::sceneJoint(j, bodies, count++)).ok());
  return world;
}

struct Counted {
  AllocationCounts sum;
  std::uint64_t worstJoints = 0;  // in one step
  int stepsWithJointAllocations = 0;
  int stepsWithNewton = 0;
};

// `warmUp` steps (the ragdolls land on the pile after about 450), then `steps` counted ones.
Counted countSteps(World& world, int warmUp, int steps) {
  for (int i = 0; i < warmUp; ++i) world.step();
  Counted out;
  testing::traceJointAllocations(true);  // (gdb: break rbsim_joint_allocation)
  for (int i = 0; i < steps; ++i) {
    const AllocationScope scope;
    world.step();
    const AllocationCounts c = scope.counts();
    out.sum.total += c.total;
    out.sum.joints += c.joints;
    out.sum.jointNewton += c.jointNewton;
    out.stepsWithNewton += c.jointNewton > 0 ? 1 : 0;
    out.worstJoints = std::max(out.worstJoints, c.joints);
    out.stepsWithJointAllocations += c.joints > 0 ? 1 : 0;
  }
  testing::traceJointAllocations(false);
  return out;
}

void expectNoJointAllocations(const std::string& scene, int n, int warmUp, int steps) {
  if (!testing::allocationCountingWorks()) GTEST_SKIP() << "malloc is not counted here (a sanitizer's own)";
  World world = makeSceneWorld(scene, n);
  const Counted c = countSteps(world, warmUp, steps);
  std::printf("%s %d, steps %d to %d: %.2f allocations per step in all, %.2f in joint code (%d steps with some, at "
              "most %llu); %.2f in the Newton fallback's sparse LU (%d steps took it)\n",
              scene.c_str(), n, warmUp, warmUp + steps, static_cast<double>(c.sum.total) / steps,
              static_cast<double>(c.sum.joints) / steps, c.stepsWithJointAllocations,
              static_cast<unsigned long long>(c.worstJoints), static_cast<double>(c.sum.jointNewton) / steps,
              c.stepsWithNewton);
  EXPECT_EQ(c.sum.joints, 0u) << "joint code allocated in " << c.stepsWithJointAllocations << " of " << steps
                              << " steady steps";
}

TEST(JointAllocations, TheCounterSeesAllocationsAndTheirPart) {
  if (!testing::allocationCountingWorks()) GTEST_SKIP() << "malloc is not counted here (a sanitizer's own)";
  const AllocationScope scope;
  std::vector<double> v(100);
  v.resize(1000);  // a second allocation: the first buffer is too small
  EXPECT_EQ(scope.counts().total, 2u) << v[999];
  EXPECT_EQ(scope.counts().joints, 0u);
  {
    const StepPartScope part(StepPart::Joints);
    v.resize(5000);
  }
  EXPECT_EQ(scope.counts().total, 3u) << v[4999];
  EXPECT_EQ(scope.counts().joints, 1u);
}

TEST(JointAllocations, NoneInJointCodeInASteadyPileOfRagdolls) { expectNoJointAllocations("ragdolls", 20, 1000, 200); }

TEST(JointAllocations, NoneInJointCodeInASwingingChain) { expectNoJointAllocations("chain", 100, 300, 300); }

}  // namespace
}  // namespace rbsim
