// Terrains' height grids from .png files (meshio/height_grid.h): any
// bytes give a grid or an error, never a crash, a hang or a huge allocation.

#include <cstddef>
#include <cstdint>

#include "meshio/height_grid.h"
#include "scratch_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  (void)rbsim::loadHeightGrid(rbsim::fuzz::writeScratchFile("heights.png", data, size));
  return 0;
}
