#pragma once
// For tests of the library's internal layers (collision, time of impact),
// which take the internal Body: the body behind an id of a world.

#include <stdexcept>

#include "physics/body/body.h"
#include "rbsim/physics/world.h"

namespace rbsim::testing {

inline const Body& internalBody(const World& world, BodyId id) {
  if (!world.isValid(id)) throw std::invalid_argument("internalBody: not a body of this world");
  for (int i = 0; i < world.bodyCount(); ++i)
    if (world.idOf(i) == id) return world.internalBodies()[static_cast<std::size_t>(i)];
  throw std::logic_error("internalBody: a valid id with no dense index");
}

}  // namespace rbsim::testing
