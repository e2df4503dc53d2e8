#include "mesh_body.h"

#include "config/config_loader.h"
#include "small_world.h"

namespace rbsim::fuzz {

void loadMeshAsBody(const std::string& meshPath) {
  // The scratch path has no characters YAML would need quoted.
  const std::string yaml = "{name: fuzzed_mesh, shape: {type: mesh, file: '" + meshPath +
                           "'}, position: [0, 0, 0.5]}";
  if (const auto def = parseBodyDef(yaml, "spawn_yaml", "")) {
    World world = smallWorld();
    if (world.createBody(*def))
      for (int i = 0; i < 2; ++i) world.step();
  }
  // The same file as a static trimesh (any surface, open or closed) under
  // the small world's bodies: its BVH, active edges and triangle contacts.
  const std::string surface = "{name: fuzzed_trimesh, static: true, shape: {type: trimesh, file: '" +
                              meshPath + "'}, position: [0, 0, -0.5]}";
  if (const auto def = parseBodyDef(surface, "spawn_yaml", "")) {
    World world = smallWorld();
    if (world.createBody(*def))
      for (int i = 0; i < 2; ++i) world.step();
  }
}

}  // namespace rbsim::fuzz
