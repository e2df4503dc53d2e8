#pragma once
// How a body looks, as opposed to what it is: a robot link's URDF <visual>
// elements. Presentation only: the physics library never sees them (a body
// is simulated from its BodyDef alone); the server keeps them by body name
// beside the world and publishes them in world_t (lcmtypes visual_t) for
// viewers to draw.

#include <array>
#include <map>
#include <string>
#include <vector>

#include "rbsim/physics/types.h"

namespace rbsim {

struct Visual {
  enum class Kind { Box, Sphere, Cylinder, Mesh };
  Kind kind = Kind::Box;
  // Placement in the body's shape frame (a robot body's top link's frame):
  // p_shape = orientation p_visual + position.
  Vec3 position = Vec3::Zero();                     // m
  Quaternion orientation = Quaternion::identity();
  Vec3 halfExtents = Vec3::Zero();  // m: box
  double radius = 0.0;              // m: sphere, cylinder
  double halfLength = 0.0;          // m: cylinder, along z
  // Mesh: the URL path under the viewer bridge's mesh route ("world/...",
  // "spawn/..."), empty when the file lies outside the directories the
  // bridge serves; the file as the URDF names it, for reports.
  std::string meshUrl;
  std::string meshFile;
  Vec3 scale = Vec3::Ones();
  bool hasColor = false;
  std::array<double, 4> rgba = {0.0, 0.0, 0.0, 0.0};  // linear, 0..1
};

// The visuals of the bodies that have them, by body name.
using BodyVisuals = std::map<std::string, std::vector<Visual>, std::less<>>;

// The names under which the viewer's bridge serves mesh files (rbview
// --meshes and --spawn-meshes): the world file's directory and the spawn
// directory.
inline constexpr const char* kWorldMeshRoute = "world";
inline constexpr const char* kSpawnMeshRoute = "spawn";

}  // namespace rbsim
