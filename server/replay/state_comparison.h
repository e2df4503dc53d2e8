#pragma once
// Bit-for-bit comparison of two world_state_t pages, or two joints_t pages
// (a recorded one and a replayed one), describing the first difference for
// people: which step, which body or joint, which quantity and by how much.

#include <optional>
#include <string>

#include <rbsim/joints_t.hpp>
#include <rbsim/world_state_t.hpp>

namespace rbsim {

// Nullopt when every field is bitwise equal (utime aside: it is wall-clock
// time, not state). Otherwise e.g. "step 120, body 'box_3' (id 4): position
// differs by 1.2e-06 m: log [...], replay [...]".
std::optional<std::string> firstStateDifference(const rbsim::world_state_t& recorded,
                                                const rbsim::world_state_t& replayed);

// The same for the joints' pages: "step 120, joint 'elbow': rate differs by
// 3e-15 rad/s or m/s: log [...], replay [...]".
std::optional<std::string> firstJointsDifference(const rbsim::joints_t& recorded,
                                                 const rbsim::joints_t& replayed);

}  // namespace rbsim
