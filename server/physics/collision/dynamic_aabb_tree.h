#pragma once
// A dynamic bounding-volume tree of fattened AABBs (as in Box2D and Bullet's
// btDbvt): insertion by the surface-area heuristic, AVL-style rotations to
// keep it balanced, and proxies that only move in the tree when their tight
// box leaves the fat one, so that a resting scene costs almost nothing.
//
// Balance: the rotations (Box2D v2.4's) restore the AVL condition along the
// path of every insertion and removal, but the SAH may pair a leaf with a
// tall subtree, which one rotation cannot fully even out; so the AVL
// condition is not an invariant. The height stays within the AVL bound
// (1.44 log2 of the node count) in the randomised tests.
//
// Determinism: the tree's shape, and so the order in which query() visits
// proxies, depends only on the sequence of calls (no pointers, hashes or
// clocks). Nodes live in one vector; freed nodes are reused last-in first-out.

#include <cstdint>
#include <vector>

#include "physics/collision/aabb.h"

namespace rbsim {

class DynamicAabbTree {
 public:
  static constexpr int kNull = -1;

  explicit DynamicAabbTree(double fatMargin = 0.05);  // m added on every side

  // Stores `tight` fattened by the margin; returns the proxy id.
  int createProxy(const Aabb& tight, int32_t userData);
  void destroyProxy(int proxy);
  // Re-inserts the proxy only if `tight` is no longer inside its fat box, or
  // if the fat box has become much larger than needed (a fast body that
  // slowed down); returns whether it did. `displacement` (m) stretches the
  // new fat box in the direction of motion.
  bool moveProxy(int proxy, const Aabb& tight, const Vec3& displacement);

  const Aabb& fatAabb(int proxy) const;
  int32_t userData(int proxy) const;
  void setUserData(int proxy, int32_t userData);

  // Calls visit(proxy) for every proxy whose fat box overlaps `box`; stops
  // early if visit returns false. Not reentrant: visit must not query this
  // tree again (the traversal stack is shared).
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) const;

  // Rebuilds the tree's inner nodes from its leaves, top down, splitting
  // each node's leaves by the binned surface-area heuristic (the
  // insertion's cost measure, applied to all leaves at once; cf. Bullet's
  // btDbvt::optimizeTopDown). Proxies keep their ids and boxes. Insertions
  // one at a time leave a tree built for pairs; the top-down tree is
  // shallower and its nodes overlap less, which a ray walk pays for at
  // every node. Deterministic: the split depends only on the leaves' boxes
  // and ids.
  void rebuildTopDown();
  // For an empty tree: a proxy for each of `tight` (fattened), proxy k with
  // user data k, built top down at once as rebuildTopDown does, rather than
  // inserted one by one. Returns the proxies' ids.
  std::vector<int> createProxiesTopDown(const std::vector<Aabb>& tight);

  // The tree's shape, read only, for walks of its own (the ray casts'
  // query/ray_tree.h): the root (kNull when empty) and, for an inner node,
  // its two children; a node's box (a leaf's is its fat box).
  int root() const { return m_root; }
  bool isLeaf(int node) const { return m_nodes[static_cast<std::size_t>(node)].isLeaf(); }
  int child1(int node) const { return m_nodes[static_cast<std::size_t>(node)].child1; }
  int child2(int node) const { return m_nodes[static_cast<std::size_t>(node)].child2; }
  const Aabb& box(int node) const { return m_nodes[static_cast<std::size_t>(node)].box; }

  int proxyCount() const { return m_proxyCount; }
  int height() const;  // edges on the longest root-to-leaf path; 0 when empty
  // Checks parent links, heights, that each parent box holds its children
  // and that every node is either in the tree or free: for tests.
  bool isValid() const;

 private:
  struct Node {
    Aabb box;            // leaves: the fat box; internal nodes: the union of the children
    int parent = kNull;  // free nodes: the next free node
    int child1 = kNull;
    int child2 = kNull;
    int height = -1;  // 0 for leaves, -1 when free
    int32_t userData = -1;
    bool isLeaf() const { return child1 == kNull; }
  };

  int allocateNode();
  void freeNode(int node);
  int findBestSibling(const Aabb& box) const;
  void insertLeaf(int leaf);
  void removeLeaf(int leaf);
  // Refits the boxes and heights from `node` up to the root, rebalancing on the way.
  void refitUpwards(int node);
  int balance(int node);
  int rotateUp(int node, int tallChild);
  void refit(int node);
  void replaceChild(int parent, int oldChild, int newChild);
  bool isLeafProxy(int proxy) const;
  int buildSubtree(int* leaves, std::size_t count);

  std::vector<Node> m_nodes;
  int m_root = kNull;
  int m_freeList = kNull;
  int m_proxyCount = 0;
  double m_fatMargin;
  mutable std::vector<int> m_stack;
};

template <class Visit>
void DynamicAabbTree::query(const Aabb& box, Visit&& visit) const {
  if (m_root == kNull) return;
  m_stack.clear();
  m_stack.push_back(m_root);
  while (!m_stack.empty()) {
    const int index = m_stack.back();
    m_stack.pop_back();
    const Node& node = m_nodes[static_cast<std::size_t>(index)];
    if (!node.box.overlaps(box)) continue;
    if (node.isLeaf()) {
      if (!visit(index)) return;
    } else {
      m_stack.push_back(node.child1);
      m_stack.push_back(node.child2);
    }
  }
}

}  // namespace rbsim
