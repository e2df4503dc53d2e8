// The task pool: every task of a loop runs exactly once, on any thread
// count, loop after loop; chunks cut the same whatever the thread count.
#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <time.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "physics/parallel/task_pool.h"
#include "physics/parallel/thread_sanitizer.h"

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
      std::atomic<int> spin{0};
      while (spin.fetch_add(1, std::memory_order_relaxed) < 2000) {
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

// A worker that cannot help, deterministically: held in a signal handler
// until the test lets it go, so it joins no loop however long the loops
// are, while the pool's code stays as it is. The signal is sent to the
// worker's own thread (found by a loop of two tasks that wait for each
// other, one of which must run on the worker).
// Not under ThreadSanitizer: it defers a signal until its thread calls an
// intercepted function, and a worker asleep in the futex call of
// std::atomic::wait may never make one.
#define SKIP_UNDER_THREAD_SANITIZER() \
  if (kThreadSanitizer) GTEST_SKIP() << "holds a worker with a signal, which ThreadSanitizer may defer"

std::atomic<bool> g_workerHeld{false};
std::atomic<bool> g_releaseWorker{false};
static_assert(std::atomic<bool>::is_always_lock_free, "used in a signal handler");

extern "C" void holdWorker(int) {
  g_workerHeld.store(true);
  const timespec pause{0, 100000};  // 0.1 ms; nanosleep is async-signal-safe
  while (!g_releaseWorker.load()) nanosleep(&pause, nullptr);
}

class HeldWorker {
 public:
  explicit HeldWorker(TaskPool& pool) {
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<int> started{0};
    pthread_t worker{};
    pool.run(2, [&](std::size_t) {
      if (std::this_thread::get_id() != caller) worker = pthread_self();
      started.fetch_add(1);
      while (started.load() < 2) std::this_thread::yield();
    });
    g_workerHeld.store(false);
    g_releaseWorker.store(false);
    struct sigaction action {};
    action.sa_handler = holdWorker;
    sigemptyset(&action.sa_mask);
    sigaction(SIGUSR1, &action, &m_previous);
    pthread_kill(worker, SIGUSR1);
    while (!g_workerHeld.load()) std::this_thread::yield();
  }
  HeldWorker(const HeldWorker&) = delete;
  HeldWorker& operator=(const HeldWorker&) = delete;
  ~HeldWorker() { release(); }

  void release() {
    if (m_released) return;
    m_released = true;
    g_releaseWorker.store(true);
    sigaction(SIGUSR1, &m_previous, nullptr);  // a handler already running ends as it began
  }

 private:
  struct sigaction m_previous {};
  bool m_released = false;
};

// Runs a loop of `count` tasks that wait for nothing; returns whether they
// all ran on the caller.
bool runOnCallerOnly(TaskPool& pool, std::size_t count) {
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> onCaller{true};
  pool.run(count, [&](std::size_t) {
    if (std::this_thread::get_id() != caller) onCaller.store(false);
  });
  return onCaller.load();
}

// A loop that two threads must run together (each of its two tasks waits
// for the other): a worker runs one of its two tasks, or it never returns
// (the test's timeout).
void runWithTheWorker(TaskPool& pool) {
  std::atomic<int> started{0};
  pool.run(2, [&](std::size_t) {
    started.fetch_add(1);
    while (started.load() < 2) std::this_thread::yield();
  });
}

TEST(TaskPool, RunsLoopsOnTheCallerAloneWhileTheWorkersCannotHelpThenTriesAgain) {
  SKIP_UNDER_THREAD_SANITIZER();
  TaskPool pool(2, LoopSharing::Adaptive);
  HeldWorker held(pool);
  // Loops the held worker cannot join: one window, at most two (the first
  // may have begun with the loop that found the worker), and the rule
  // engages.
  uint32_t loops = 0;
  while (!pool.runsOnCallerAlone() && loops < 2 * TaskPool::kWindowLoops) {
    ASSERT_TRUE(runOnCallerOnly(pool, 8));
    ++loops;
  }
  ASSERT_TRUE(pool.runsOnCallerAlone()) << "still sharing after " << loops << " loops the worker could not join";
  EXPECT_GE(loops, TaskPool::kWindowLoops - 1);
  // Released, the worker is not offered the next kSoloLoops loops: all run
  // on the caller, however long (these wait long enough for a worker
  // spinning between loops to join, were they offered).
  held.release();
  for (uint32_t loop = 0; loop < TaskPool::kSoloLoops; ++loop) {
    ASSERT_TRUE(pool.runsOnCallerAlone()) << "solo loop " << loop;
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<bool> onCaller{true};
    pool.run(2, [&](std::size_t) {
      if (std::this_thread::get_id() != caller) onCaller.store(false);
      if (loop % 512 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
    });
    ASSERT_TRUE(onCaller.load()) << "solo loop " << loop << " ran a task on a worker";
  }
  // Then the pool tries again; a worker that helps (half of every loop's
  // tasks) keeps it sharing, window after window.
  ASSERT_FALSE(pool.runsOnCallerAlone()) << "still solo after " << TaskPool::kSoloLoops << " loops";
  for (uint32_t loop = 0; loop < 3 * TaskPool::kWindowLoops; ++loop) {
    runWithTheWorker(pool);
    ASSERT_FALSE(pool.runsOnCallerAlone()) << "solo again after " << loop << " loops the worker shared";
  }
}

TEST(TaskPool, AWorkerThatRunsAnEighthOfTheTasksKeepsTheLoopsShared) {
  // Each loop: the worker runs one of 8 tasks, the least share that pays
  // (1/kLeastWorkerShare), for three windows.
  static_assert(TaskPool::kLeastWorkerShare == 8, "the loops below give the worker 1 task of 8");
  TaskPool pool(2, LoopSharing::Adaptive);
  const std::thread::id caller = std::this_thread::get_id();
  for (uint32_t loop = 0; loop < 3 * TaskPool::kWindowLoops; ++loop) {
    std::atomic<int> byWorker{0};
    std::atomic<int> byCaller{0};
    // The worker takes task 7 (from the back) and holds it until the
    // caller has run tasks 0-6; the caller's task 0 waits until the worker
    // has taken its one.
    pool.run(8, [&](std::size_t i) {
      if (std::this_thread::get_id() != caller) {
        byWorker.fetch_add(1);
        while (byCaller.load() < 7) std::this_thread::yield();
        return;
      }
      if (i == 0)
        while (byWorker.load() == 0) std::this_thread::yield();
      byCaller.fetch_add(1);
    });
    ASSERT_EQ(byWorker.load(), 1) << "loop " << loop;
    ASSERT_FALSE(pool.runsOnCallerAlone()) << "solo after " << loop << " loops with 1/8 on the worker";
  }
}

TEST(TaskPool, AlwaysSharingNeverRunsLoopsOnTheCallerAlone) {
  // The switch for ThreadSanitizer runs: a worker that cannot help does not
  // take the loops away from the workers.
  SKIP_UNDER_THREAD_SANITIZER();
  TaskPool pool(2, LoopSharing::Always);
  EXPECT_EQ(pool.sharing(), LoopSharing::Always);
  {
    HeldWorker held(pool);
    for (uint32_t loop = 0; loop < 3 * TaskPool::kWindowLoops; ++loop) {
      ASSERT_TRUE(runOnCallerOnly(pool, 8));
      ASSERT_FALSE(pool.runsOnCallerAlone()) << "loop " << loop;
    }
  }
  runWithTheWorker(pool);  // and the worker still joins, once released
}

TEST(TaskPool, LoopSharingComesFromTheEnvironment) {
  // RBSIM_POOL_ALWAYS_SHARE: 1 keeps every loop shared, 0 lets the pool
  // run loops on the caller alone; the ThreadSanitizer phase of
  // scripts/run_tests.sh sets 1. (No pool's thread runs while this test
  // changes the environment.)
  const char* before = std::getenv("RBSIM_POOL_ALWAYS_SHARE");
  const std::optional<std::string> saved = before ? std::optional<std::string>(before) : std::nullopt;
  setenv("RBSIM_POOL_ALWAYS_SHARE", "1", 1);
  EXPECT_EQ(loopSharingFromEnvironment(), LoopSharing::Always);
  EXPECT_EQ(TaskPool(2).sharing(), LoopSharing::Always);
  setenv("RBSIM_POOL_ALWAYS_SHARE", "0", 1);
  EXPECT_EQ(loopSharingFromEnvironment(), LoopSharing::Adaptive);
  EXPECT_EQ(TaskPool(2).sharing(), LoopSharing::Adaptive);
  unsetenv("RBSIM_POOL_ALWAYS_SHARE");
  EXPECT_EQ(loopSharingFromEnvironment(), kThreadSanitizer ? LoopSharing::Always : LoopSharing::Adaptive)
      << "unset: always shared in a ThreadSanitizer build only";
  if (saved) setenv("RBSIM_POOL_ALWAYS_SHARE", saved->c_str(), 1);
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
