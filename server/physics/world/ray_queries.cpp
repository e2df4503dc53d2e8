// World's ray casts (world.h): the world's side of query/ray_scene.h. The
// scene is brought up to date with the bodies, the ray and its filter are
// put in the scene's terms (dense indices), and its hits in the world's
// (ids, points, distances).
#include <stdexcept>
#include <string>

#include "physics/query/ray_scene.h"
#include "physics/world/world_data.h"
#include "rbsim/physics/world.h"

namespace rbsim {

namespace {

const RayScene& currentScene(const WorldData& world) {
  world.rayScene.refresh(world.bodies, world.revision);
  return world.rayScene;
}

// A ray with a direction and finite ends; anything else hits nothing.
bool isCastable(const Ray& ray) {
  return ray.from.allFinite() && ray.to.allFinite() && ray.from != ray.to;
}

int excludedIndex(const WorldData& world, const RayFilter& filter) {
  if (filter.excluded.isNull()) return -1;
  if (const std::string why = invalidIdReason(world, filter.excluded); !why.empty())
    throw std::invalid_argument("ray filter: the excluded body: " + why);
  return static_cast<int>(denseIndexOf(world, filter.excluded));
}

SceneRay sceneRay(const Ray& ray, const RayFilter& filter, int excluded) {
  return {RaySegment(ray.from, ray.to - ray.from), filter.filter, excluded};
}

RayHit worldHit(const WorldData& world, const Ray& ray, const SceneHit& hit) {
  const Vec3 delta = ray.to - ray.from;
  RayHit result;
  result.body = world.denseIds[static_cast<std::size_t>(hit.bodyIndex)];
  result.part = hit.part;
  result.piece = hit.piece;
  result.fraction = hit.fraction;
  result.distance = hit.fraction * delta.norm();
  result.point = ray.from + hit.fraction * delta;
  result.normal = hit.normal;
  return result;
}

}  // namespace

std::optional<RayHit> World::castRay(const Ray& ray, const RayFilter& filter) const {
  const int excluded = excludedIndex(*m_data, filter);
  if (!isCastable(ray)) return std::nullopt;
  const std::optional<SceneHit> hit = currentScene(*m_data).closest(sceneRay(ray, filter, excluded));
  if (!hit) return std::nullopt;
  return worldHit(*m_data, ray, *hit);
}

std::vector<RayHit> World::castRayAll(const Ray& ray, const RayFilter& filter) const {
  const int excluded = excludedIndex(*m_data, filter);
  std::vector<RayHit> result;
  if (!isCastable(ray)) return result;
  std::vector<SceneHit> hits;
  currentScene(*m_data).all(sceneRay(ray, filter, excluded), hits);
  result.reserve(hits.size());
  for (const SceneHit& hit : hits) result.push_back(worldHit(*m_data, ray, hit));
  return result;
}

bool World::castRayAny(const Ray& ray, const RayFilter& filter) const {
  const int excluded = excludedIndex(*m_data, filter);
  return isCastable(ray) && currentScene(*m_data).any(sceneRay(ray, filter, excluded));
}

void World::castRays(std::span<const Ray> rays, std::span<std::optional<RayHit>> hits,
                     const RayFilter& filter) const {
  if (hits.size() != rays.size())
    throw std::invalid_argument("castRays: " + std::to_string(hits.size()) + " hits for " +
                                std::to_string(rays.size()) + " rays");
  const int excluded = excludedIndex(*m_data, filter);
  const RayScene& scene = currentScene(*m_data);
  // One loop over the rays on the world's threads; each task writes its own
  // rays' answers, through the same closest() a single cast takes.
  const auto castChunk = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Ray& ray = rays[i];
      std::optional<SceneHit> hit;
      if (isCastable(ray)) hit = scene.closest(sceneRay(ray, filter, excluded));
      hits[i] = hit ? std::optional<RayHit>(worldHit(*m_data, ray, *hit)) : std::nullopt;
    }
  };
  // Rays per task: enough that a task outweighs claiming it, few enough
  // that the threads share a lidar's sweep evenly.
  constexpr std::size_t kRaysPerTask = 64;
  const std::unique_lock pool = scene.tryBorrowPool();
  if (pool.owns_lock() && rays.size() > kRaysPerTask) {
    // The pool is the world's mutable part: a const cast borrows it, as
    // only one batch at a time may (tryBorrowPool).
    forEachChunk(taskPool(*m_data), rays.size(), kRaysPerTask,
                 [&](std::size_t, std::size_t begin, std::size_t end) { castChunk(begin, end); });
  } else {
    castChunk(0, rays.size());
  }
}

}  // namespace rbsim
