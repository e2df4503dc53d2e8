#pragma once
// An accelerometer and gyroscope on a rigid body, read from the step the
// world just took.
//
// The acceleration is that of the sensor's material point over the step:
// the centre of mass's (v₁ − v₀)/dt, plus the tangential term α × r with
// α = (ω₁ − ω₀)/dt and the centripetal term ω₁ × (ω₁ × r), r from the
// centre of mass to the sensor after the step. An accelerometer measures
// the specific force a − g (the acceleration the non-gravitational forces
// give), so it reads +g up at rest and 0 in free fall, as MuJoCo's
// `accelerometer` and Gazebo's IMU do; both vectors are then turned into
// the sensor frame.

#include "rbsim/physics/body_view.h"
#include "rbsim/physics/math_types.h"
#include "sensors/sensor_frame.h"
#include "sensors/sensor_reading.h"

namespace rbsim {

// The body's velocities before a step (world frame, centre of mass).
struct BodyVelocities {
  Vec3 linear = Vec3::Zero();   // m/s
  Vec3 angular = Vec3::Zero();  // rad/s
};

// `before` are the body's velocities before the step of length `dt` (s)
// that `body` is now after; `gravity` in m/s², world frame. No noise.
ImuReading readImu(const BodyView& body, const SensorFrame& frame, const BodyVelocities& before,
                   const Vec3& gravity, double dt);

}  // namespace rbsim
