#pragma once
// Triangle meshes for the trimesh tests, built in code so that every
// coordinate is known exactly.

#include <array>

#include "rbsim/physics/triangle_mesh.h"

namespace rbsim::testing {

// A flat square grid in the plane z = 0, x and y in [−halfSize, halfSize],
// `cells` × `cells` squares each split into two triangles along alternating
// diagonals; fronts facing +z.
inline TriangleMesh flatGrid(int cells, double halfSize) {
  TriangleMesh mesh;
  const double step = 2.0 * halfSize / cells;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) mesh.vertices.emplace_back(-halfSize + i * step, -halfSize + j * step, 0.0);
  const auto at = [cells](int i, int j) { return j * (cells + 1) + i; };
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if ((i + j) % 2 == 0) {
        mesh.triangles.push_back({a, b, c});
        mesh.triangles.push_back({a, c, d});
      } else {
        mesh.triangles.push_back({a, b, d});
        mesh.triangles.push_back({b, c, d});
      }
    }
  }
  return mesh;
}

// A step, open: a floor at z = 0 for x in [−2, 0], a wall at x = 0 from
// z = 0 to `height` facing −x, and a top at z = height for x in [0, 2];
// y in [−1, 1]. The floor–wall edge is concave, the wall–top edge convex.
inline TriangleMesh stepMesh(double height) {
  TriangleMesh mesh;
  mesh.vertices = {{-2, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-2, 1, 0},
                   {0, -1, height}, {0, 1, height}, {2, -1, height}, {2, 1, height}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3},   // floor, +z
                    {1, 4, 5}, {1, 5, 2},   // wall, −x
                    {4, 6, 7}, {4, 7, 5}};  // top, +z
  return mesh;
}

}  // namespace rbsim::testing
