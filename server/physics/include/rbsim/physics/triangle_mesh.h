#pragma once
// An indexed triangle mesh: the boundary representation of a closed polyhedron.

#include <array>
#include <string>
#include <vector>

#include "rbsim/physics/expected.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct TriangleMesh {
  std::vector<Vec3> vertices;                 // m, in the mesh's own frame
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

// Checks that the mesh bounds a solid: no degenerate (zero-area) or
// out-of-range triangles, every edge shared by exactly two triangles that
// traverse it in opposite directions (closed and consistently wound), and a
// strictly positive enclosed volume (outward normals). The error names
// `sourceName` (usually the file path) and the first problem found; triangle
// and vertex numbers in messages count from 0.
Expected<bool> validateClosedMesh(const TriangleMesh& mesh, const std::string& sourceName);

// Checks a mesh that need not bound a solid (a trimesh shape's surface: a
// floor, a ramp, a room, open or closed): at least one triangle, every
// index in range, every vertex a triangle uses finite, and no triangle of
// zero area (three collinear or repeated vertices, relative to the size
// of the mesh as validateClosedMesh judges it). The error names
// `sourceName` and the first bad triangle (counting from 0).
Expected<bool> validateSurfaceMesh(const TriangleMesh& mesh, const std::string& sourceName);

// Corners of the axis-aligned box around the vertices the triangles use.
void usedVertexBounds(const TriangleMesh& mesh, Vec3& lower, Vec3& upper);

// The same mesh with every vertex mapped by p -> rotation * p + translation.
// A reflection (det(rotation) < 0) turns the mesh inside out.
TriangleMesh transformed(const TriangleMesh& mesh, const Mat3& rotation, const Vec3& translation);

}  // namespace rbsim
