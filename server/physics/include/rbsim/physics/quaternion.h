#pragma once
// Unit quaternion for orientation, stored and passed as (w, x, y, z).
//
// We keep our own small type rather than Eigen::Quaterniond because Eigen
// stores (x, y, z, w): one order in code, config and messages leaves no room
// for a silent swap. A quaternion q = [s, v] with s = cos(θ/2) and
// v = sin(θ/2) u rotates by θ about the unit axis u
// (Baraff, "Rigid Body Simulation", SIGGRAPH course notes).

#include <array>
#include <cmath>

#include "rbsim/physics/math_types.h"

namespace rbsim {

struct Quaternion {
  double w = 1.0;
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  static Quaternion identity() { return {}; }
  static Quaternion fromAxisAngle(const Vec3& axis, double angle);
  // From a proper rotation matrix (Shepperd's method: picks the largest
  // diagonal term so that the division is always well conditioned).
  static Quaternion fromRotationMatrix(const Mat3& rotation);
  // Roll about x, then pitch about y, then yaw about z, all about the fixed
  // (world) axes: R = Rz(yaw) Ry(pitch) Rx(roll), the aerospace/ROS convention.
  static Quaternion fromRollPitchYaw(double roll, double pitch, double yaw);

  Vec3 vec() const { return {x, y, z}; }
  double squaredNorm() const { return w * w + x * x + y * y + z * z; }
  double norm() const;
  Quaternion normalized() const;
  Quaternion conjugate() const { return {w, -x, -y, -z}; }

  // Body -> world rotation matrix; its columns are the body axes in world
  // coordinates.
  Mat3 toRotationMatrix() const;
  // (roll, pitch, yaw) as in fromRollPitchYaw; pitch in [-π/2, π/2].
  Vec3 toRollPitchYaw() const;
  // q v q*: rotates a vector from body to world.
  Vec3 rotate(const Vec3& v) const;
  // q* v q: rotates a vector from world to body.
  Vec3 inverseRotate(const Vec3& v) const;

  std::array<double, 4> toWxyz() const { return {w, x, y, z}; }
  bool isFinite() const;
};

// Hamilton product: (a b) rotates by b first, then by a.
Quaternion operator*(const Quaternion& a, const Quaternion& b);
bool operator==(const Quaternion& a, const Quaternion& b);

// The operations of the stepping loop are inline: they run for every body
// every step, and the library is built without link-time optimisation.

inline double Quaternion::norm() const { return std::sqrt(squaredNorm()); }

inline Quaternion Quaternion::normalized() const {
  const double inv = 1.0 / norm();
  return {w * inv, x * inv, y * inv, z * inv};
}

inline Mat3 Quaternion::toRotationMatrix() const {
  const double xx = x * x, yy = y * y, zz = z * z;
  const double xy = x * y, xz = x * z, yz = y * z;
  const double wx = w * x, wy = w * y, wz = w * z;
  Mat3 r;
  r << 1.0 - 2.0 * (yy + zz), 2.0 * (xy - wz), 2.0 * (xz + wy),  //
      2.0 * (xy + wz), 1.0 - 2.0 * (xx + zz), 2.0 * (yz - wx),   //
      2.0 * (xz - wy), 2.0 * (yz + wx), 1.0 - 2.0 * (xx + yy);
  return r;
}

inline Quaternion operator*(const Quaternion& a, const Quaternion& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
          a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

}  // namespace rbsim
