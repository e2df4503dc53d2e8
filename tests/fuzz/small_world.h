#pragma once
// The world the message and command targets act on: a few bodies of
// different shapes, some touching the ground, so that wrenches and steps
// reach the contact code. Body names are in tests/fuzz/dictionaries/lcm.dict.

#include "rbsim/physics/world.h"

namespace rbsim::fuzz {

// Built once per process; targets copy it so that every input starts from
// the same state (a fuzz input must not depend on the ones before it).
const World& smallWorld();

}  // namespace rbsim::fuzz
