#pragma once
// Loading triangle meshes from files: Wavefront OBJ (faces triangulated as
// fans), STL, ASCII and binary (told apart by content, not by name), and
// COLLADA through assimp (collada_mesh.h). OBJ and STL keep their own
// readers: they are faster than assimp's and report line numbers
// (docs/world_file.md, "Meshes", has the measurement).
// Load-time I/O only; nothing here runs in the stepping path.

#include <string>

#include "rbsim/physics/types.h"
#include "rbsim/physics/shapes.h"

namespace rbsim {

// Mesh files are untrusted input: a file with more triangles than this is
// rejected before its triangles are stored.
inline constexpr int kMaxMeshTriangles = 2'000'000;

// Chooses the reader by extension (.obj, .stl, .dae, case-insensitive).
// STL and COLLADA vertices are welded by exact position so that closedness
// can be checked; COLLADA comes in metres and Z-up (its unit and up axis
// applied).
// Errors name the file and, where it applies, the line. Loading does not
// check that the mesh is closed: call validateClosedMesh before computing
// mass properties.
Expected<TriangleMesh> loadMesh(const std::string& path);
Expected<TriangleMesh> loadObj(const std::string& path);
Expected<TriangleMesh> loadStl(const std::string& path);

}  // namespace rbsim
