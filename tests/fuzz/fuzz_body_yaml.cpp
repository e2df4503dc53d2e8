// One body in YAML, as a SPAWN command's spawn_yaml or a `bodies:` entry:
// parsed (parseBodyDef), created in a small world and stepped. Mesh files
// named in the input are resolved against the repository's test meshes.

#include <cstddef>
#include <cstdint>
#include <string>

#include "config/config_loader.h"
#include "fuzz_paths.h"
#include "small_world.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rbsim;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto def = parseBodyDef(text, "spawn_yaml", rbsim::fuzz::kMeshDir);
  if (!def) return 0;
  World world = fuzz::smallWorld();
  if (!world.createBody(*def)) return 0;
  for (int i = 0; i < 2; ++i) world.step();
  return 0;
}
