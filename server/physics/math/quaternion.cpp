#include "rbsim/physics/quaternion.h"

#include <algorithm>
#include <cmath>

namespace rbsim {

Quaternion Quaternion::fromAxisAngle(const Vec3& axis, double angle) {
  const Vec3 u = axis.normalized();
  const double s = std::sin(0.5 * angle);
  return {std::cos(0.5 * angle), s * u.x(), s * u.y(), s * u.z()};
}

Quaternion Quaternion::fromRotationMatrix(const Mat3& m) {
  const double trace = m(0, 0) + m(1, 1) + m(2, 2);
  Quaternion q;
  if (trace >= m(0, 0) && trace >= m(1, 1) && trace >= m(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + trace);  // s = 4w
    q = {0.25 * s, (m(2, 1) - m(1, 2)) / s, (m(0, 2) - m(2, 0)) / s, (m(1, 0) - m(0, 1)) / s};
  } else if (m(0, 0) >= m(1, 1) && m(0, 0) >= m(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + m(0, 0) - m(1, 1) - m(2, 2));  // s = 4x
    q = {(m(2, 1) - m(1, 2)) / s, 0.25 * s, (m(0, 1) + m(1, 0)) / s, (m(0, 2) + m(2, 0)) / s};
  } else if (m(1, 1) >= m(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + m(1, 1) - m(0, 0) - m(2, 2));  // s = 4y
    q = {(m(0, 2) - m(2, 0)) / s, (m(0, 1) + m(1, 0)) / s, 0.25 * s, (m(1, 2) + m(2, 1)) / s};
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m(2, 2) - m(0, 0) - m(1, 1));  // s = 4z
    q = {(m(1, 0) - m(0, 1)) / s, (m(0, 2) + m(2, 0)) / s, (m(1, 2) + m(2, 1)) / s, 0.25 * s};
  }
  // Keep w >= 0 so that equal rotations map to equal quaternions.
  if (q.w < 0.0) q = {-q.w, -q.x, -q.y, -q.z};
  return q.normalized();
}

Quaternion Quaternion::fromRollPitchYaw(double roll, double pitch, double yaw) {
  const Quaternion qx = fromAxisAngle(Vec3::UnitX(), roll);
  const Quaternion qy = fromAxisAngle(Vec3::UnitY(), pitch);
  const Quaternion qz = fromAxisAngle(Vec3::UnitZ(), yaw);
  return qz * qy * qx;
}

Vec3 Quaternion::toRollPitchYaw() const {
  const Mat3 r = toRotationMatrix();
  // R = Rz(yaw) Ry(pitch) Rx(roll): r20 = -sin(pitch).
  const double sinPitch = std::clamp(-r(2, 0), -1.0, 1.0);
  const double pitch = std::asin(sinPitch);
  double roll, yaw;
  if (std::abs(sinPitch) < 1.0 - 1e-12) {
    roll = std::atan2(r(2, 1), r(2, 2));
    yaw = std::atan2(r(1, 0), r(0, 0));
  } else {
    // Gimbal lock: only roll - yaw (or roll + yaw) is defined; put it all in yaw.
    roll = 0.0;
    yaw = std::atan2(-r(0, 1), r(1, 1));
  }
  return {roll, pitch, yaw};
}

Vec3 Quaternion::rotate(const Vec3& v) const {
  // v' = v + 2 u × (u × v + w v), with u the vector part: two cross products
  // instead of two full quaternion products.
  const Vec3 u = vec();
  const Vec3 t = 2.0 * u.cross(v);
  return v + w * t + u.cross(t);
}

Vec3 Quaternion::inverseRotate(const Vec3& v) const { return conjugate().rotate(v); }

bool Quaternion::isFinite() const {
  return std::isfinite(w) && std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
}

bool operator==(const Quaternion& a, const Quaternion& b) {
  return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z;
}

}  // namespace rbsim
