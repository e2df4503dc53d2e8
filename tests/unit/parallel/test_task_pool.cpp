// The task pool: every task of a loop runs exactly once, on any thread
// count, loop after loop; chunks cut the same whatever the thread count.
#include <gtest/gtest.h>

#include <atomic>
#include <numeric>
#include <thread>
#include <vector>

#include "physics/parallel/task_pool.h"

namespace rbsim {
namespace {

TEST(TaskPool, RunsEveryTaskExactlyOnceOnEveryThreadCount) {
  for (const int threads : {1, 2, 3, 8}) {
    TaskPool pool(threads);
    EXPECT_EQ(pool.threadCount(), threads);
    for (const std::size_t count : {0u, 1u, 2u, 7u, 1000u}) {
      std::vector<std::atomic<int>> runs(count);
      for (int loop = 0; loop < 50; ++loop)
        pool.run(count, [&](std::size_t i) { runs[i].fetch_add(1, std::memory_order_relaxed); });
      for (std::size_t i = 0; i < count; ++i)
        ASSERT_EQ(runs[i].load(), 50) << threads << " threads, " << count << " tasks, task " << i;
    }
  }
}

TEST(TaskPool, SharesTheTasksAmongItsThreads) {
  // Tasks that wait for each other can only finish if two threads run them
  // at once: a pool that ran everything on the caller would hang here (the
  // test's timeout), one that shares them returns.
  TaskPool pool(2);
  std::atomic<int> started{0};
  pool.run(2, [&](std::size_t) {
    started.fetch_add(1);
    while (started.load() < 2) std::this_thread::yield();
  });
  EXPECT_EQ(started.load(), 2);
}

TEST(TaskPool, TheCallerTakesTasksFromTheFrontTheWorkersFromTheBack) {
  // What keeps a repeated loop's data in each core's cache: the caller's
  // tasks are a prefix of the loop, the worker's the rest.
  TaskPool pool(2);
  const std::thread::id caller = std::this_thread::get_id();
  for (int loop = 0; loop < 200; ++loop) {
    std::vector<char> byCaller(64, 0);
    pool.run(byCaller.size(), [&](std::size_t i) {
      byCaller[i] = std::this_thread::get_id() == caller ? 1 : 0;
      // Long enough for the worker to join some of the loops.
      for (volatile int spin = 0; spin < 2000; spin = spin + 1) {
      }
    });
    std::size_t prefix = 0;
    while (prefix < byCaller.size() && byCaller[prefix]) ++prefix;
    for (std::size_t i = prefix; i < byCaller.size(); ++i)
      ASSERT_EQ(byCaller[i], 0) << "loop " << loop << ": task " << i << " after the caller's prefix of " << prefix;
  }
}

TEST(TaskPool, OneThreadRunsTheTasksInOrderOnTheCaller) {
  TaskPool pool(1);
  std::vector<std::size_t> order;
  const std::thread::id caller = std::this_thread::get_id();
  bool onCaller = true;
  pool.run(5, [&](std::size_t i) {
    order.push_back(i);
    onCaller = onCaller && std::this_thread::get_id() == caller;
  });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(onCaller);
}

TEST(TaskPool, ChunksCoverTheRangeOnceAndDoNotDependOnTheThreadCount) {
  for (const int threads : {1, 2, 8}) {
    TaskPool pool(threads);
    const std::size_t count = 1003, chunkSize = 64;
    ASSERT_EQ(chunkCount(count, chunkSize), 16u);
    std::vector<std::size_t> chunkOf(count, 99);
    std::vector<std::size_t> sums(chunkCount(count, chunkSize), 0);
    forEachChunk(pool, count, chunkSize, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        chunkOf[i] = chunk;
        sums[chunk] += i;
      }
    });
    for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(chunkOf[i], i / chunkSize) << "item " << i;
    EXPECT_EQ(std::accumulate(sums.begin(), sums.end(), std::size_t{0}), count * (count - 1) / 2);
  }
}

TEST(TaskPool, AnOwnPoolIsNeverShared) {
  OwnTaskPool first;
  TaskPool& pool = first.get(2);
  EXPECT_EQ(pool.threadCount(), 2);
  EXPECT_EQ(&first.get(2), &pool) << "kept while the count stays";
  OwnTaskPool copy = first;
  EXPECT_NE(&copy.get(2), &pool) << "a copy makes its own";
  EXPECT_EQ(first.get(3).threadCount(), 3) << "remade for a new count";
  EXPECT_GE(first.get(0).threadCount(), 1) << "0: one per core";
  EXPECT_EQ(resolveThreadCount(5), 5);
  EXPECT_GE(resolveThreadCount(0), 1);
}

}  // namespace
}  // namespace rbsim
