#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "physics/collision/dynamic_aabb_tree.h"
#include "scenes/scene_random.h"

namespace rbsim {
namespace {

using scenes::SceneRandom;

Aabb randomBox(SceneRandom& random, double extent) {
  const Vec3 center(random.uniform(-extent, extent), random.uniform(-extent, extent),
                    random.uniform(-extent, extent));
  const Vec3 half(random.uniform(0.01, 0.3), random.uniform(0.01, 0.3), random.uniform(0.01, 0.3));
  return {center - half, center + half};
}

std::vector<int> queried(const DynamicAabbTree& tree, const Aabb& box) {
  std::vector<int> hits;
  tree.query(box, [&hits](int proxy) {
    hits.push_back(proxy);
    return true;
  });
  std::sort(hits.begin(), hits.end());
  return hits;
}

std::vector<int> bruteForce(const DynamicAabbTree& tree, const std::vector<int>& proxies,
                            const Aabb& box) {
  std::vector<int> hits;
  for (const int proxy : proxies)
    if (tree.fatAabb(proxy).overlaps(box)) hits.push_back(proxy);
  std::sort(hits.begin(), hits.end());
  return hits;
}

// An AVL tree over n leaves (2n − 1 nodes) is at most about 1.44 log2(2n) high.
// Ours is AVL-balanced along insertion paths, not strictly everywhere (see
// DynamicAabbTree::balance), and is held to the same bound.
int heightBound(int leaves) {
  return static_cast<int>(std::ceil(1.4405 * std::log2(2.0 * leaves + 1.0)));
}

TEST(DynamicAabbTree, EmptyTreeIsValidAndFindsNothing) {
  DynamicAabbTree tree;
  EXPECT_TRUE(tree.isValid());
  EXPECT_EQ(tree.height(), 0);
  EXPECT_TRUE(queried(tree, Aabb::everything()).empty());
}

TEST(DynamicAabbTree, StoresTheFatBoxAndTheUserData) {
  DynamicAabbTree tree(0.05);
  const Aabb tight{Vec3(0, 0, 0), Vec3(1, 2, 3)};
  const int proxy = tree.createProxy(tight, 42);
  EXPECT_EQ(tree.userData(proxy), 42);
  EXPECT_TRUE(tree.fatAabb(proxy).min.isApprox(Vec3::Constant(-0.05)));
  EXPECT_TRUE(tree.fatAabb(proxy).max.isApprox(Vec3(1.05, 2.05, 3.05)));
  tree.setUserData(proxy, 7);
  EXPECT_EQ(tree.userData(proxy), 7);
}

TEST(DynamicAabbTree, MovesAProxyOnlyWhenItLeavesItsFatBox) {
  DynamicAabbTree tree(0.1);
  const Aabb tight{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  const int proxy = tree.createProxy(tight, 0);
  const Vec3 small(0.05, 0, 0);
  EXPECT_FALSE(tree.moveProxy(proxy, {tight.min + small, tight.max + small}, small));
  const Vec3 large(0.2, 0, 0);
  EXPECT_TRUE(tree.moveProxy(proxy, {tight.min + large, tight.max + large}, large));
  // The new fat box is stretched along the motion.
  EXPECT_DOUBLE_EQ(tree.fatAabb(proxy).max.x(), 1.2 + 0.1 + 0.2);
  EXPECT_DOUBLE_EQ(tree.fatAabb(proxy).min.x(), 0.2 - 0.1);
  EXPECT_TRUE(tree.isValid());
}

TEST(DynamicAabbTree, ShrinksTheFatBoxOfABodyThatStopped) {
  DynamicAabbTree tree(0.1);
  const Aabb tight{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  const int proxy = tree.createProxy(tight, 0);
  const Vec3 fast(5.0, 0, 0);
  const Aabb moved{tight.min + fast, tight.max + fast};
  EXPECT_TRUE(tree.moveProxy(proxy, moved, fast));          // stretched 5 m ahead
  EXPECT_TRUE(tree.moveProxy(proxy, moved, Vec3::Zero()));  // stopped: too big now
  EXPECT_FALSE(tree.moveProxy(proxy, moved, Vec3::Zero()));
  EXPECT_DOUBLE_EQ(tree.fatAabb(proxy).max.x(), 6.1);
}

TEST(DynamicAabbTree, RandomInsertMoveRemoveStaysValidBalancedAndQueriesMatchBruteForce) {
  SceneRandom random(0xA4B7u);
  DynamicAabbTree tree(0.05);
  std::vector<int> proxies;
  std::vector<Aabb> tight;
  const double extent = 10.0;
  for (int i = 0; i < 2000; ++i) {
    tight.push_back(randomBox(random, extent));
    proxies.push_back(tree.createProxy(tight.back(), i));
  }
  ASSERT_TRUE(tree.isValid());
  EXPECT_LE(tree.height(), heightBound(tree.proxyCount()));

  for (int round = 0; round < 50; ++round) {
    for (int op = 0; op < 200; ++op) {
      const double dice = random.uniform(0, 1);
      const auto k =
          static_cast<std::size_t>(random.uniform(0, static_cast<double>(proxies.size())));
      if (dice < 0.7) {  // move by a random step, small or large
        const double reach = dice < 0.5 ? 0.02 : 2.0;
        const Vec3 step(random.uniform(-reach, reach), random.uniform(-reach, reach),
                        random.uniform(-reach, reach));
        tight[k] = {tight[k].min + step, tight[k].max + step};
        tree.moveProxy(proxies[k], tight[k], step);
      } else if (dice < 0.85 && proxies.size() > 1) {  // remove
        tree.destroyProxy(proxies[k]);
        proxies.erase(proxies.begin() + static_cast<std::ptrdiff_t>(k));
        tight.erase(tight.begin() + static_cast<std::ptrdiff_t>(k));
      } else {  // add
        tight.push_back(randomBox(random, extent));
        proxies.push_back(tree.createProxy(tight.back(), 0));
      }
    }
    ASSERT_TRUE(tree.isValid()) << "round " << round;
    ASSERT_EQ(tree.proxyCount(), static_cast<int>(proxies.size()));
    EXPECT_LE(tree.height(), heightBound(tree.proxyCount()));
    for (std::size_t i = 0; i < proxies.size(); ++i)
      ASSERT_TRUE(tree.fatAabb(proxies[i]).contains(tight[i]));
    for (int q = 0; q < 20; ++q) {
      const Aabb box = randomBox(random, extent).fattened(random.uniform(0, 2));
      ASSERT_EQ(queried(tree, box), bruteForce(tree, proxies, box));
    }
  }
}

TEST(DynamicAabbTree, HeightGrowsLogarithmicallyWhenInsertedInOrder) {
  // Sorted insertion is the worst case for a tree without rotations.
  DynamicAabbTree tree(0.0);
  for (int i = 0; i < 4096; ++i) {
    const Vec3 corner(i * 1.0, 0, 0);
    tree.createProxy({corner, corner + Vec3::Constant(0.5)}, i);
  }
  EXPECT_TRUE(tree.isValid());
  EXPECT_LE(tree.height(), heightBound(4096));
  EXPECT_GE(tree.height(), 12);  // log2(4096): no tree can be flatter
}

TEST(DynamicAabbTree, QueryStopsWhenTheVisitorSaysSo) {
  DynamicAabbTree tree;
  for (int i = 0; i < 10; ++i) tree.createProxy({Vec3::Zero(), Vec3::Ones()}, i);
  int visits = 0;
  tree.query(Aabb::everything(), [&visits](int) { return ++visits < 3; });
  EXPECT_EQ(visits, 3);
}

// The ray casts' rebuild: the same proxies, ids and boxes under new inner
// nodes, a valid tree, no taller than the insertions' one, that keeps
// working with moves and removals afterwards.
TEST(DynamicAabbTree, RebuiltTopDownKeepsItsProxiesAndStaysValid) {
  SceneRandom random(0x70D0);
  DynamicAabbTree tree(0.05);
  std::vector<int> proxies;
  for (int i = 0; i < 500; ++i) proxies.push_back(tree.createProxy(randomBox(random, 10.0), i));
  const int insertedHeight = tree.height();
  std::vector<Aabb> boxes;
  for (const int proxy : proxies) boxes.push_back(tree.fatAabb(proxy));
  tree.rebuildTopDown();
  ASSERT_TRUE(tree.isValid());
  EXPECT_EQ(tree.proxyCount(), 500);
  EXPECT_LE(tree.height(), insertedHeight);
  for (std::size_t i = 0; i < proxies.size(); ++i) {
    EXPECT_EQ(tree.userData(proxies[i]), static_cast<int32_t>(i));
    EXPECT_EQ(tree.fatAabb(proxies[i]).min, boxes[i].min);
  }
  for (int round = 0; round < 50; ++round) {
    const Aabb box = randomBox(random, 12.0);
    ASSERT_EQ(queried(tree, box), bruteForce(tree, proxies, box));
  }
  for (int i = 0; i < 100; ++i) tree.moveProxy(proxies[static_cast<std::size_t>(i)], randomBox(random, 10.0), Vec3::Zero());
  for (int i = 100; i < 200; ++i) tree.destroyProxy(proxies[static_cast<std::size_t>(i)]);
  EXPECT_TRUE(tree.isValid());
  DynamicAabbTree single(0.05);
  single.createProxy(randomBox(random, 1.0), 0);
  single.rebuildTopDown();
  EXPECT_TRUE(single.isValid());
}

TEST(DynamicAabbTree, SameCallsGiveTheSameTree) {
  const auto build = [] {
    SceneRandom random(0x5EEDu);
    DynamicAabbTree tree(0.05);
    std::vector<int> proxies;
    for (int i = 0; i < 500; ++i) proxies.push_back(tree.createProxy(randomBox(random, 5.0), i));
    for (int i = 0; i < 500; i += 3) {
      const Vec3 step = Vec3::Constant(random.uniform(-1, 1));
      const Aabb moved = randomBox(random, 5.0);
      tree.moveProxy(proxies[static_cast<std::size_t>(i)], moved, step);
    }
    for (int i = 0; i < 500; i += 7) tree.destroyProxy(proxies[static_cast<std::size_t>(i)]);
    std::vector<int> order;
    tree.query(Aabb::everything(), [&order](int proxy) {
      order.push_back(proxy);
      return true;
    });
    return order;
  };
  EXPECT_EQ(build(), build());
}

}  // namespace
}  // namespace rbsim
