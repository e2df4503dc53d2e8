#include "fuzz_paths.h"

namespace rbsim::fuzz {

const char* const kMeshDir = RBSIM_FUZZ_MESH_DIR;
const char* const kConfigDir = RBSIM_FUZZ_CONFIG_DIR;
const char* const kUrdfDir = RBSIM_FUZZ_URDF_DIR;

}  // namespace rbsim::fuzz
