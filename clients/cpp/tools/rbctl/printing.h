#pragma once
// rbctl's output: one line per record, "key value" pairs, so that people can
// read it and scripts can pick fields with awk.

#include <cstdio>
#include <rbsim/status_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <rbsim/world_t.hpp>
#include <string>

namespace rbsim::rbctl {

// `body` empty: every body.
void printState(std::FILE* out, const rbsim::world_state_t& state, const std::string& body);
void printStatus(std::FILE* out, const rbsim::status_t& status);
void printWorld(std::FILE* out, const rbsim::world_t& world);

}  // namespace rbsim::rbctl
