// A whole config file: the world (parseWorldConfig, contact section
// included) and the server's own sections (loadServerSettings, which reads
// a path, so the input goes through a scratch file). A world that loads is
// built (World::fromDef: mass properties, hulls) and stepped a few times,
// as rbserver would.

#include <cstddef>
#include <cstdint>
#include <string>

#include "config/config_loader.h"
#include "daemon/server_settings.h"
#include "physics/world/world.h"
#include "scratch_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rbsim;
  (void)loadServerSettings(fuzz::writeScratchFile("world.yaml", data, size));

  const std::string text(reinterpret_cast<const char*>(data), size);
  // Relative mesh paths resolve as for config/*.yaml (config/meshes/...).
  const auto def = parseWorldConfig(text, "world.yaml", RBSIM_FUZZ_CONFIG_DIR);
  if (!def) return 0;
  auto world = World::fromDef(*def);
  if (!world) return 0;
  for (int i = 0; i < 3; ++i) world->step();
  return 0;
}
