#pragma once
// Handle to a body in a World. Index 0 is null; the generation makes a handle
// to a removed body fail loudly instead of reaching whatever reused its slot.

#include <cstdint>

namespace rbsim {

struct BodyId {
  int32_t index = 0;        // slot + 1; 0 = null
  uint32_t generation = 0;  // bumped every time the slot is freed

  bool isNull() const { return index == 0; }
  friend bool operator==(const BodyId&, const BodyId&) = default;
};

}  // namespace rbsim
