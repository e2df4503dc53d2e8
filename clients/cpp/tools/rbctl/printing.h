#pragma once
// rbctl's output: one line per record, "key value" pairs, so that people can
// read it and scripts can pick fields with awk; or JSON with the wire field
// names (--json). python3 -m rbsim prints the same (rbsim/printing.py).

#include <cstdio>
#include <rbsim/joints_t.hpp>
#include "rbsim/client/sensor_reader.h"
#include <rbsim/robot_state_t.hpp>
#include <rbsim/status_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <rbsim/world_t.hpp>
#include <string>
#include <vector>

namespace rbsim::rbctl {

// `bodies` empty: every body.
void printState(std::FILE* out, const rbsim::world_state_t& state,
                const std::vector<std::string>& bodies);
void printStatus(std::FILE* out, const rbsim::status_t& status);
void printWorld(std::FILE* out, const rbsim::world_t& world);
void printStateJson(std::FILE* out, const rbsim::world_state_t& state,
                    const std::vector<std::string>& bodies);
void printStatusJson(std::FILE* out, const rbsim::status_t& status);
void printWorldJson(std::FILE* out, const rbsim::world_t& world);
// The joints of `world` with their state from `joints` (none: null), as one
// JSON object: step, world_revision, joints.
void printJointsJson(std::FILE* out, const rbsim::world_t& world, const rbsim::joints_t* joints);
// The world's joints (type, bodies, axis, limits) with their state in
// `joints` (of the same world revision; nullptr when the world has none).
void printJoints(std::FILE* out, const rbsim::world_t& world, const rbsim::joints_t* joints);
// One robot's state: its joints and base; with `dynamics` also M, h, g and
// the links' poses (the Jacobians are in the JSON only).
void printRobotState(std::FILE* out, const rbsim::robot_state_t& state, bool dynamics);
// The state with the wire field names (all but utime), the dynamics' fields
// only with `dynamics`.
void printRobotStateJson(std::FILE* out, const rbsim::robot_state_t& state, bool dynamics);

// One line per reading: "sensor NAME type T step S sim_time T body B" and the
// reading's fields (docs/cli.md, "sensor"); the same line as python3 -m rbsim.
void printSensor(std::FILE* out, const client::SensorMessage& message);

}  // namespace rbsim::rbctl
