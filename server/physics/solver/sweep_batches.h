#pragma once
// The order of a Gauss–Seidel sweep over the contacts that threads can
// share: the constraints cut into batches in which no two touch the same
// moving body (a graph colouring of the contact graph, as Box2D v3 and
// PhysX colour theirs). Within a batch no constraint sees another's
// impulse, so its constraints may be solved in any order, on any thread,
// with the same result; batches follow each other, each seeing all before.
//
// The colouring is greedy in the constraints' own order (sorted by bodies'
// serials, so it depends on the world alone): each takes the lowest colour
// that neither of its moving bodies has taken yet. Static bodies (zero
// inverse mass) join no colour: every contact on the ground may share one.
// Constraints that find none of the 64 colours free (a body in more than
// 64 contacts) go to a last batch that is solved in order on one thread.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/parallel/task_pool.h"

namespace rbsim {

struct SweepBatches {
  std::vector<int> order;       // constraint indices, batch after batch
  std::vector<int> batchStart;  // batch b: order[batchStart[b]] .. order[batchStart[b + 1] − 1]
  std::vector<char> inOrder;    // per batch: 1 when its constraints share bodies (the overflow batch)

  int batchCount() const { return static_cast<int>(batchStart.size()) - 1; }
  std::span<const int> batch(int b) const {
    return {order.data() + batchStart[static_cast<std::size_t>(b)],
            static_cast<std::size_t>(batchStart[static_cast<std::size_t>(b) + 1] -
                                     batchStart[static_cast<std::size_t>(b)])};
  }
};

// The bodies of one constraint (dense indices).
struct ConstraintBodies {
  int bodyA = 0;
  int bodyB = 0;
};

class SweepBatcher {
 public:
  // Batches of `constraints` (moves[i]: body i moves). With `stage` (one
  // entry per constraint; empty: all in one stage) the constraints are first
  // ordered by stage, ascending, and each stage is coloured on its own, its
  // batches after those of the stages below: a sweep that must pass from
  // stage to stage in order (the shock sweep, level by level upwards).
  void build(std::span<const ConstraintBodies> constraints, std::span<const char> moves,
             std::span<const int> stage, SweepBatches& out);

 private:
  std::vector<uint64_t> m_coloursTaken;  // per body: the colours of its constraints in this stage
  std::vector<int> m_colourOf;           // per constraint of the stage: its colour, or −1 (overflow)
  std::vector<int> m_byStage;            // constraint indices ordered by stage
  std::vector<int> m_colourCount;        // constraints per colour in the stage
  std::vector<int> m_colourStart;        // scratch of the counting sort
};

// Calls solve(m) for every constraint m of `batches`, batch after batch,
// each batch shared among the pool's threads (the result is the same for
// every thread count: see above).
template <class Solve>
void sweepInBatches(const SweepBatches& batches, TaskPool& pool, Solve&& solve) {
  // A batch smaller than this is solved on the calling thread: sharing it
  // would cost more than it saves.
  constexpr std::size_t kSmallestShared = 48;
  constexpr std::size_t kConstraintsPerTask = 16;
  for (int b = 0; b < batches.batchCount(); ++b) {
    const std::span<const int> batch = batches.batch(b);
    if (batches.inOrder[static_cast<std::size_t>(b)] || batch.size() < kSmallestShared ||
        pool.threadCount() == 1) {
      for (const int m : batch) solve(static_cast<std::size_t>(m));
      continue;
    }
    forEachChunk(pool, batch.size(), kConstraintsPerTask, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) solve(static_cast<std::size_t>(batch[k]));
    });
  }
}

}  // namespace rbsim
