#pragma once
// The anchors' "pile" scene: N cubes of half-extent 0.1 m and density
// 1000 kg/m³ in a 10 × 10 grid of columns, 0.25 m pitch in x, y and z, the
// bottom layer 0.05 m above a static ground plane z = 0, each cube turned by
// up to ±0.1 rad about a random axis; dt = 1 ms, gravity −9.81 m/s² along z.
// The random sequence is the anchors' (splitmix64, seed 0x9113), so the cubes
// start exactly where Bullet's, ODE's and MuJoCo's do.
//
// The settled variant stacks the same columns as exact resting towers (cube
// k of a column at z = 0.1 + 0.2 k, unrotated, faces touching): the contact
// configuration of a pile at rest, for timing collision detection alone
// while there is no contact response to let the dropped pile settle.

#include <cmath>
#include <string>

#include "rbsim/physics/world_settings.h"
#include "scenes/scene_random.h"

namespace rbsim::scenes {

enum class PileVariant { Dropped, Settled };

// A rotation by an angle uniform in [−maxAngle, maxAngle] (rad) about a
// uniformly random axis: the anchors' small_rotation, draw for draw.
inline Quaternion smallRotation(SceneRandom& random, double maxAngle) {
  Vec3 axis;
  double norm = 0.0;
  do {
    axis = Vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
    norm = axis.norm();
  } while (norm < 1e-3 || norm > 1.0);
  const double angle = random.uniform(-maxAngle, maxAngle);
  const Vec3 v = axis / norm * std::sin(angle / 2);
  return Quaternion{std::cos(angle / 2), v.x(), v.y(), v.z()};
}

inline WorldDef makePileScene(int count, PileVariant variant) {
  constexpr int kColumns = 10;
  constexpr double kPitch = 0.25;      // m, between column centres and (dropped) layers
  constexpr double kHalfExtent = 0.1;  // m
  WorldDef def;
  def.settings.dt = 1e-3;
  def.settings.gravity = Vec3(0.0, 0.0, -9.81);

  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  def.bodies.push_back(ground);

  SceneRandom random(0x9113u);
  for (int i = 0; i < count; ++i) {
    const int layer = i / (kColumns * kColumns);
    const int column = i % (kColumns * kColumns);
    BodyDef body;
    body.name = "box" + std::to_string(i);
    body.shape = BoxShape{Vec3::Constant(kHalfExtent)};
    body.density = 1000.0;
    const double x = (column % kColumns - (kColumns - 1) / 2.0) * kPitch;
    const double y = (column / kColumns - (kColumns - 1) / 2.0) * kPitch;
    if (variant == PileVariant::Dropped) {
      body.position = Vec3(x, y, 0.15 + layer * kPitch);
      body.orientation = smallRotation(random, 0.1);
    } else {
      body.position = Vec3(x, y, kHalfExtent + 2 * kHalfExtent * layer);
    }
    def.bodies.push_back(body);
  }
  return def;
}

}  // namespace rbsim::scenes
