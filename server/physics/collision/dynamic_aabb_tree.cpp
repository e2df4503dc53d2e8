#include "physics/collision/dynamic_aabb_tree.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <limits>

namespace rbsim {

namespace {

constexpr std::size_t at(int index) {
  return static_cast<std::size_t>(index);
}

// A fat box is rebuilt when it exceeds the tight box by more than this many
// margins, so a body that moved fast and then slowed down does not keep a
// long box (and its false pairs) for ever. Box2D uses 4 as well.
constexpr double kHugeMarginFactor = 4.0;

}  // namespace

DynamicAabbTree::DynamicAabbTree(double fatMargin) : m_fatMargin(fatMargin) {
  assert(fatMargin >= 0.0);
}

int DynamicAabbTree::allocateNode() {
  int node;
  if (m_freeList == kNull) {
    node = static_cast<int>(m_nodes.size());
    m_nodes.emplace_back();
  } else {
    node = m_freeList;
    m_freeList = m_nodes[at(node)].parent;
    m_nodes[at(node)] = Node{};
  }
  m_nodes[at(node)].height = 0;
  return node;
}

void DynamicAabbTree::freeNode(int node) {
  Node& freed = m_nodes[at(node)];
  freed = Node{};
  freed.parent = m_freeList;
  m_freeList = node;
}

bool DynamicAabbTree::isLeafProxy(int proxy) const {
  return proxy >= 0 && at(proxy) < m_nodes.size() && m_nodes[at(proxy)].height == 0;
}

int DynamicAabbTree::createProxy(const Aabb& tight, int32_t userData) {
  assert(!tight.isEmpty());
  const int proxy = allocateNode();
  Node& leaf = m_nodes[at(proxy)];
  leaf.box = tight.fattened(m_fatMargin);
  leaf.userData = userData;
  insertLeaf(proxy);
  ++m_proxyCount;
  return proxy;
}

void DynamicAabbTree::destroyProxy(int proxy) {
  assert(isLeafProxy(proxy));
  removeLeaf(proxy);
  freeNode(proxy);
  --m_proxyCount;
}

bool DynamicAabbTree::moveProxy(int proxy, const Aabb& tight, const Vec3& displacement) {
  assert(isLeafProxy(proxy));
  assert(!tight.isEmpty());
  Aabb fat = tight.fattened(m_fatMargin);
  // Stretch towards where the body is heading (Box2D's "predict AABB movement").
  for (int axis = 0; axis < 3; ++axis) {
    if (displacement[axis] < 0.0) {
      fat.min[axis] += displacement[axis];
    } else {
      fat.max[axis] += displacement[axis];
    }
  }
  const Aabb& stored = m_nodes[at(proxy)].box;
  if (stored.contains(tight) && fat.fattened(kHugeMarginFactor * m_fatMargin).contains(stored)) {
    return false;
  }
  removeLeaf(proxy);
  m_nodes[at(proxy)].box = fat;
  insertLeaf(proxy);
  return true;
}

const Aabb& DynamicAabbTree::fatAabb(int proxy) const {
  assert(isLeafProxy(proxy));
  return m_nodes[at(proxy)].box;
}

int32_t DynamicAabbTree::userData(int proxy) const {
  assert(isLeafProxy(proxy));
  return m_nodes[at(proxy)].userData;
}

void DynamicAabbTree::setUserData(int proxy, int32_t userData) {
  assert(isLeafProxy(proxy));
  m_nodes[at(proxy)].userData = userData;
}

int DynamicAabbTree::height() const {
  return m_root == kNull ? 0 : m_nodes[at(m_root)].height;
}

// The sibling that adds the least surface area to the tree when the new leaf
// is paired with it (the SAH cost of a tree is the summed area of its
// internal nodes). Pairing with node X costs area(X ∪ D) for the new parent
// plus the growth of every ancestor of X (the "inherited" cost). A branch is
// pruned when a lower bound on any placement below it cannot beat the best
// cost found, and otherwise the descent follows the cheaper child: the
// greedy branch-and-bound of Box2D v3 (b2FindBestSibling), after Bittner,
// Hapala and Havran, "Fast insertion-based optimization of bounding volume
// hierarchies" (2013).
int DynamicAabbTree::findBestSibling(const Aabb& boxD) const {
  const Vec3 centerD = boxD.center();
  const double areaD = boxD.halfSurfaceArea();

  int index = m_root;
  double area = m_nodes[at(index)].box.halfSurfaceArea();
  double directCost = m_nodes[at(index)].box.merged(boxD).halfSurfaceArea();
  double inheritedCost = 0.0;
  int bestSibling = index;
  double bestCost = directCost;

  while (!m_nodes[at(index)].isLeaf()) {
    const Node& node = m_nodes[at(index)];
    const double cost = directCost + inheritedCost;
    if (cost < bestCost) {
      bestSibling = index;
      bestCost = cost;
    }
    inheritedCost += directCost - area;

    struct Option {
      int node;
      bool leaf;
      double area;
      double directCost;
      double lowerCost;
    };
    Option options[2];
    const int children[2] = {node.child1, node.child2};
    for (int k = 0; k < 2; ++k) {
      const Node& child = m_nodes[at(children[k])];
      Option& option = options[k];
      option.node = children[k];
      option.leaf = child.isLeaf();
      option.area = child.box.halfSurfaceArea();
      option.directCost = child.box.merged(boxD).halfSurfaceArea();
      option.lowerCost = std::numeric_limits<double>::infinity();
      if (option.leaf) {
        // A leaf can only become the sibling itself.
        const double leafCost = option.directCost + inheritedCost;
        if (leafCost < bestCost) {
          bestSibling = option.node;
          bestCost = leafCost;
        }
      } else {
        // Either the child itself (directCost) or something below it (at
        // least the child's growth plus area(D)).
        option.lowerCost = inheritedCost + option.directCost + std::min(areaD - option.area, 0.0);
      }
    }

    if (options[0].leaf && options[1].leaf) break;
    if (bestCost <= options[0].lowerCost && bestCost <= options[1].lowerCost) break;

    double key0 = options[0].lowerCost;
    double key1 = options[1].lowerCost;
    if (key0 == key1) {
      // Both children hold D whole: no area difference, take the nearer one.
      key0 = (m_nodes[at(options[0].node)].box.center() - centerD).squaredNorm();
      key1 = (m_nodes[at(options[1].node)].box.center() - centerD).squaredNorm();
    }
    const Option& next =
        (key0 < key1 && !options[0].leaf) || options[1].leaf ? options[0] : options[1];
    index = next.node;
    area = next.area;
    directCost = next.directCost;
  }
  return bestSibling;
}

void DynamicAabbTree::insertLeaf(int leaf) {
  if (m_root == kNull) {
    m_root = leaf;
    m_nodes[at(leaf)].parent = kNull;
    return;
  }
  const int sibling = findBestSibling(m_nodes[at(leaf)].box);
  const int oldParent = m_nodes[at(sibling)].parent;
  const int newParent = allocateNode();
  Node& parent = m_nodes[at(newParent)];
  parent.parent = oldParent;
  parent.child1 = sibling;
  parent.child2 = leaf;
  m_nodes[at(sibling)].parent = newParent;
  m_nodes[at(leaf)].parent = newParent;
  if (oldParent == kNull) {
    m_root = newParent;
  } else {
    replaceChild(oldParent, sibling, newParent);
  }
  refitUpwards(newParent);
}

void DynamicAabbTree::removeLeaf(int leaf) {
  if (leaf == m_root) {
    m_root = kNull;
    return;
  }
  const int parent = m_nodes[at(leaf)].parent;
  const int grandParent = m_nodes[at(parent)].parent;
  const int sibling =
      m_nodes[at(parent)].child1 == leaf ? m_nodes[at(parent)].child2 : m_nodes[at(parent)].child1;
  m_nodes[at(sibling)].parent = grandParent;
  freeNode(parent);
  m_nodes[at(leaf)].parent = kNull;
  if (grandParent == kNull) {
    m_root = sibling;
    return;
  }
  replaceChild(grandParent, parent, sibling);
  refitUpwards(grandParent);
}

void DynamicAabbTree::refitUpwards(int node) {
  for (int index = node; index != kNull; index = m_nodes[at(index)].parent) {
    index = balance(index);
    refit(index);
  }
}

void DynamicAabbTree::refit(int node) {
  Node& n = m_nodes[at(node)];
  const Node& a = m_nodes[at(n.child1)];
  const Node& b = m_nodes[at(n.child2)];
  n.box = a.box.merged(b.box);
  n.height = 1 + std::max(a.height, b.height);
}

void DynamicAabbTree::replaceChild(int parent, int oldChild, int newChild) {
  Node& p = m_nodes[at(parent)];
  if (p.child1 == oldChild) {
    p.child1 = newChild;
  } else {
    assert(p.child2 == oldChild);
    p.child2 = newChild;
  }
}

// AVL balance as in Box2D v2.4 (b2DynamicTree::Balance): when one child is
// more than one level taller than the other, rotate it up. Returns the node
// now at `node`'s place.
int DynamicAabbTree::balance(int node) {
  // Only the children's heights are read: this node's own is refitted after.
  const Node& n = m_nodes[at(node)];
  if (n.isLeaf()) return node;
  const int difference = m_nodes[at(n.child2)].height - m_nodes[at(n.child1)].height;
  if (difference > 1) return rotateUp(node, n.child2);
  if (difference < -1) return rotateUp(node, n.child1);
  return node;
}

// `tallChild` (C) takes the place of `node` (A). C keeps the taller of its
// children (F) and hands the shorter one (G) to A, in C's old place; A
// becomes C's other child. In parent(children) form:
//   A(B, C(F, G))  ->  C(A(B, G), F)
int DynamicAabbTree::rotateUp(int node, int tallChild) {
  const int a = node;
  const int c = tallChild;
  int f = m_nodes[at(c)].child1;
  int g = m_nodes[at(c)].child2;
  if (m_nodes[at(f)].height < m_nodes[at(g)].height) std::swap(f, g);

  const int aParent = m_nodes[at(a)].parent;
  m_nodes[at(c)].parent = aParent;
  if (aParent == kNull) {
    m_root = c;
  } else {
    replaceChild(aParent, a, c);
  }
  replaceChild(a, c, g);
  m_nodes[at(g)].parent = a;
  m_nodes[at(c)].child1 = a;
  m_nodes[at(c)].child2 = f;
  m_nodes[at(a)].parent = c;
  refit(a);
  refit(c);
  return c;
}

void DynamicAabbTree::rebuildTopDown() {
  if (m_root == kNull) return;
  std::vector<int> leaves;
  leaves.reserve(static_cast<std::size_t>(m_proxyCount));
  // Gather the leaves in the order of their ids, so that the build depends
  // on the boxes and ids alone, and free every inner node.
  for (std::size_t i = 0; i < m_nodes.size(); ++i) {
    if (m_nodes[i].height == 0) {
      leaves.push_back(static_cast<int>(i));
    }
  }
  for (std::size_t i = 0; i < m_nodes.size(); ++i)
    if (m_nodes[i].height > 0) freeNode(static_cast<int>(i));
  m_root = buildSubtree(leaves.data(), leaves.size());
  m_nodes[at(m_root)].parent = kNull;
}

// Splits the leaves in two by the surface-area heuristic, binned (Wald,
// "On fast construction of SAH-based bounding volume hierarchies", 2007):
// along each axis the leaves' centres fall into kBins bins, and of the
// kBins − 1 planes between bins the one with the least
// count(left) area(left) + count(right) area(right) wins. Leaves whose
// centres all fall in one bin are split at the median instead.
std::vector<int> DynamicAabbTree::createProxiesTopDown(const std::vector<Aabb>& tight) {
  assert(m_root == kNull);
  std::vector<int> proxies;
  proxies.reserve(tight.size());
  for (std::size_t k = 0; k < tight.size(); ++k) {
    assert(!tight[k].isEmpty());
    const int proxy = allocateNode();
    m_nodes[at(proxy)].box = tight[k].fattened(m_fatMargin);
    m_nodes[at(proxy)].userData = static_cast<int32_t>(k);
    proxies.push_back(proxy);
  }
  m_proxyCount += static_cast<int>(tight.size());
  if (proxies.empty()) return proxies;
  std::vector<int> leaves = proxies;
  m_root = buildSubtree(leaves.data(), leaves.size());
  m_nodes[at(m_root)].parent = kNull;
  return proxies;
}

int DynamicAabbTree::buildSubtree(int* leaves, std::size_t count) {
  if (count == 1) return leaves[0];
  constexpr int kBins = 16;
  Aabb centers = Aabb::empty();
  for (std::size_t i = 0; i < count; ++i) centers.include(m_nodes[at(leaves[i])].box.center());
  const Vec3 extent = centers.max - centers.min;
  const auto binOf = [&](int leaf, int axis) {
    const double offset = m_nodes[at(leaf)].box.center()[axis] - centers.min[axis];
    return std::min(static_cast<int>(kBins * offset / extent[axis]), kBins - 1);
  };
  int bestAxis = -1;
  int bestPlane = 0;  // leaves in bins [0, bestPlane] go left
  double bestCost = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    if (!(extent[axis] > 0.0)) continue;
    Aabb boxes[kBins];
    int counts[kBins] = {};
    for (std::size_t i = 0; i < count; ++i) {
      const int bin = binOf(leaves[i], axis);
      boxes[bin] = boxes[bin].merged(m_nodes[at(leaves[i])].box);
      ++counts[bin];
    }
    // Sweeps from the right, then from the left: cost of each plane.
    double rightArea[kBins];
    int rightCount[kBins];
    Aabb right = Aabb::empty();
    int rightLeaves = 0;
    for (int bin = kBins - 1; bin > 0; --bin) {
      right = right.merged(boxes[bin]);
      rightLeaves += counts[bin];
      rightArea[bin] = right.isEmpty() ? 0.0 : right.halfSurfaceArea();
      rightCount[bin] = rightLeaves;
    }
    Aabb left = Aabb::empty();
    int leftLeaves = 0;
    for (int plane = 0; plane < kBins - 1; ++plane) {
      left = left.merged(boxes[plane]);
      leftLeaves += counts[plane];
      if (leftLeaves == 0 || rightCount[plane + 1] == 0) continue;
      const double cost = leftLeaves * left.halfSurfaceArea() + rightCount[plane + 1] * rightArea[plane + 1];
      if (cost < bestCost) {
        bestCost = cost;
        bestAxis = axis;
        bestPlane = plane;
      }
    }
  }
  std::size_t half;
  if (bestAxis >= 0) {
    // A stable partition: the order within each side stays that of the
    // input, so the result depends only on the leaves.
    half = static_cast<std::size_t>(
        std::stable_partition(leaves, leaves + count, [&](int leaf) { return binOf(leaf, bestAxis) <= bestPlane; }) -
        leaves);
  } else {
    // Centres all in one point: the median by id.
    half = count / 2;
  }
  const int child1 = buildSubtree(leaves, half);
  const int child2 = buildSubtree(leaves + half, count - half);
  const int node = allocateNode();
  Node& parent = m_nodes[at(node)];
  parent.child1 = child1;
  parent.child2 = child2;
  m_nodes[at(child1)].parent = node;
  m_nodes[at(child2)].parent = node;
  refit(node);
  return node;
}

