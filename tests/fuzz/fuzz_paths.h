#pragma once
// The folders the fuzz targets read beside their input, from the build.
// Defined in fuzz_paths.cpp, the one file compiled with the absolute paths,
// so that the targets' sources compile to the same objects in any clone
// (the compiler cache shares them; CI builds a fresh clone).

namespace rbsim::fuzz {

extern const char* const kMeshDir;    // tests/data/meshes
extern const char* const kConfigDir;  // config
extern const char* const kUrdfDir;    // tests/data/urdf

}  // namespace rbsim::fuzz
