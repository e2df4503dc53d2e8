#include "physics/parallel/task_pool.h"
#include "physics/parallel/thread_sanitizer.h"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>

namespace rbsim {

namespace {

// Waits until `changed()` holds: spins first, briefly (a pause is 25 ns
// here); then yields the core between looks, so that a thread with work to
// do on the same core (on more threads than cores, or when another process
// holds the other core and the scheduler put both threads on one) gets it;
// a yield costs 0.6 us when nothing else wants the core, so a thread alone
// on its core still sees a change within a microsecond; then sleeps on the
// atomic (a futex), so that a worker between steps (the pacing thread sleeps
// there) gives its core back. `sleep(value)` blocks while the atomic still
// holds `value`.
// A worker waiting for the next loop yields long enough to cover the serial
// stretches of a step (the broad phase, the colouring of the contacts, the
// islands): measured on the pile of 1000, 200 yields (120 us) left it asleep
// 2-3 times a step, and waking a thread asleep on a futex costs 28 us here
// (a virtual machine's idle core) against under 1 us yielding.
constexpr std::chrono::microseconds kSpin{2};
constexpr std::chrono::microseconds kWorkerYielding{300};
constexpr std::chrono::microseconds kCallerYielding{120};

template <class Changed, class Sleep>
void waitUntil(std::chrono::microseconds yielding, Changed&& changed, Sleep&& sleep) {
  const auto start = std::chrono::steady_clock::now();
  do {
    for (int i = 0; i < 16; ++i) {
      if (changed()) return;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
  } while (std::chrono::steady_clock::now() - start < kSpin);
  do {
    if (changed()) return;
    sched_yield();
  } while (std::chrono::steady_clock::now() - start < kSpin + yielding);
  while (!changed()) sleep();
}


// m_unclaimed: [front, back) packed in one word.
constexpr uint64_t packUnclaimed(uint64_t front, uint64_t back) { return front | (back << 32); }

}  // namespace

int resolveThreadCount(int threads) {
  if (threads > 0) return threads;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

LoopSharing loopSharingFromEnvironment() {
  const char* text = std::getenv("RBSIM_POOL_ALWAYS_SHARE");
  if (text && text[0] != '\0') return std::strcmp(text, "0") == 0 ? LoopSharing::Adaptive : LoopSharing::Always;
  return kThreadSanitizer ? LoopSharing::Always : LoopSharing::Adaptive;
}

TaskPool::TaskPool(int threads, LoopSharing sharing) : m_sharing(sharing) {
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
  if (m_soloLoopsLeft > 0) {
    --m_soloLoopsLeft;
    for (std::size_t i = 0; i < count; ++i) call(task, i);
    return;
  }
  const std::size_t byCaller = shareLoop(count, call, task);
  if (m_sharing == LoopSharing::Always) return;
  // The workers' share of the window's tasks decides whether the next
  // loops are shared at all.
  m_windowTasks += count;
  m_windowWorkerTasks += count - byCaller;
  if (++m_windowLoops < kWindowLoops) return;
  if (m_windowWorkerTasks * kLeastWorkerShare < m_windowTasks) m_soloLoopsLeft = kSoloLoops;
  m_windowLoops = 0;
  m_windowTasks = 0;
  m_windowWorkerTasks = 0;
}

std::size_t TaskPool::shareLoop(std::size_t count, TaskCall call, void* task) {
  m_call = call;
  m_task = task;
  m_unclaimed.store(packUnclaimed(0, count), std::memory_order_relaxed);
  m_loop.store(kOpen, std::memory_order_release);  // publishes the loop to joiners
  m_generation.fetch_add(1, std::memory_order_release);
  m_generation.notify_all();
  const std::size_t byCaller = runClaimedTasks(true);
  // Every task is claimed: close the loop, then wait for the workers that
  // joined it to finish theirs (and their reads of m_call and m_task),
  // before the next loop may overwrite them.
  if (m_loop.fetch_and(~kOpen, std::memory_order_acq_rel) == kOpen) return byCaller;  // nobody joined
  waitUntil(kCallerYielding, [&] { return m_loop.load(std::memory_order_acquire) == 0; },
            [&] {
              const uint32_t inside = m_loop.load(std::memory_order_acquire);
              if (inside != 0) m_loop.wait(inside, std::memory_order_acquire);
            });
  return byCaller;
}

std::size_t TaskPool::runClaimedTasks(bool fromFront) {
  std::size_t ran = 0;
  uint64_t unclaimed = m_unclaimed.load(std::memory_order_relaxed);
  for (;;) {
    const uint64_t front = unclaimed & 0xffffffffu;
    const uint64_t back = unclaimed >> 32;
    if (front >= back) return ran;
    const uint64_t index = fromFront ? front : back - 1;
    const uint64_t claimed = fromFront ? packUnclaimed(front + 1, back) : packUnclaimed(front, back - 1);
    if (!m_unclaimed.compare_exchange_weak(unclaimed, claimed, std::memory_order_relaxed)) continue;
    m_call(m_task, static_cast<std::size_t>(index));
    ++ran;
    unclaimed = m_unclaimed.load(std::memory_order_relaxed);
  }
}

void TaskPool::workerLoop() {
  uint32_t seen = 0;
  for (;;) {
    waitUntil(kWorkerYielding, [&] { return m_generation.load(std::memory_order_acquire) != seen; },
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
    runClaimedTasks(false);
    // The last worker out of a closed loop wakes the caller, which may be
    // asleep on it.
    if (m_loop.fetch_sub(1, std::memory_order_acq_rel) == 1) m_loop.notify_one();
  }
}

}  // namespace rbsim
