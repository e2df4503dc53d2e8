// The joint step keeps its factor of K from the end of a step (the velocity
// projection's, at x_{n+1}) for the next step's K₀ (SHAKE and the contact
// sweeps' projection), only when its inputs are bit-identical: so a world
// restored from a snapshot, which stores no factor and makes each afresh,
// steps to the same bits as the world it was saved from, and a copy of a
// world to the same bits as the original.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "joint/busy_jointed_world.h"
#include "physics/joint/row_system.h"

namespace rbsim {
namespace {

using testing::makeBusyJointedWorld;

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
