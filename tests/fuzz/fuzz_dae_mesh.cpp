// COLLADA mesh files (loadCollada: the document check, then assimp, then
// the node transforms and the welding), then the rest of a mesh body's path.

#include <cstddef>
#include <cstdint>

#include "mesh_body.h"
#include "scratch_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rbsim::fuzz::loadMeshAsBody(rbsim::fuzz::writeScratchFile("mesh.dae", data, size));
  return 0;
}
