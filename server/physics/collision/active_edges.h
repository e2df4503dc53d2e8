#pragma once
// Which edges of a triangle mesh may produce contact normals of their own
// (Jolt's MeshShape active edges; Bullet's btAdjustInternalEdgeContacts
// solves the same problem). A body sliding over a floor of many triangles
// must not catch on the edges between them: only a real ridge may push it
// sideways. An edge is active when it bounds a single triangle (the border
// of an open mesh), is shared by more than two or by two wound against
// each other (no dihedral angle to judge), or is a convex ridge whose
// faces' normals differ by more than the threshold angle. Flat and concave
// edges are inactive: a contact there takes the triangle's face normal.

#include <array>
#include <cstdint>
#include <vector>

#include "rbsim/physics/math_types.h"

namespace rbsim {

// Normals within 5° count as one flat surface (Jolt's default threshold).
inline constexpr double kActiveEdgeCosine = 0.9961946980917455;  // cos 5°

// Per triangle, bit e set when its edge e (vertex e to vertex e + 1 mod 3)
// is active. Edges are matched by vertex position, not index, so that
// meshes loaded without welding (STL) still find their neighbours.
// Triangles must not be degenerate (validateSurfaceMesh).
std::vector<uint8_t> findActiveEdges(const std::vector<Vec3>& vertices,
                                     const std::vector<std::array<int, 3>>& triangles,
                                     double cosineThreshold = kActiveEdgeCosine);

// Is the feature of a triangle made of vertex `v` (0..2) active? A vertex
// is when one of its two edges is.
inline bool isActiveVertex(uint8_t activeEdges, int v) {
  return (activeEdges & (1u << v)) != 0 || (activeEdges & (1u << ((v + 2) % 3))) != 0;
}

}  // namespace rbsim
