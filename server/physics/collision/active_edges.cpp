#include "physics/collision/active_edges.h"

#include <algorithm>
#include <tuple>

namespace rbsim {

namespace {

bool lexLess(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// One triangle's side of an edge, keyed by the edge's end positions in
// lexicographic order, so that sorting brings an edge's sides together.
struct EdgeSide {
  Vec3 low;
  Vec3 high;
  int triangle = 0;
  int edge = 0;            // 0..2
  bool forward = false;    // the triangle runs low -> high
};

bool sameEdge(const EdgeSide& x, const EdgeSide& y) {
  return x.low == y.low && x.high == y.high;
}

}  // namespace

std::vector<uint8_t> findActiveEdges(const std::vector<Vec3>& vertices,
                                     const std::vector<std::array<int, 3>>& triangles,
                                     double cosineThreshold) {
  const auto corner = [&](std::size_t t, int k) -> const Vec3& {
    return vertices[static_cast<std::size_t>(triangles[t][static_cast<std::size_t>(k)])];
  };
  std::vector<Vec3> normals(triangles.size());
  std::vector<EdgeSide> sides;
  sides.reserve(3 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    normals[t] = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0)).normalized();
    for (int e = 0; e < 3; ++e) {
      const Vec3& from = corner(t, e);
      const Vec3& to = corner(t, (e + 1) % 3);
      const bool forward = lexLess(from, to);
      sides.push_back({forward ? from : to, forward ? to : from, static_cast<int>(t), e, forward});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const EdgeSide& x, const EdgeSide& y) {
    if (x.low != y.low) return lexLess(x.low, y.low);
    if (x.high != y.high) return lexLess(x.high, y.high);
    return std::tie(x.triangle, x.edge) < std::tie(y.triangle, y.edge);
  });

  std::vector<uint8_t> active(triangles.size(), 0);
  const auto setActive = [&](const EdgeSide& side) {
    active[static_cast<std::size_t>(side.triangle)] |= static_cast<uint8_t>(1u << side.edge);
  };
  for (std::size_t begin = 0; begin < sides.size();) {
    std::size_t end = begin + 1;
    while (end < sides.size() && sameEdge(sides[begin], sides[end])) ++end;
    const EdgeSide& first = sides[begin];
    if (end - begin != 2 || sides[begin + 1].forward == first.forward) {
      // A border, a non-manifold edge or an inconsistent winding.
      for (std::size_t k = begin; k < end; ++k) setActive(sides[k]);
    } else {
      const EdgeSide& second = sides[begin + 1];
      const Vec3& n1 = normals[static_cast<std::size_t>(first.triangle)];
      const Vec3& n2 = normals[static_cast<std::size_t>(second.triangle)];
      // Convex when the second triangle's far vertex lies behind the first's plane.
      const Vec3& far2 = corner(static_cast<std::size_t>(second.triangle), (second.edge + 2) % 3);
      const bool convex = n1.dot(far2 - first.low) < 0.0;
      if (convex && n1.dot(n2) < cosineThreshold) {
        setActive(first);
        setActive(second);
      }
    }
    begin = end;
  }
  return active;
}

}  // namespace rbsim
