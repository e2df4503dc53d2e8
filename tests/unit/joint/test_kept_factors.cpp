// The joint step keeps its factor of K from the end of a step (the velocity
// projection's, at x_{n+1}) for the next step's K₀ (SHAKE and the contact
// sweeps' projection) when its inputs are bit-identical, and a group in free
// flight that moves slowly keeps one across steps while it converges
// (JointSolverSettings::keepRatio). A world restored from a snapshot (which
// holds the factors' inputs and makes them again) and a copy of a world step
// to the same bits as the original; a kept factor is made afresh when a
// whip makes it converge too slowly, and the joints stay closed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "joint/busy_jointed_world.h"
#include "physics/joint/row_system.h"

namespace rbsim {
namespace {

using testing::makeBusyJointedWorld;

// A chain of ball joints hanging from the world along −z, 20 links of
// 0.1 m and 0.1 kg, nothing to touch: one group in free flight.
World makeHangingChain() {
  WorldSettings settings = testing::jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3);
  settings.contact.enabled = false;
  World world(settings);
  BodyId previous;
  for (int k = 0; k < 20; ++k) {
    const BodyId link = testing::addBody(world, "link" + std::to_string(k), CapsuleShape{0.01, 0.04}, 0.1,
                                         Vec3(0, 0, -(k + 0.5) * 0.1), Quaternion::identity());
    JointDef ball;
    ball.name = "joint" + std::to_string(k);
    ball.type = JointType::Spherical;
    ball.bodyA = previous;
    ball.bodyB = link;
    ball.anchor = Vec3(0, 0, -k * 0.1);
    testing::addJoint(world, ball);
    previous = link;
  }
  return world;
}

double largestJointError(const World& world) {
  double worst = 0.0;
  for (int j = 0; j < world.jointCount(); ++j) worst = std::max(worst, world.jointStateAt(j).error);
  return worst;
}

// Steps `count` times; the factorisations made meanwhile, the largest joint
// error after a step.
std::uint64_t stepCounting(World& world, int count, double& worstJoint) {
  const std::uint64_t before = RowSystem::counts().factorisations;
  for (int i = 0; i < count; ++i) {
    world.step();
    worstJoint = std::max(worstJoint, largestJointError(world));
  }
  return RowSystem::counts().factorisations - before;
}

TEST(KeptFactors, ASlowGroupKeepsOneFactorAcrossStepsAndAWhipMakesItAfresh) {
  World world = makeHangingChain();
  const BodyId tip = world.idOf(19);
  ASSERT_TRUE(world.setBodyVelocities(tip, Vec3(0.01, 0, 0), Vec3::Zero()).ok());  // a slow swing
  double worst = 0.0;
  stepCounting(world, 100, worst);
  const double swingEnergy = testing::mechanicalEnergy(world);
  const std::uint64_t slow = stepCounting(world, 400, worst);
  const double swingDrift = std::abs(testing::mechanicalEnergy(world) - swingEnergy);
  // Whipped: the tip thrown sideways at 5 m/s.
  ASSERT_TRUE(world.setBodyVelocities(tip, Vec3(5, 0, 0), Vec3::Zero()).ok());
  world.step();
  const double whipEnergy = testing::mechanicalEnergy(world);
  const double whipKinetic = world.totalKineticEnergy();
  double whipWorst = 0.0;
  const std::uint64_t fast = stepCounting(world, 400, whipWorst);
  const double whipDrift = std::abs(testing::mechanicalEnergy(world) - whipEnergy);
  std::printf("hanging chain: %llu factorisations in 400 slow steps, %llu in 400 whipped ones; joint error %.1e / "
              "%.1e m; energy drift %.1e / %.1e J\n",
              static_cast<unsigned long long>(slow), static_cast<unsigned long long>(fast), worst, whipWorst,
              swingDrift, whipDrift);
  EXPECT_LT(slow, 40u) << "a slow swing keeps its factor across steps";
  EXPECT_GT(fast, 200u) << "the whip makes K afresh where the kept one converges too slowly";
  EXPECT_LT(worst, 1e-11);
  EXPECT_LT(whipWorst, 1e-11);
  // The same bands as with a factor made every step: the swing's energy
  // kept (RATTLE), the whip's to its step's accuracy.
  EXPECT_LT(swingDrift, 1e-9);
  EXPECT_LT(whipDrift, 1e-3 * whipKinetic);
}

TEST(KeptFactors, AWorldRestoredWhileItKeepsAFactorAcrossStepsStepsToTheSameBits) {
  World original = makeHangingChain();
  const BodyId tip = original.idOf(19);
  ASSERT_TRUE(original.setBodyVelocities(tip, Vec3(0.01, 0, 0), Vec3::Zero()).ok());
  double worst = 0.0;
  stepCounting(original, 200, worst);
  ASSERT_EQ(stepCounting(original, 50, worst), 0u) << "the factor is an earlier step's when the snapshot is taken";
  const Expected<std::vector<uint8_t>> bytes = original.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  Expected<World> restored = World::decodeSnapshot(*bytes, original.settings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  EXPECT_EQ(*restored->encodeSnapshot(), *bytes) << "a restored world saves to the same bytes";
  World copy = original;
  const auto stepAll = [&](int count, const char* what) {
    for (int i = 0; i < count; ++i) {
      original.step();
      restored->step();
      copy.step();
      ASSERT_EQ(restored->stateHash(), original.stateHash()) << what << ", step " << i << " after the restore";
      ASSERT_EQ(copy.stateHash(), original.stateHash()) << what << ", step " << i << " after the copy";
    }
  };
  stepAll(100, "swinging");
  for (World* world : {&original, &*restored, &copy})
    ASSERT_TRUE(world->setBodyVelocities(world->idOf(19), Vec3(5, 0, 0), Vec3::Zero()).ok());
  stepAll(200, "whipped");
}

TEST(KeptFactors, TheStepKeepsItsFactorsAndARestoredWorldStepsToTheSameBits) {
  World original = makeBusyJointedWorld();
  for (int i = 0; i < 1400; ++i) original.step();
  ASSERT_GT(original.contactPointCount(), 10) << "the ragdoll is on the ground";

  // The steps keep factors: most groups start where their last step ended.
  const RowSystemCounts before = RowSystem::counts();
  for (int i = 0; i < 100; ++i) original.step();
  const RowSystemCounts after = RowSystem::counts();
  EXPECT_GT(after.kept - before.kept, 100u) << "factors kept over 100 steps";

  const Expected<std::vector<uint8_t>> bytes = original.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  Expected<World> restored = World::decodeSnapshot(*bytes, original.settings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  World copy = original;  // keeps the solver's factors
  ASSERT_EQ(restored->stateHash(), original.stateHash());
  for (int i = 0; i < 600; ++i) {
    original.step();
    restored->step();
    copy.step();
    ASSERT_EQ(restored->stateHash(), original.stateHash()) << "step " << i << " after the restore";
    ASSERT_EQ(copy.stateHash(), original.stateHash()) << "step " << i << " after the copy";
  }
}

}  // namespace
}  // namespace rbsim
