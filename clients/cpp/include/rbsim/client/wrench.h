#pragma once
// A wrench request as a C++ value; Client::applyWrench turns it into a
// wrench_t (lcmtypes/rbsim/wrench_t.lcm has the full semantics).

#include <array>
#include <cstdint>
#include <string>

namespace rbsim::client {

// x, y, z in the units and frame the field names.
using Vec3 = std::array<double, 3>;

// The values are those of wrench_t::FRAME_* and MODE_* (checked in client.cpp).
enum class Frame : int8_t {
  World = 0,  // fixed in the world; `point` is a world position
  Body = 1,   // body frame (origin at the centre of mass, principal axes); turns with the body
};

enum class WrenchMode : int8_t {
  OneStep = 0,     // during one step
  Duration = 1,    // during `duration` s of simulated time
  Persistent = 2,  // until cleared; replaces this client's previous persistent wrench on the body
  Clear = 3,       // removes this client's duration and persistent wrenches on the body
};

struct Wrench {
  std::string body;            // name; may be empty only for Clear, meaning every body
  Vec3 force{0.0, 0.0, 0.0};   // N, in `frame`
  Vec3 torque{0.0, 0.0, 0.0};  // N·m, in `frame`: a pure couple added to (point − x) × force
  // m, in `frame`: where the force acts. In the world frame this is a world
  // position, not an offset: leaving it at the origin for a body elsewhere
  // also applies the moment of the force about the centre of mass. In the
  // body frame it is relative to the centre of mass, so zero means "through it".
  Vec3 point{0.0, 0.0, 0.0};
  Frame frame = Frame::World;
  WrenchMode mode = WrenchMode::OneStep;
  double duration = 0.0;     // s of simulated time, Duration only, > 0
  int64_t applyAtStep = -1;  // the step during which it first acts; -1 = the next step
};

}  // namespace rbsim::client
