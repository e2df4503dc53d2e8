// malloc, calloc and realloc counted by step part (allocation_counter.h),
// forwarding to glibc's own (__libc_malloc and the rest, which glibc
// exports for exactly this). free, memalign and the rest are glibc's: they
// work on the same heap. Left out under a sanitizer, which has its own.
#include "support/allocation_counter.h"

#include <cstddef>
#include <cstdlib>

#include "physics/common/step_part.h"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define RBSIM_COUNT_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define RBSIM_COUNT_ALLOCATIONS 0
#endif
#endif
#ifndef RBSIM_COUNT_ALLOCATIONS
#define RBSIM_COUNT_ALLOCATIONS 1
#endif

namespace {

// Plain thread-local counters: no allocation, no lock, nothing to
// initialise (so malloc may count before anything else has run).
constinit thread_local std::uint64_t t_total = 0;
constinit thread_local std::uint64_t t_joints = 0;
constinit thread_local std::uint64_t t_jointNewton = 0;
constinit thread_local bool t_trace = false;

}  // namespace

// Called for each allocation in joint code while traceJointAllocations is
// on: to see where one comes from,
//   gdb -ex 'break rbsim_joint_allocation' -ex run --args build/tests/test_joint_allocations
// and `bt` at the break.
extern "C" __attribute__((noinline)) void rbsim_joint_allocation() { asm volatile(""); }

namespace {

inline void count() {
  ++t_total;
  const rbsim::StepPart part = rbsim::currentStepPart();
  if (part == rbsim::StepPart::Joints) {
    ++t_joints;
    if (t_trace) rbsim_joint_allocation();
  } else if (part == rbsim::StepPart::JointNewton) {
    ++t_jointNewton;
  }
}

}  // namespace

#if RBSIM_COUNT_ALLOCATIONS
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void __libc_free(void* pointer);

void* malloc(std::size_t size) {
  count();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  count();
  return __libc_calloc(n, size);
}
void* realloc(void* pointer, std::size_t size) {
  count();
  return __libc_realloc(pointer, size);
}
void free(void* pointer) { __libc_free(pointer); }
}
#endif

namespace rbsim::testing {

AllocationCounts allocationCounts() { return {t_total, t_joints, t_jointNewton}; }

void traceJointAllocations(bool on) { t_trace = on; }

bool allocationCountingWorks() {
  const std::uint64_t before = t_total;
  void* volatile p = std::malloc(16);
  std::free(p);
  return t_total != before;
}

}  // namespace rbsim::testing
