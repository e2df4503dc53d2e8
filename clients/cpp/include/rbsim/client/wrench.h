#pragma once
// A wrench request as a C++ value; Client::applyWrench turns it into a
// wrench_t (lcmtypes/rbsim/wrench_t.lcm has the full semantics).

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace rbsim::client {

// x, y, z in the units and frame the field names.
using Vec3 = std::array<double, 3>;

// The values are those of wrench_t::FRAME_* and MODE_* (checked in client.cpp).
enum class Frame : int8_t {
  World = 0,  // the world frame
  // The frame the body is given in (its config frame, as for a URDF link);
  // world_t's shape_position and shape_orientation place it in the
  // principal-axes frame of the state. Turns with the body.
  Body = 1,
};

enum class WrenchMode : int8_t {
  OneStep = 0,     // during one step
  Duration = 1,    // during `duration` s of simulated time
  Persistent = 2,  // until cleared; replaces this client's previous persistent wrench on the body
  Clear = 3,       // removes this client's duration and persistent wrenches on the body
  ClearAllClients = 4,  // removes every client's duration and persistent wrenches on the body
};

struct Wrench {
  std::string body;            // name; may be empty only for the clears, meaning every body
  Vec3 force{0.0, 0.0, 0.0};   // N, in `frame`
  Vec3 torque{0.0, 0.0, 0.0};  // N·m, in `frame`: a pure couple added to the moment of the force
  // m, in `pointFrame`: where the force acts, a point of the body either way.
  // A world point is a world position (not an offset) at the moment the
  // wrench first acts; the body carries it from then on. A body point is
  // fixed in the body frame. Unset: the centre of mass, exactly (the server
  // places it: wrench_t::POINT_FRAME_CENTER_OF_MASS), so no moment.
  std::optional<Vec3> point;
  Frame frame = Frame::World;  // of force and torque
  // Of point; unset: the same as `frame` (a world force at a world point, a
  // body force at a body point). Ignored without a point.
  std::optional<Frame> pointFrame;
  WrenchMode mode = WrenchMode::OneStep;
  double duration = 0.0;     // s of simulated time, Duration only, > 0
  int64_t applyAtStep = -1;  // the step during which it first acts; -1 = the next step
};

}  // namespace rbsim::client
