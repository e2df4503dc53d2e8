#include "mesh_body.h"

#include "config/config_loader.h"
#include "small_world.h"

namespace rbsim::fuzz {

void loadMeshAsBody(const std::string& meshPath) {
  // The scratch path has no characters YAML would need quoted.
  const std::string yaml = "{name: fuzzed_mesh, shape: {type: mesh, file: '" + meshPath +
                           "'}, position: [0, 0, 0.5]}";
  const auto def = parseBodyDef(yaml, "spawn_yaml", "");
  if (!def) return;
  World world = smallWorld();
  if (!world.createBody(*def)) return;
  for (int i = 0; i < 2; ++i) world.step();
}

}  // namespace rbsim::fuzz
