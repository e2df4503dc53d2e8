// World's shape casts (world.h): the world's side of the ray scene's
// sweeps (query/ray_scene.h), as ray_queries.cpp is for rays.
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "physics/query/ray_scene.h"
#include "physics/world/world_data.h"
#include "rbsim/physics/world.h"

namespace rbsim {

namespace {

// Why a length of the cast shape is unusable, or "" when it is fine.
std::string badLength(const char* what, double value, bool zeroAllowed) {
  if (std::isfinite(value) && (value > 0.0 || (zeroAllowed && value == 0.0))) return "";
  return std::string("castShape: the shape's ") + what + " is " + std::to_string(value) + ", expected " +
         (zeroAllowed ? "a finite length >= 0" : "a finite length > 0");
}

void checkCastShape(const CastShape& shape) {
  const std::string why = std::visit(
      [](const auto& s) -> std::string {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, SphereShape>) {
          return badLength("radius", s.radius, false);
        } else if constexpr (std::is_same_v<S, BoxShape>) {
          for (int axis = 0; axis < 3; ++axis)
            if (std::string w = badLength("half extent", s.halfExtents[axis], false); !w.empty()) return w;
          return "";
        } else {
          // Capsule and cylinder: a capsule of half length 0 is a sphere.
          if (std::string w = badLength("radius", s.radius, false); !w.empty()) return w;
          return badLength("half length", s.halfLength, std::is_same_v<S, CapsuleShape>);
        }
      },
      shape);
  if (!why.empty()) throw std::invalid_argument(why);
}

ConvexGeometry sweptGeometry(const CastShape& shape) {
  return std::visit([](const auto& s) { return ConvexGeometry(s); }, shape);
}

bool isCastable(const ShapeCast& cast) {
  return cast.from.allFinite() && cast.to.allFinite() && cast.orientation.isFinite() &&
         cast.orientation.norm() > 0.0;
}

int excludedIndex(const WorldData& world, const RayFilter& filter) {
  if (filter.excluded.isNull()) return -1;
  if (const std::string why = invalidIdReason(world, filter.excluded); !why.empty())
    throw std::invalid_argument("shape cast filter: the excluded body: " + why);
  return static_cast<int>(denseIndexOf(world, filter.excluded));
}

SceneSweep sceneSweep(const ShapeCast& cast, const RayFilter& filter, int excluded) {
  return {sweptGeometry(cast.shape), Transform::fromPose(cast.from, cast.orientation.normalized()),
          cast.to - cast.from, filter.filter, excluded};
}

ShapeCastHit worldHit(const WorldData& world, const ShapeCast& cast, const SceneSweepHit& touch) {
  ShapeCastHit result;
  result.body = world.denseIds[static_cast<std::size_t>(touch.hit.bodyIndex)];
  result.part = touch.hit.part;
  result.piece = touch.hit.piece;
  result.fraction = touch.hit.fraction;
  result.distance = touch.hit.fraction * (cast.to - cast.from).norm();
  result.point = touch.point;
  result.normal = touch.hit.normal;
  return result;
}

const RayScene& currentScene(const WorldData& world) {
  world.rayScene.refresh(world.bodies, world.revision);
  return world.rayScene;
}

}  // namespace

std::optional<ShapeCastHit> World::castShape(const ShapeCast& cast, const RayFilter& filter) const {
  checkCastShape(cast.shape);
  const int excluded = excludedIndex(*m_data, filter);
  if (!isCastable(cast)) return std::nullopt;
  const std::optional<SceneSweepHit> touch = currentScene(*m_data).sweepClosest(sceneSweep(cast, filter, excluded));
  if (!touch) return std::nullopt;
  return worldHit(*m_data, cast, *touch);
}

std::vector<ShapeCastHit> World::castShapeAll(const ShapeCast& cast, const RayFilter& filter) const {
  checkCastShape(cast.shape);
  const int excluded = excludedIndex(*m_data, filter);
  std::vector<ShapeCastHit> result;
  if (!isCastable(cast)) return result;
  std::vector<SceneSweepHit> touches;
  currentScene(*m_data).sweepAll(sceneSweep(cast, filter, excluded), touches);
  result.reserve(touches.size());
  for (const SceneSweepHit& touch : touches) result.push_back(worldHit(*m_data, cast, touch));
  return result;
}

}  // namespace rbsim
