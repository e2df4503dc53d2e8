#pragma once
// The mesh targets' common path: a mesh file, as a config or a SPAWN names
// it, goes through the config loader (loadMesh, validateClosedMesh, the
// vertex bounds) and, if accepted, becomes a body of the small world (mass
// properties by Mirtich's integrals, collision hulls by qhull) that is then
// stepped against the other bodies; then the same file as a static trimesh
// body, stepped under them.

#include <string>

namespace rbsim::fuzz {

void loadMeshAsBody(const std::string& meshPath);

}  // namespace rbsim::fuzz
