#pragma once
// Reading COLLADA (.dae) meshes through assimp: every mesh that the visual
// scene's nodes instance, placed by its node's transform, as one triangle
// mesh in metres and Z-up.
//
// The file's <unit meter="..."> is applied (in double precision: assimp
// would apply it as a float) and its <up_axis> turned to Z-up the way
// Gazebo does: Z_UP is kept as it is, Y_UP (COLLADA's default) is rotated
// +90 degrees about X so that the file's +Y points along +Z, and X_UP so
// that its +X does. Polygons are triangulated; lines and points are not
// part of a solid and are skipped; vertices are welded by exact position
// (as for STL), so that a closed mesh whose faces carry their own normals
// still shares its edges for validateClosedMesh. A node whose transform
// mirrors gets its triangles' order reversed, so that they still face out.
//
// The file is untrusted: it must be at most kMaxColladaBytes, passes
// checkColladaDocument (collada_guard.h) before assimp sees it, and assimp
// reads it from memory with every other file refused, so that references
// to other files (images, external nodes) are never followed. assimp's log
// stays off. Errors name the file, with assimp's reason where it has one.

#include <cstdint>
#include <string>

#include "rbsim/physics/shapes.h"
#include "rbsim/physics/types.h"

namespace rbsim {

inline constexpr std::uintmax_t kMaxColladaBytes = std::uintmax_t{128} << 20;

Expected<TriangleMesh> loadCollada(const std::string& path);

}  // namespace rbsim
