#pragma once
// The little vector algebra the tests need to predict what the server does,
// written out independently of the physics library (which a test must not
// trust to check itself).

#include <array>
#include <cmath>

#include "rbsim/client/wrench.h"

namespace rbsim::e2e {

using client::Vec3;
using Mat3 = std::array<Vec3, 3>;  // rows

inline Vec3 toVec3(const double (&v)[3]) {
  return {v[0], v[1], v[2]};
}
inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 operator*(double s, const Vec3& v) {
  return {s * v[0], s * v[1], s * v[2]};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& v) {
  return std::sqrt(dot(v, v));
}

inline Vec3 operator*(const Mat3& m, const Vec3& v) {
  return {dot(m[0], v), dot(m[1], v), dot(m[2], v)};
}

inline Mat3 transpose(const Mat3& m) {
  return {{{m[0][0], m[1][0], m[2][0]}, {m[0][1], m[1][1], m[2][1]}, {m[0][2], m[1][2], m[2][2]}}};
}

// The rotation of a unit quaternion (w, x, y, z), body -> world.
inline Mat3 rotationOf(const double (&q)[4]) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

// L = R diag(I) Rᵀ ω: angular momentum about the centre of mass, world frame,
// from the principal moments `inertia` (body frame) and a state's q and ω.
inline Vec3 angularMomentum(const double (&orientation)[4], const double (&inertia)[3],
                            const double (&angularVelocity)[3]) {
  const Mat3 r = rotationOf(orientation);
  Vec3 bodyOmega = transpose(r) * toVec3(angularVelocity);
  for (int i = 0; i < 3; ++i) bodyOmega[static_cast<std::size_t>(i)] *= inertia[i];
  return r * bodyOmega;
}

// |a − b| relative to |b| (or absolute when b is zero).
inline double relativeError(const Vec3& a, const Vec3& b) {
  const double scale = norm(b);
  return scale > 0.0 ? norm(a - b) / scale : norm(a);
}

}  // namespace rbsim::e2e
