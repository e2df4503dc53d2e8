// Between arm_bench.h's plain data and Bullet's types, for both Bullet
// adapters. btQuaternion is (x, y, z, w); ours are (w, x, y, z).
#pragma once

#include <btBulletDynamicsCommon.h>

#include "arm_bench.h"

namespace rbsim::bench::robots {

#ifdef BT_USE_DOUBLE_PRECISION
constexpr const char* kBulletPrecision = "f64";
#else
constexpr const char* kBulletPrecision = "f32";
#endif

inline btVector3 toBt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v[0]), static_cast<btScalar>(v[1]),
                   static_cast<btScalar>(v[2]));
}

inline btQuaternion toBt(const Quat& q) {
  return btQuaternion(static_cast<btScalar>(q[1]), static_cast<btScalar>(q[2]),
                      static_cast<btScalar>(q[3]), static_cast<btScalar>(q[0]));
}

inline Vec3 fromBt(const btVector3& v) {
  return {v.x(), v.y(), v.z()};
}

inline Quat fromBt(const btQuaternion& q) {
  return {q.w(), q.x(), q.y(), q.z()};
}

inline btTransform toBt(const Pose& pose) {
  return btTransform(toBt(pose.orientation), toBt(pose.position));
}

}  // namespace rbsim::bench::robots
