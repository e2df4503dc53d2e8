#pragma once
// A convex polyhedron with its faces and edges: the collision geometry of a
// mesh (the hull of its vertices), built with qhull.

#include <array>
#include <string>
#include <vector>

#include "rbsim/physics/expected.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct ConvexHull {
  struct Face {
    Vec3 normal = Vec3::UnitZ();  // unit, outward
    double offset = 0.0;          // m: normal · p = offset on the face
    std::vector<int> vertices;    // counter-clockwise seen from outside; coplanar triangles merged
  };
  std::vector<Vec3> vertices;                // m, in the hull's frame; only hull vertices
  std::vector<Face> faces;
  std::vector<std::array<int, 2>> edges;     // each undirected edge once, for SAT edge axes
};

// The convex hull of `points` (qhull). Rejects, with a message naming
// `sourceName`, fewer than 4 distinct points, and coplanar or collinear sets
// (zero volume).
Expected<ConvexHull> buildConvexHull(const std::vector<Vec3>& points, const std::string& sourceName);

}  // namespace rbsim
