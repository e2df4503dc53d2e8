// The contact solver's sweep batches: every constraint once, no two of a
// batch on one moving body, static bodies shared freely, stages in order,
// and the overflow of a body in more than 64 contacts kept in order.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "physics/solver/sweep_batches.h"

namespace rbsim {
namespace {

// Fails unless `batches` holds each of the constraints once and no
// parallel batch has two constraints on one moving body.
void expectValidBatches(const std::vector<ConstraintBodies>& constraints, const std::vector<char>& moves,
                        const SweepBatches& batches) {
  ASSERT_EQ(batches.order.size(), constraints.size());
  ASSERT_EQ(static_cast<std::size_t>(batches.batchCount()), batches.inOrder.size());
  EXPECT_EQ(std::set<int>(batches.order.begin(), batches.order.end()).size(), constraints.size());
  for (int b = 0; b < batches.batchCount(); ++b) {
    EXPECT_FALSE(batches.batch(b).empty()) << "batch " << b;
    if (batches.inOrder[static_cast<std::size_t>(b)]) continue;
    std::set<int> bodies;
    for (const int m : batches.batch(b)) {
      for (const int body : {constraints[static_cast<std::size_t>(m)].bodyA,
                             constraints[static_cast<std::size_t>(m)].bodyB}) {
        if (!moves[static_cast<std::size_t>(body)]) continue;
        EXPECT_TRUE(bodies.insert(body).second) << "batch " << b << " touches body " << body << " twice";
      }
    }
  }
}

TEST(SweepBatches, AStackOnTheGroundAlternatesAndSharesTheGround) {
  // Body 0 is the ground; 1..10 a tower: contacts (0,1), (1,2), ... (9,10),
  // and a second tower 11..20 on the same ground.
  std::vector<ConstraintBodies> constraints;
  for (int tower : {0, 10})
    for (int k = 0; k < 10; ++k) constraints.push_back({k == 0 ? 0 : tower + k, tower + k + 1});
  std::vector<char> moves(21, 1);
  moves[0] = 0;
  SweepBatcher batcher;
  SweepBatches batches;
  batcher.build(constraints, moves, {}, batches);
  expectValidBatches(constraints, moves, batches);
  // A chain needs two colours, whatever the ground does: both towers' feet
  // share the first.
  ASSERT_EQ(batches.batchCount(), 2);
  EXPECT_EQ(batches.batch(0).size(), 10u);
  EXPECT_EQ(batches.batch(0)[0], 0);
  EXPECT_EQ(batches.batch(0)[5], 10) << "the second tower's foot, on the shared ground";
}

TEST(SweepBatches, StagesComeInOrderEachColouredAlone) {
  std::vector<ConstraintBodies> constraints = {{1, 2}, {0, 1}, {2, 3}, {0, 4}, {4, 2}};
  const std::vector<int> stage = {1, 0, 2, 0, 1};
  std::vector<char> moves = {0, 1, 1, 1, 1};
  SweepBatcher batcher;
  SweepBatches batches;
  batcher.build(constraints, moves, stage, batches);
  expectValidBatches(constraints, moves, batches);
  // Stage 0: (0,1) and (0,4) share only the ground: one batch. Stage 1:
  // (1,2) and (4,2) share body 2: two batches. Stage 2: one.
  ASSERT_EQ(batches.batchCount(), 4);
  EXPECT_EQ(std::vector<int>(batches.batch(0).begin(), batches.batch(0).end()), (std::vector<int>{1, 3}));
  EXPECT_EQ(std::vector<int>(batches.batch(1).begin(), batches.batch(1).end()), std::vector<int>{0});
  EXPECT_EQ(std::vector<int>(batches.batch(2).begin(), batches.batch(2).end()), std::vector<int>{4});
  EXPECT_EQ(std::vector<int>(batches.batch(3).begin(), batches.batch(3).end()), std::vector<int>{2});
}

TEST(SweepBatches, ABodyInMoreThan64ContactsOverflowsIntoAnOrderedBatch) {
  // A hub touched by 70 spokes: 64 colours, then 6 constraints that must be
  // solved one after the other, in their own order.
  std::vector<ConstraintBodies> constraints;
  for (int k = 0; k < 70; ++k) constraints.push_back({0, k + 1});
  const std::vector<char> moves(71, 1);
  SweepBatcher batcher;
  SweepBatches batches;
  batcher.build(constraints, moves, {}, batches);
  expectValidBatches(constraints, moves, batches);
  ASSERT_EQ(batches.batchCount(), 65);
  EXPECT_TRUE(batches.inOrder[64]);
  EXPECT_EQ(std::vector<int>(batches.batch(64).begin(), batches.batch(64).end()),
            (std::vector<int>{64, 65, 66, 67, 68, 69}));
}

}  // namespace
}  // namespace rbsim
