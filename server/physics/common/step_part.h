#pragma once
// Which part of a world step the calling thread is in: a thread-local tag
// set for a scope, read by nothing in the library. The allocation counter
// of the tests and benchmarks (tests/support/allocation_counter.h) reads it
// to tell the heap allocations of the joint code from the rest's: the
// joint step must make none in a steady scene (issue 39), and a count by
// part says where one comes back. Setting it costs a thread-local store.

namespace rbsim {

enum class StepPart : unsigned char {
  Other,
  Joints,  // the joint step and the joints' part of the contact step
  // Within the joint step, the Newton fallback of its position projection
  // (a step whose start's rows converge too slowly): Eigen's sparse LU,
  // which allocates at every factorisation.
  JointNewton,
};

inline constinit thread_local StepPart t_stepPart = StepPart::Other;

inline StepPart currentStepPart() { return t_stepPart; }

// Marks the calling thread as in `part` until the scope ends (nests).
class StepPartScope {
 public:
  explicit StepPartScope(StepPart part) : m_previous(t_stepPart) { t_stepPart = part; }
  ~StepPartScope() { t_stepPart = m_previous; }
  StepPartScope(const StepPartScope&) = delete;
  StepPartScope& operator=(const StepPartScope&) = delete;

 private:
  StepPart m_previous;
};

}  // namespace rbsim
