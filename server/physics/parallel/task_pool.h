#pragma once
// A fixed set of worker threads that run the tasks of one parallel loop at
// a time: the world's step hands them its per-pair, per-contact and
// per-body work (world.threads).
//
// Determinism is the callers' part, by construction: a loop is cut into
// tasks whose number and bounds do not depend on the thread count
// (forEachChunk), each task writes only what its index owns, and results
// that must be combined (a sum, a maximum, a list) are kept per task and
// combined afterwards in task order. Which thread runs which task then does
// not matter: 1, 2 or 8 threads give the same bits. (Threads that change
// results are a known complaint about other engines, mujoco#1093.)
//
// The threads are made once, with the pool. A loop costs no allocation and
// takes no lock: tasks are claimed from an atomic pair of counters, and the
// threads wait between loops on an atomic (a futex on Linux) after a short
// spin and a stretch of yields (task_pool.cpp says how long, and why).
//
// The caller claims tasks from the front of the loop, the workers from its
// back, until they meet. A loop that is run again (a solver sweep, the next
// step's integration) then gives each thread mostly the same tasks as the
// last time, whose data is still in its core's cache: claimed one by one
// from a shared counter, every task would go to either thread by chance,
// and its data (a contact's rows, a body) would cross between the cores at
// every sweep, which cost more than the second thread gained.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include "rbsim/physics/thread_settings.h"

namespace rbsim {

// Whether the pool may run loops on the caller alone while its workers do
// not help (TaskPool::kLeastWorkerShare below says when).
enum class LoopSharing {
  // Loops run on the caller alone for a while when the workers ran too few
  // of the last ones' tasks: the default.
  Adaptive,
  // Every loop is offered to the workers. For ThreadSanitizer runs: a loop
  // that runs on the caller alone has no race to find, and TSan slows the
  // caller down, so the workers' share would often be too small and the
  // rule would hide the very races the run looks for.
  Always,
};

// RBSIM_POOL_ALWAYS_SHARE=1 in the environment: Always; =0: Adaptive.
// Unset: Always in a ThreadSanitizer build (so that a TSan binary run by
// hand checks what scripts/run_tests.sh's phase checks), else Adaptive.
LoopSharing loopSharingFromEnvironment();

class TaskPool {
 public:
  // threads >= 1: threads − 1 workers are started; the caller of run() is
  // the last thread. 1 runs every loop on the caller, as a plain loop.
  explicit TaskPool(int threads, LoopSharing sharing = loopSharingFromEnvironment());
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;
  ~TaskPool();

  int threadCount() const { return static_cast<int>(m_workers.size()) + 1; }
  LoopSharing sharing() const { return m_sharing; }

  // When the workers ran less than 1/kLeastWorkerShare of the tasks of the
  // last kWindowLoops loops, the next kSoloLoops loops run on the caller
  // alone, then the pool tries again. Workers that come too late to help
  // (a world too small to gain: its loops are done before they join) or
  // that share a core with the caller or with another process (a busy
  // machine) cost the caller more than they save; left without loops they
  // go to sleep, and the caller keeps a core to itself. Which thread runs a
  // task never changes a result, so neither does this. Loops of one task
  // (run on the caller in any case) do not count.
  static constexpr uint32_t kWindowLoops = 256;
  static constexpr uint64_t kLeastWorkerShare = 8;
  static constexpr uint32_t kSoloLoops = 4096;
  // Whether the next loop will run on the caller alone (the rule above is
  // engaged). Read by the caller of run() only; for tests and diagnostics.
  bool runsOnCallerAlone() const { return m_soloLoopsLeft > 0; }

  // Calls task(i) once for every i in [0, count) and returns when all have
  // returned. Tasks run concurrently on any of the threads, in any order:
  // each must write only what belongs to its index. Tasks must not throw,
  // and must not call run() on the same pool.
  template <class Task>
  void run(std::size_t count, Task&& task) {
    if (count == 0) return;
    if (m_workers.empty() || count == 1 || count > kMaxTasks) {
      for (std::size_t i = 0; i < count; ++i) task(i);
      return;
    }
    runErased(count, &callTask<Task>, &task);
  }

