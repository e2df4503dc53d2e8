#pragma once
// Heap allocations counted by part of the world step, for the test that the
// joint code makes none in a steady scene and for bench/joints (issue 39).
//
// Linking allocation_counter.cpp into an executable replaces malloc,
// calloc and realloc (glibc's documented way: "Replacing malloc") with
// versions that count each call on the calling thread, by the step part
// the thread is in (physics/common/step_part.h), then forward to glibc's.
// Counting malloc rather than operator new also sees Eigen's matrices,
// which allocate with malloc. Counts are the calling thread's: the joint
// code runs on the thread that steps the world; a step's parallel work on
// other threads (collision detection with more than one thread) is not in
// them.

#include <cstdint>

namespace rbsim::testing {

struct AllocationCounts {
  std::uint64_t total = 0;   // every allocation of this thread
  std::uint64_t joints = 0;  // those made in StepPart::Joints
  std::uint64_t jointNewton = 0;  // those made in StepPart::JointNewton (not in `joints`)
};

// Since the thread started.
AllocationCounts allocationCounts();

// While on, each allocation in joint code on this thread calls the empty
// function rbsim_joint_allocation, for a debugger's breakpoint.
void traceJointAllocations(bool on);

// Whether the counter is in this executable and counting (not under a
// sanitizer, which replaces malloc itself).
bool allocationCountingWorks();

// The allocations of this thread while it lives.
class AllocationScope {
 public:
  AllocationScope() : m_start(allocationCounts()) {}
  AllocationCounts counts() const {
    const AllocationCounts now = allocationCounts();
    return {now.total - m_start.total, now.joints - m_start.joints, now.jointNewton - m_start.jointNewton};
  }

 private:
  AllocationCounts m_start;
};

}  // namespace rbsim::testing
