#pragma once
// Linear-algebra value types of the physics library.
//
// Conventions used everywhere in rbsim: SI units (m, kg, s, rad, N, N·m,
// kg·m²), right-handed frames, z up (gravity defaults to (0, 0, -9.81) m/s²),
// quaternions in (w, x, y, z) order, Hamilton product, body -> world.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rbsim {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

}  // namespace rbsim
