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

inline void count() {
  ++t_total;
  if (rbsim::currentStepPart() == rbsim::StepPart::Joints) ++t_joints;
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

AllocationCounts allocationCounts() { return {t_total, t_joints}; }

bool allocationCountingWorks() {
  const std::uint64_t before = t_total;
  void* volatile p = std::malloc(16);
  std::free(p);
  return t_total != before;
}

}  // namespace rbsim::testing
