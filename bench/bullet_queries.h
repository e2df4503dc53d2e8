#pragma once
// The Bullet side of the query benchmarks (bench_rays.cpp,
// bench_trimesh.cpp), for builds that have Bullet: rbsim's vectors as
// Bullet's, and Bullet's closest ray hit as a distance.

#include <btBulletCollisionCommon.h>

#include <optional>

#include "rbsim/physics/ray_cast.h"

namespace rbsim::bench {

inline btVector3 toBullet(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

// btCollisionWorld::rayTest with a ClosestRayResultCallback: the distance
// (m) to the nearest hit, or nothing.
inline std::optional<double> bulletRayTest(const btCollisionWorld& world, const Ray& ray) {
  const btVector3 from = toBullet(ray.from);
  const btVector3 to = toBullet(ray.to);
  btCollisionWorld::ClosestRayResultCallback callback(from, to);
  world.rayTest(from, to, callback);
  if (!callback.hasHit()) return std::nullopt;
  return callback.m_closestHitFraction * (to - from).length();
}

}  // namespace rbsim::bench
