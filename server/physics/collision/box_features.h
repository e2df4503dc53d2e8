#pragma once
// The vertices and faces of a box, numbered once for every routine that
// needs them (box–box, box–plane, support features, the box as a hull), so
// that feature ids mean the same thing everywhere.

#include <array>

#include "physics/collision/convex_hull.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

// Vertex i has coordinate k at +halfExtents[k] if bit k of i is set, else at −.
Vec3 boxVertex(const Vec3& halfExtents, int index);

// Face f looks along +axis (f = 2 axis) or −axis (f = 2 axis + 1).
inline int boxFaceIndex(int axis, bool negative) {
  return 2 * axis + (negative ? 1 : 0);
}
Vec3 boxFaceNormal(int face);
// The face's four vertex indices, counter-clockwise seen from outside.
std::array<int, 4> boxFaceVertices(int face);

// The box as a convex hull with the same vertex and face numbering, so that
// boxes pair with hulls (and capsules) through the hull routines.
ConvexHull boxHull(const Vec3& halfExtents);

}  // namespace rbsim
