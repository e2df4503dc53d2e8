// STL mesh files, ASCII and binary (loadStl tells them apart by content),
// then the rest of a mesh body's path.

#include <cstddef>
#include <cstdint>

#include "mesh_body.h"
#include "scratch_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rbsim::fuzz::loadMeshAsBody(rbsim::fuzz::writeScratchFile("mesh.stl", data, size));
  return 0;
}
