#pragma once
// Handles to bodies and joints in a World. Index 0 is null; the generation makes a handle
// to a removed body fail loudly instead of reaching whatever reused its slot,
// and the world tag makes a handle from another world fail the same way.
//
// A copy of a world (a reset copy, a look-ahead) is the same world at another
// moment: it keeps the tag, so handles taken from either name the same
// bodies in both. A world built anew (from a definition or a snapshot) has a
// tag of its own.

#include <cstdint>

namespace rbsim {

struct BodyId {
  int32_t index = 0;        // slot + 1; 0 = null
  uint32_t generation = 0;  // bumped every time the slot is freed
  uint32_t world = 0;       // tag of the world that handed it out

  bool isNull() const { return index == 0; }
  friend bool operator==(const BodyId&, const BodyId&) = default;
};

// Handle to a joint, on the same scheme (slot + 1, generation, world tag).
struct JointId {
  int32_t index = 0;
  uint32_t generation = 0;
  uint32_t world = 0;

  bool isNull() const { return index == 0; }
  friend bool operator==(const JointId&, const JointId&) = default;
};

}  // namespace rbsim
