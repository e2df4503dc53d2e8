#pragma once
// The anchors' "spheres" scene: N spheres of radius 0.1 m and density
// 1000 kg/m³ dropped into a 2 × 2 m bin (four static walls 4 m high on a
// static ground plane), 9 × 9 per layer at 0.22 m pitch with ±0.01 m of
// jitter, layers 0.25 m apart from z = 0.15 m; dt = 1 ms, gravity −9.81 m/s².
// The jitter is the anchors' (splitmix64, seed 0x5B4E5), so the spheres
// start where Bullet's, ODE's and MuJoCo's do.

#include <string>

#include "rbsim/physics/world_settings.h"
#include "scenes/scene_random.h"

namespace rbsim::scenes {

inline WorldDef makeSphereBinScene(int count) {
  constexpr int kColumns = 9;
  constexpr double kPitch = 0.22;       // m, between neighbours in a layer
  constexpr double kLayerPitch = 0.25;  // m
  constexpr double kWallHalfHeight = 2.0;  // m
  WorldDef def;
  def.settings.dt = 1e-3;
  def.settings.gravity = Vec3(0.0, 0.0, -9.81);

  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  def.bodies.push_back(ground);
  const struct {
    const char* name;
    Vec3 position, halfExtents;
  } walls[] = {{"wall_x+", Vec3(1.05, 0, kWallHalfHeight), Vec3(0.05, 1.1, kWallHalfHeight)},
               {"wall_x-", Vec3(-1.05, 0, kWallHalfHeight), Vec3(0.05, 1.1, kWallHalfHeight)},
               {"wall_y+", Vec3(0, 1.05, kWallHalfHeight), Vec3(1.1, 0.05, kWallHalfHeight)},
               {"wall_y-", Vec3(0, -1.05, kWallHalfHeight), Vec3(1.1, 0.05, kWallHalfHeight)}};
  for (const auto& wall : walls) {
    BodyDef body;
    body.name = wall.name;
    body.shape = BoxShape{wall.halfExtents};
    body.position = wall.position;
    body.isStatic = true;
    def.bodies.push_back(body);
  }

  SceneRandom random(0x5B4E5u);
  for (int i = 0; i < count; ++i) {
    const int layer = i / (kColumns * kColumns);
    const int column = i % (kColumns * kColumns);
    BodyDef body;
    body.name = "sphere" + std::to_string(i);
    body.shape = SphereShape{0.1};
    body.density = 1000.0;
    const double x = (column % kColumns - (kColumns - 1) / 2.0) * kPitch + random.uniform(-0.01, 0.01);
    const double y = (column / kColumns - (kColumns - 1) / 2.0) * kPitch + random.uniform(-0.01, 0.01);
    body.position = Vec3(x, y, 0.15 + layer * kLayerPitch);
    def.bodies.push_back(body);
  }
  return def;
}

}  // namespace rbsim::scenes
