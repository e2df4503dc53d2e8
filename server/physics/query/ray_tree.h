#pragma once
// The ray casts' copy of a dynamic AABB tree (collision/dynamic_aabb_tree.h),
// laid out for walking it with rays. The dynamic tree is made for
// insertions and moves: a node holds its own box and its links, so a walk
// that tests a node's two children loads three scattered nodes, one after
// the other. Here each node holds its two children's boxes, side by side
// axis by axis so that one pair of operations tests both, in floats rounded
// outwards (a box only grows, so the walk stays conservative), in one
// 64-byte cache line; nodes are in depth-first order, so a node's first
// child is the next line. The layout is the usual one of ray-tracing BVHs
// (two children's boxes in their parent: Wald, Benthin and Boulos,
// "Getting rid of packets", 2008; boxes rounded outwards to a smaller
// type: Ylitie, Karras and Laine, "Efficient incoherent ray traversal on
// GPUs through compressed wide BVHs", 2017).
//
// The walk visits the leaves whose boxes the ray meets, nearer boxes first,
// and lets the visitor narrow the search as it finds hits (as Box2D's
// b2DynamicTree::RayCast does). It keeps its stack on the caller's stack,
// so any number of threads may walk one tree at once.

#include <cstdint>
#include <limits>
#include <vector>

#include "physics/collision/dynamic_aabb_tree.h"
#include "physics/query/ray_segment.h"

namespace rbsim {

class RayTree {
 public:
  // Copies `tree`'s shape; a leaf stands for its proxy's user data (>= 0).
  void assign(const DynamicAabbTree& tree);

  // Calls visit(userData) for every leaf whose box the ray meets at a
  // fraction in [0, maxFraction], nearer boxes first; visit returns the new
  // maxFraction (at most the one in force), or a negative value to stop.
  // Boxes entered exactly at maxFraction are still visited, so that a
  // caller can settle ties whatever the tree's shape.
  template <class Visit>
  void cast(const RaySegment& ray, double maxFraction, Visit&& visit) const {
    walk<false>(ray, Eigen::Array3d::Zero(), maxFraction, visit);
  }
  // The same walk for a box of half extents `grow` centred on the ray's
  // point, swept along it (a shape cast's bounds): each box of the tree is
  // grown by `grow` on every side (their Minkowski sum), so a leaf is
  // visited when the swept box meets its box.
  template <class Visit>
  void sweep(const RaySegment& ray, const Vec3& grow, double maxFraction, Visit&& visit) const {
    walk<true>(ray, grow.array(), maxFraction, visit);
  }

  int height() const { return m_height; }

 private:
  // A child: an inner node's index (>= 0) or a leaf's user data u as −1 − u.
  using Ref = int32_t;
  static constexpr Ref kEmpty = std::numeric_limits<Ref>::min();

  struct alignas(64) Node {
    float lower[3][2];  // m: lower[axis][k] of child k, rounded down
    float upper[3][2];  // m, rounded up
    Ref child[2];
  };

  Ref copy(const DynamicAabbTree& tree, int node, int depth);

  template <bool Grown, class Visit>
  void walk(const RaySegment& ray, const Eigen::Array3d& grow, double maxFraction, Visit& visit) const;

  // Where the ray enters each of the node's two boxes (0 inside), or +inf
  // for a box it does not meet in [0, maxFraction]: the slab test
  // (ray_segment.h) of both at once; with Grown, of the boxes grown by
  // `grow` (a ray's walk compiles without it).
  template <bool Grown>
  static Eigen::Array2d enters(const RaySegment& ray, const Node& node, const Eigen::Array3d& grow,
                               double maxFraction) {
    Eigen::Array2d near = Eigen::Array2d::Zero();
    Eigen::Array2d far = Eigen::Array2d::Constant(maxFraction);
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Array2d low = Eigen::Map<const Eigen::Array2f>(node.lower[axis]).cast<double>();
      Eigen::Array2d high = Eigen::Map<const Eigen::Array2f>(node.upper[axis]).cast<double>();
      if constexpr (Grown) {
        low -= grow[axis];
        high += grow[axis];
      }
      const Eigen::Array2d t0 = (low - ray.origin[axis]) * ray.inverseDelta[axis];
      const Eigen::Array2d t1 = (high - ray.origin[axis]) * ray.inverseDelta[axis];
      near = near.max(t0.min(t1));
      far = far.min(t0.max(t1));
    }
    return (near <= far).select(near, std::numeric_limits<double>::infinity());
  }

  std::vector<Node> m_nodes;
  Ref m_root = kEmpty;
  Aabb m_rootBox;
  int m_height = 0;  // edges on the longest path from the root to a leaf
};

template <bool Grown, class Visit>
void RayTree::walk(const RaySegment& ray, const Eigen::Array3d& grow, double maxFraction, Visit& visit) const {
  if (m_root == kEmpty) return;
  struct Pending {
    Ref ref;
    double enter;  // where the ray enters its box
  };
  // Each step pops one entry and pushes at most two, so the stack never
  // holds more than the height + 1 entries.
  constexpr std::size_t kInlineDepth = 64;
  Pending inlineStack[kInlineDepth];
  std::vector<Pending> tallStack;
  Pending* stack = inlineStack;
  if (static_cast<std::size_t>(m_height) + 2 > kInlineDepth) {
    tallStack.resize(static_cast<std::size_t>(m_height) + 2);
    stack = tallStack.data();
  }
  std::size_t size = 0;
  if (segmentEntersBox(ray, m_rootBox.min.array() - grow, m_rootBox.max.array() + grow, maxFraction) > maxFraction)
    return;
  // Down the nearer child of each node at once, its sibling kept on the
  // stack for later (when the ray meets both): a walk to the first leaf
  // costs no stack traffic.
  Ref current = m_root;
  while (true) {
    if (current >= 0) {
      const Node& node = m_nodes[static_cast<std::size_t>(current)];
      const Eigen::Array2d enter = enters<Grown>(ray, node, grow, maxFraction);
      const int nearer = enter[1] < enter[0] ? 1 : 0;
      if (enter[nearer] <= maxFraction) {
        if (enter[1 - nearer] <= maxFraction) stack[size++] = {node.child[1 - nearer], enter[1 - nearer]};
        current = node.child[nearer];
        continue;
      }
    } else {
      const double narrowed = visit(-1 - current);
      if (narrowed < 0.0) return;
      maxFraction = narrowed < maxFraction ? narrowed : maxFraction;
    }
    // Nothing below here: the next kept sibling the ray still meets before
    // maxFraction (a hit found since it was kept may have made it too far).
    while (size > 0 && stack[size - 1].enter > maxFraction) --size;
    if (size == 0) return;
    current = stack[--size].ref;
  }
}

}  // namespace rbsim