bool DynamicAabbTree::isValid() const {
  if (m_root == kNull) return m_proxyCount == 0;
  if (m_nodes[at(m_root)].parent != kNull) return false;
  int leaves = 0;
  int reached = 0;
  std::vector<int> stack{m_root};
  while (!stack.empty()) {
    const int index = stack.back();
    stack.pop_back();
    ++reached;
    const Node& node = m_nodes[at(index)];
    if (node.isLeaf()) {
      if (node.height != 0 || node.child2 != kNull) return false;
      ++leaves;
      continue;
    }
    const int children[2] = {node.child1, node.child2};
    for (const int child : children) {
      if (child < 0 || at(child) >= m_nodes.size()) return false;
      const Node& c = m_nodes[at(child)];
      if (c.parent != index || c.height < 0 || !node.box.contains(c.box)) return false;
      stack.push_back(child);
    }
    const int h1 = m_nodes[at(node.child1)].height;
    const int h2 = m_nodes[at(node.child2)].height;
    if (node.height != 1 + std::max(h1, h2)) return false;
  }
  int free = 0;
  for (int index = m_freeList; index != kNull; index = m_nodes[at(index)].parent) {
    if (m_nodes[at(index)].height != -1 || ++free > static_cast<int>(m_nodes.size())) return false;
  }
  return leaves == m_proxyCount && reached + free == static_cast<int>(m_nodes.size());
}

}  // namespace rbsim
