#include "physics/collision/triangle_mesh_bvh.h"

#include <algorithm>
#include <numeric>

namespace rbsim {

TriangleMeshBvh::TriangleMeshBvh(const std::vector<Aabb>& triangleBoxes)
    : m_triangleBoxes(triangleBoxes) {
  const int count = static_cast<int>(triangleBoxes.size());
  if (count == 0) return;
  m_order.resize(triangleBoxes.size());
  std::iota(m_order.begin(), m_order.end(), 0);
  std::vector<Vec3> centres;
  centres.reserve(triangleBoxes.size());
  for (const Aabb& box : triangleBoxes) centres.push_back(box.center());
  m_nodes.reserve(2 * triangleBoxes.size());
  build(0, count, centres);
}

// Builds the node of m_order[begin, end) and its subtree; returns its index.
int TriangleMeshBvh::build(int begin, int end, std::vector<Vec3>& centres) {
  const int index = static_cast<int>(m_nodes.size());
  m_nodes.emplace_back();
  Aabb box = Aabb::empty();
  Aabb centreBox = Aabb::empty();
  for (int k = begin; k < end; ++k) {
    const int triangle = m_order[static_cast<std::size_t>(k)];
    box = box.merged(m_triangleBoxes[static_cast<std::size_t>(triangle)]);
    centreBox.include(centres[static_cast<std::size_t>(triangle)]);
  }
  m_nodes[static_cast<std::size_t>(index)].box = box;
  if (end - begin <= kLeafSize) {
    m_nodes[static_cast<std::size_t>(index)].first = begin;
    m_nodes[static_cast<std::size_t>(index)].count = end - begin;
    return index;
  }
  int axis = 0;
  const Vec3 extent = centreBox.max - centreBox.min;
  if (extent.y() > extent[axis]) axis = 1;
  if (extent.z() > extent[axis]) axis = 2;
  const int middle = begin + (end - begin) / 2;
  std::nth_element(m_order.begin() + begin, m_order.begin() + middle, m_order.begin() + end,
                   [&](int x, int y) {
                     const double cx = centres[static_cast<std::size_t>(x)][axis];
                     const double cy = centres[static_cast<std::size_t>(y)][axis];
                     return cx < cy || (cx == cy && x < y);
                   });
  build(begin, middle, centres);  // lands at index + 1
  const int second = build(middle, end, centres);
  m_nodes[static_cast<std::size_t>(index)].first = second;
  m_nodes[static_cast<std::size_t>(index)].count = 0;
  return index;
}

}  // namespace rbsim