 private:
  static constexpr std::size_t kMaxTasks = 0xffffffffu;  // what m_unclaimed holds; more run on the caller
  using TaskCall = void (*)(void* task, std::size_t index);
  template <class Task>
  static void callTask(void* task, std::size_t index) {
    (*static_cast<Task*>(task))(index);
  }

  void runErased(std::size_t count, TaskCall call, void* task);
  // Runs one loop shared with the workers; returns how many of its tasks
  // the caller ran.
  std::size_t shareLoop(std::size_t count, TaskCall call, void* task);
  void workerLoop();
  // Claims and runs tasks of the current loop until none is left: from the
  // front (the caller) or from the back (the workers). Returns how many.
  std::size_t runClaimedTasks(bool fromFront);

  std::vector<std::thread> m_workers;
  LoopSharing m_sharing;
  // The rule's counts (kWindowLoops above): the caller's alone.
  uint32_t m_windowLoops = 0;
  uint64_t m_windowTasks = 0;
  uint64_t m_windowWorkerTasks = 0;
  uint32_t m_soloLoopsLeft = 0;
  // The current loop. Written by run() only while no worker is inside a
  // loop; a worker reads them after it has joined the open loop (acquire).
  TaskCall m_call = nullptr;
  void* m_task = nullptr;
  // The unclaimed tasks [front, back) of the current loop: front in the low
  // 32 bits, back in the high 32 (one atomic, so that a claim from either
  // end sees the other's).
  std::atomic<uint64_t> m_unclaimed{0};
  // kOpen while the caller is in the loop, plus the number of workers
  // inside it. A worker joins only while it is open, so the caller waits
  // for the workers that came in time, never for one still asleep or
  // descheduled (on a busy machine a worker may wake milliseconds late: it
  // then finds the loop closed and goes back to waiting).
  static constexpr uint32_t kOpen = 1u << 31;
  std::atomic<uint32_t> m_loop{0};
  std::atomic<uint32_t> m_generation{0};  // bumped for each loop, and to stop: what workers wait on
  // Atomic: a worker that woke late for an earlier loop may read it while
  // the destructor sets it.
  std::atomic<bool> m_stopping{false};
};

// How many chunks of chunkSize items cover count items.
inline std::size_t chunkCount(std::size_t count, std::size_t chunkSize) {
  return (count + chunkSize - 1) / chunkSize;
}

// Runs body(chunk, begin, end) over [0, count) cut into chunks of
// chunkSize items: chunk k covers [k chunkSize, min((k + 1) chunkSize,
// count)). The cut depends only on count and chunkSize, never on the thread
// count, so per-chunk results combined in chunk order are deterministic.
template <class Body>
void forEachChunk(TaskPool& pool, std::size_t count, std::size_t chunkSize, Body&& body) {
  const std::size_t chunks = chunkCount(count, chunkSize);
  pool.run(chunks, [&](std::size_t chunk) {
    const std::size_t begin = chunk * chunkSize;
    const std::size_t end = begin + chunkSize < count ? begin + chunkSize : count;
    body(chunk, begin, end);
  });
}

// resolveThreadCount: rbsim/physics/thread_settings.h.

// The pool of an object that may be copied (a world is, for checkpoints):
// made when first asked for, remade when the thread count changes, and
// never shared. A copy starts without one and makes its own when it first
// needs it, so two copies can step on different threads at once.
class OwnTaskPool {
 public:
  OwnTaskPool() = default;
  OwnTaskPool(const OwnTaskPool&) {}
  OwnTaskPool& operator=(const OwnTaskPool&) { return *this; }
  OwnTaskPool(OwnTaskPool&&) noexcept = default;
  OwnTaskPool& operator=(OwnTaskPool&&) noexcept = default;
  ~OwnTaskPool() = default;

  // requested: a thread count, or 0 for one per core (resolveThreadCount,
  // asked once, when the pool is made).
  TaskPool& get(int requested) {
    if (!m_pool || requested != m_requested) {
      m_pool.reset();  // its threads end before the new ones start
      m_pool = std::make_unique<TaskPool>(resolveThreadCount(requested));
      m_requested = requested;
    }
    return *m_pool;
  }

 private:
  std::unique_ptr<TaskPool> m_pool;
  int m_requested = 0;
};


}  // namespace rbsim
