#include "physics/query/ray_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rbsim {

namespace {

// The float nearest x on the low (or high) side: a box rounded outwards
// holds the box it was made from.
float roundedDown(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float roundedUp(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

}  // namespace

void RayTree::assign(const DynamicAabbTree& tree) {
  m_nodes.clear();
  m_height = 0;
  m_root = kEmpty;
  if (tree.root() == DynamicAabbTree::kNull) return;
  m_rootBox = tree.box(tree.root());
  m_root = copy(tree, tree.root(), 0);
}

// Depth first: a node's first child comes right after it.
RayTree::Ref RayTree::copy(const DynamicAabbTree& tree, int node, int depth) {
  m_height = std::max(m_height, depth);
  if (tree.isLeaf(node)) return -1 - tree.userData(node);
  const auto index = static_cast<Ref>(m_nodes.size());
  m_nodes.emplace_back();
  const int children[2] = {tree.child1(node), tree.child2(node)};
  for (int k = 0; k < 2; ++k) {
    // Set through the index: copying the child may grow (move) the nodes.
    const Aabb& box = tree.box(children[k]);
    Node& parent = m_nodes[static_cast<std::size_t>(index)];
    for (int axis = 0; axis < 3; ++axis) {
      parent.lower[axis][k] = roundedDown(box.min[axis]);
      parent.upper[axis][k] = roundedUp(box.max[axis]);
    }
    const Ref child = copy(tree, children[k], depth + 1);
    m_nodes[static_cast<std::size_t>(index)].child[k] = child;
  }
  return index;
}

}  // namespace rbsim
