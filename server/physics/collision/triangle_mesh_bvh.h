#pragma once
// A static bounding-volume hierarchy over the triangles of a mesh: an
// axis-aligned box tree built once, top down, and stored as a flat array in
// depth-first order (a node's first child follows it; the second is found
// by index). Queries walk it with an explicit stack, without allocating.
// The boxes are in the mesh's frame (for a trimesh shape, the body frame).

#include <array>
#include <cstdint>
#include <vector>

#include "physics/collision/aabb.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

class TriangleMeshBvh {
 public:
  struct Node {
    Aabb box;
    int first = 0;  // leaf: first slot in triangleOrder(); inner: the second child's node index
    int count = 0;  // leaf: how many triangles (> 0); inner: 0
  };

  // Leaves hold at most this many triangles.
  static constexpr int kLeafSize = 4;

  TriangleMeshBvh() = default;
  // One box per triangle, in triangle order. Each node splits its triangles
  // at the median of their box centres along the longest side of the
  // centres' box (ties broken by triangle index, so the tree only depends
  // on the boxes).
  explicit TriangleMeshBvh(const std::vector<Aabb>& triangleBoxes);

  const std::vector<Node>& nodes() const { return m_nodes; }
  const std::vector<int>& triangleOrder() const { return m_order; }
  bool empty() const { return m_nodes.empty(); }
  Aabb bounds() const { return m_nodes.empty() ? Aabb::empty() : m_nodes.front().box; }

  // Calls visit(triangle) for every triangle whose box the predicate
  // enters(box) accepts at every level down to its leaf; `enters` is asked
  // of the node boxes and of the triangles' own boxes. The predicate may
  // change between calls (a ray shortening as it hits).
  template <class Enters, class Visit>
  void traverse(Enters&& enters, Visit&& visit) const {
    if (m_nodes.empty()) return;
    std::array<int, 64> stack;  // depth <= log2(triangles) + 1, far below 64
    int top = 0;
    stack[static_cast<std::size_t>(top++)] = 0;
    while (top > 0) {
      const int index = stack[static_cast<std::size_t>(--top)];
      const Node& node = m_nodes[static_cast<std::size_t>(index)];
      if (!enters(node.box)) continue;
      if (node.count > 0) {
        for (int k = node.first; k < node.first + node.count; ++k) {
          const int triangle = m_order[static_cast<std::size_t>(k)];
          if (enters(m_triangleBoxes[static_cast<std::size_t>(triangle)])) visit(triangle);
        }
      } else {
        stack[static_cast<std::size_t>(top++)] = node.first;
        stack[static_cast<std::size_t>(top++)] = index + 1;  // first child: visited first
      }
    }
  }

  // Every triangle whose box overlaps `query` (closed boxes), once each.
  template <class Visit>
  void forEachOverlap(const Aabb& query, Visit&& visit) const {
    traverse([&query](const Aabb& box) { return box.overlaps(query); }, visit);
  }

 private:
  int build(int begin, int end, std::vector<Vec3>& centres);

  std::vector<Node> m_nodes;
  std::vector<int> m_order;  // triangle indices, each leaf's a contiguous run
  std::vector<Aabb> m_triangleBoxes;
};

}  // namespace rbsim
