#include "rbsim/client/lookup.h"

#include <algorithm>

namespace rbsim::client {

namespace {

template <class Body>
const Body* findByName(const std::vector<Body>& bodies, std::string_view name) {
  const auto found = std::find_if(bodies.begin(), bodies.end(),
                                  [&](const Body& body) { return body.name == name; });
  return found == bodies.end() ? nullptr : &*found;
}

}  // namespace

const rbsim::body_state_t* findBody(const rbsim::world_state_t& state, std::string_view name) {
  return findByName(state.bodies, name);
}

const rbsim::body_description_t* findBody(const rbsim::world_t& world, std::string_view name) {
  return findByName(world.bodies, name);
}

}  // namespace rbsim::client
