// The hull builder (buildConvexHull, qhull) on point sets of the kind a
// mesh loader can hand it: finite and within the config's 1e6 m bounds.
// Points are small integers on a lattice times a scale, which makes the
// cases that break hull code frequent: coplanar and collinear sets,
// duplicates, near-degenerate slivers, very large and very small scales.
//
// Input: one byte choosing the scale (10^(b % 12 − 8) m), then 3 bytes per
// point (signed x, y, z lattice coordinates).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "physics/collision/convex_hull.h"

namespace {

// What every caller of buildConvexHull relies on; a violation is a finding.
void checkHull(const rbsim::ConvexHull& hull) {
  const auto fail = [](const char* what) {
    std::fprintf(stderr, "convex hull invariant violated: %s\n", what);
    std::abort();
  };
  const int vertexCount = static_cast<int>(hull.vertices.size());
  if (vertexCount < 4 || hull.faces.size() < 4 || hull.edges.size() < 6) fail("too few features");
  for (const auto& face : hull.faces) {
    if (face.vertices.size() < 3) fail("a face with fewer than 3 vertices");
    if (!face.normal.allFinite() || std::abs(face.normal.norm() - 1.0) > 1e-9)
      fail("a face normal that is not unit");
    for (int v : face.vertices)
      if (v < 0 || v >= vertexCount) fail("a face vertex index out of range");
  }
  for (const auto& edge : hull.edges)
    for (int v : edge)
      if (v < 0 || v >= vertexCount) fail("an edge vertex index out of range");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const double scale = std::pow(10.0, static_cast<int>(data[0] % 12) - 8);
  std::vector<rbsim::Vec3> points;
  for (size_t i = 1; i + 3 <= size; i += 3) {
    points.emplace_back(static_cast<int8_t>(data[i]) * scale, static_cast<int8_t>(data[i + 1]) * scale,
                        static_cast<int8_t>(data[i + 2]) * scale);
  }
  const auto hull = rbsim::buildConvexHull(points, "fuzz");
  if (hull) checkHull(*hull);
  return 0;
}
