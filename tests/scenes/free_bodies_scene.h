#pragma once
// The free-body scene of the foundation benchmark (the same as the anchors'
// "free" scene): N cubes of half-extent 0.1 m and density 1000 kg/m³ on a
// 3-D grid of 0.5 m pitch (they never touch), uniformly random orientations,
// angular velocities uniform in [-5, 5]³ rad/s, no gravity, dt = 1 ms.

#include <string>

#include "rbsim/physics/world_settings.h"
#include "scenes/scene_random.h"

namespace rbsim::scenes {

inline WorldDef makeFreeBodiesScene(int count, IntegratorKind integrator) {
  WorldDef def;
  def.settings.dt = 1e-3;
  def.settings.gravity = Vec3::Zero();
  def.settings.integrator = integrator;
  SceneRandom random(0xF4EEu);
  int side = 1;
  while (side * side * side < count) ++side;
  const double pitch = 0.5;
  for (int i = 0; i < count; ++i) {
    BodyDef body;
    body.name = "box" + std::to_string(i);
    body.shape = BoxShape{Vec3::Constant(0.1)};
    body.density = 1000.0;
    body.position = Vec3((i % side - (side - 1) / 2.0) * pitch,
                         ((i / side) % side - (side - 1) / 2.0) * pitch,
                         1.0 + (i / (side * side)) * pitch);
    body.orientation = random.rotation();
    body.angularVelocity =
        Vec3(random.uniform(-5, 5), random.uniform(-5, 5), random.uniform(-5, 5));
    def.bodies.push_back(body);
  }
  return def;
}

}  // namespace rbsim::scenes
