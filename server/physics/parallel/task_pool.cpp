#include "physics/parallel/task_pool.h"

#include <sched.h>

#include <algorithm>

namespace rbsim {

namespace {

// Waits until `changed()` holds: spins first, since a step's parallel
// loops follow each other within microseconds and a futex wake costs about
// as much as a small loop; then yields the core between looks, so that on
// more threads than cores the thread with work to do gets it; then sleeps on
// the atomic (a futex), so that a worker between steps (the pacing thread
// sleeps there) gives its core back. `sleep(value)` blocks while the atomic
// still holds `value`.
constexpr int kPauses = 64;
constexpr int kYields = 200;

template <class Changed, class Sleep>
void waitUntil(Changed&& changed, Sleep&& sleep) {
  for (int i = 0; i < kPauses; ++i) {
    if (changed()) return;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  for (int i = 0; i < kYields; ++i) {
    if (changed()) return;
    sched_yield();
  }
  while (!changed()) sleep();
}

}  // namespace

int resolveThreadCount(int threads) {
  if (threads > 0) return threads;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

TaskPool::TaskPool(int threads) {
  const int workers = std::max(1, threads) - 1;
  m_workers.reserve(static_cast<std::size_t>(workers));
  for (int i = 0; i < workers; ++i) m_workers.emplace_back([this] { workerLoop(); });
}

TaskPool::~TaskPool() {
  m_stopping.store(true, std::memory_order_release);
  m_generation.fetch_add(1, std::memory_order_release);
  m_generation.notify_all();
  for (std::thread& worker : m_workers) worker.join();
}

void TaskPool::runErased(std::size_t count, TaskCall call, void* task) {
  m_call = call;
  m_task = task;
  m_count = count;
  m_next.store(0, std::memory_order_relaxed);
  m_loop.store(kOpen, std::memory_order_release);  // publishes the loop to joiners
  m_generation.fetch_add(1, std::memory_order_release);
  m_generation.notify_all();
  runClaimedTasks();
  // Every task is claimed: close the loop, then wait for the workers that
  // joined it to finish theirs (and their reads of m_call and m_task),
  // before the next loop may overwrite them.
  if (m_loop.fetch_and(~kOpen, std::memory_order_acq_rel) == kOpen) return;  // nobody joined
  waitUntil([&] { return m_loop.load(std::memory_order_acquire) == 0; },
            [&] {
              const uint32_t inside = m_loop.load(std::memory_order_acquire);
              if (inside != 0) m_loop.wait(inside, std::memory_order_acquire);
            });
}

void TaskPool::runClaimedTasks() {
  for (std::size_t i = m_next.fetch_add(1, std::memory_order_relaxed); i < m_count;
       i = m_next.fetch_add(1, std::memory_order_relaxed))
    m_call(m_task, i);
}

void TaskPool::workerLoop() {
  uint32_t seen = 0;
  for (;;) {
    waitUntil([&] { return m_generation.load(std::memory_order_acquire) != seen; },
              [&] { m_generation.wait(seen, std::memory_order_acquire); });
    seen = m_generation.load(std::memory_order_acquire);
    if (m_stopping.load(std::memory_order_acquire)) return;
    // Join the loop if it is still open; a closed one is done without us.
    uint32_t loop = m_loop.load(std::memory_order_acquire);
    bool joined = false;
    while ((loop & kOpen) != 0 && !joined)
      joined = m_loop.compare_exchange_weak(loop, loop + 1, std::memory_order_acq_rel,
                                            std::memory_order_acquire);
    if (!joined) continue;
    runClaimedTasks();
    // The last worker out of a closed loop wakes the caller, which may be
    // asleep on it.
    if (m_loop.fetch_sub(1, std::memory_order_acq_rel) == 1) m_loop.notify_one();
  }
}

}  // namespace rbsim
