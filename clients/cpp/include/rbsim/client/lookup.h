#pragma once
// Finding bodies by name in received messages.

#include <rbsim/body_description_t.hpp>
#include <rbsim/body_state_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <rbsim/world_t.hpp>
#include <string_view>

namespace rbsim::client {

// nullptr when the message has no body of that name.
const rbsim::body_state_t* findBody(const rbsim::world_state_t& state, std::string_view name);
const rbsim::body_description_t* findBody(const rbsim::world_t& world, std::string_view name);

}  // namespace rbsim::client
