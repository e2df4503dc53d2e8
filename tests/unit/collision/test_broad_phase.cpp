#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "physics/collision/broad_phase.h"
#include "rbsim/physics/world.h"
#include "scenes/pile_scene.h"
#include "scenes/scene_random.h"
#include "support/body_copies.h"

namespace rbsim {
namespace {

using scenes::SceneRandom;

constexpr double kContactMargin = 0.005;  // m

// A random scene: boxes (a fifth of them static) in a cube of side `extent`,
// a static ground plane and a static tilted plane.
struct RandomScene {
  std::vector<BroadPhaseBody> bodies;
  std::vector<Vec3> velocities;  // m per update
  int32_t lastSerial = 0;

  BroadPhaseBody& addBox(SceneRandom& random, double extent) {
    BroadPhaseBody body;
    body.serial = ++lastSerial;
    body.isStatic = random.uniform(0, 1) < 0.2;
    const Vec3 center(random.uniform(-extent, extent), random.uniform(-extent, extent),
                      random.uniform(0, 2 * extent));
    const Vec3 half(random.uniform(0.05, 0.3), random.uniform(0.05, 0.3),
                    random.uniform(0.05, 0.3));
    body.box = Aabb{center - half, center + half};
    bodies.push_back(body);
    velocities.push_back(body.isStatic
                             ? Vec3::Zero()
                             : Vec3(random.uniform(-0.03, 0.03), random.uniform(-0.03, 0.03),
                                    random.uniform(-0.03, 0.03)));
    return bodies.back();
  }
  void addPlane(const Vec3& normal, double offset) {
    BroadPhaseBody body;
    body.serial = ++lastSerial;
    body.isStatic = true;
    body.plane = HalfSpace{normal.normalized(), offset};
    bodies.push_back(body);
    velocities.push_back(Vec3::Zero());
  }
  void renumber() {
    for (std::size_t i = 0; i < bodies.size(); ++i) bodies[i].index = static_cast<int>(i);
  }
  void move() {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (!bodies[i].box) continue;
      bodies[i].box = Aabb{bodies[i].box->min + velocities[i], bodies[i].box->max + velocities[i]};
    }
  }
};

RandomScene makeRandomScene(SceneRandom& random, int boxes, double extent) {
  RandomScene scene;
  scene.addPlane(Vec3::UnitZ(), 0.0);
  for (int i = 0; i < boxes / 2; ++i) scene.addBox(random, extent);
  scene.addPlane(Vec3(1, 0, 1), 0.5 * extent);  // a slope over part of the scene
  for (int i = boxes / 2; i < boxes; ++i) scene.addBox(random, extent);
  scene.renumber();
  return scene;
}

// The definition, pair by pair, O(N²).
std::vector<BodyPair> bruteForcePairs(const std::vector<BroadPhaseBody>& bodies, double margin,
                                      const std::vector<uint64_t>& excluded = {}) {
  std::vector<BodyPair> pairs;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      const BroadPhaseBody& a = bodies[i];
      const BroadPhaseBody& b = bodies[j];
      if (a.isStatic && b.isStatic) continue;
      if ((a.filter.group & b.filter.mask) == 0 || (b.filter.group & a.filter.mask) == 0) continue;
      if (std::find(excluded.begin(), excluded.end(), serialPairKey(a.serial, b.serial)) != excluded.end()) continue;
      bool touch =
          a.box && b.box && a.box->fattened(0.5 * margin).overlaps(b.box->fattened(0.5 * margin));
      for (const auto& [plane, other] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
        if (plane->plane && other->box) {
          touch = touch || lowestAlong(other->box->fattened(0.5 * margin), plane->plane->normal) <=
                               plane->plane->offset + 0.5 * margin;
        }
      }
      if (touch) pairs.push_back({a.index, b.index});
    }
  }
  return pairs;
}

bool sortedBySerial(const std::vector<BodyPair>& pairs, const std::vector<BroadPhaseBody>& bodies) {
  const auto serialOf = [&bodies](int index) {
    return bodies[static_cast<std::size_t>(index)].serial;
  };
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (serialOf(pairs[k].a) >= serialOf(pairs[k].b)) return false;
    if (k > 0) {
      const auto previous = std::pair(serialOf(pairs[k - 1].a), serialOf(pairs[k - 1].b));
      if (!(previous < std::pair(serialOf(pairs[k].a), serialOf(pairs[k].b)))) return false;
    }
  }
  return true;
}

TEST(BroadPhase, PairsEqualBruteForceOnRandomScenes) {
  for (const uint64_t seed : {1u, 2u, 3u}) {
    SceneRandom random(seed);
    RandomScene scene = makeRandomScene(random, 600, 2.0);
    BroadPhase broadPhase(0.05, kContactMargin);
    broadPhase.update(scene.bodies);
    const std::vector<BodyPair> expected = bruteForcePairs(scene.bodies, kContactMargin);
    EXPECT_GT(expected.size(), 100u);
    EXPECT_EQ(broadPhase.pairs(), expected) << "seed " << seed;
    EXPECT_TRUE(sortedBySerial(broadPhase.pairs(), scene.bodies));
  }
}

TEST(BroadPhase, NeverPairsStaticWithStatic) {
  std::vector<BroadPhaseBody> bodies(3);
  for (int i = 0; i < 3; ++i) {
    bodies[static_cast<std::size_t>(i)].serial = i + 1;
    bodies[static_cast<std::size_t>(i)].index = i;
    bodies[static_cast<std::size_t>(i)].isStatic = true;
    bodies[static_cast<std::size_t>(i)].box = Aabb{Vec3::Constant(-1), Vec3::Constant(1)};
  }
  bodies[0].box.reset();
  bodies[0].plane = HalfSpace{};
  BroadPhase broadPhase;
  broadPhase.update(bodies);
  EXPECT_TRUE(broadPhase.pairs().empty());
  bodies[2].isStatic = false;  // now the third one is dynamic: it meets both
  broadPhase.update(bodies);
  EXPECT_EQ(broadPhase.pairs(), (std::vector<BodyPair>{{0, 2}, {1, 2}}));
}

TEST(BroadPhase, PairsAPlaneOnlyWithBodiesThatReachIt) {
  std::vector<BroadPhaseBody> bodies(3);
  bodies[0] = {1, 0, true, std::nullopt, HalfSpace{Vec3::UnitZ(), 0.0}, CollisionFilter{}};
  bodies[1] = {2, 1, false, Aabb{Vec3(0, 0, 0.004), Vec3(1, 1, 1)}, std::nullopt, CollisionFilter{}};  // within 5 mm
  bodies[2] = {3, 2, false, Aabb{Vec3(0, 0, 0.006), Vec3(1, 1, 1)}, std::nullopt, CollisionFilter{}};  // beyond
  BroadPhase broadPhase(0.05, kContactMargin);
  broadPhase.update(bodies);
  // The two boxes overlap each other, and only the first reaches the ground.
  EXPECT_EQ(broadPhase.pairs(), (std::vector<BodyPair>{{0, 1}, {1, 2}}));
}

TEST(BroadPhase, StaysEqualToBruteForceWhileBodiesMove) {
  SceneRandom random(7);
  RandomScene scene = makeRandomScene(random, 400, 1.5);
  BroadPhase broadPhase(0.05, kContactMargin);
  int moved = 0;
  for (int update = 0; update < 120; ++update) {
    broadPhase.update(scene.bodies);
    ASSERT_EQ(broadPhase.pairs(), bruteForcePairs(scene.bodies, kContactMargin))
        << "update " << update;
    ASSERT_TRUE(broadPhase.tree().isValid());
    if (update > 0) moved += broadPhase.movedProxyCount();
    scene.move();
  }
  // Steps of at most 3 cm against a 5 cm margin: most updates move no proxy.
  EXPECT_LT(moved, 119 * 400 / 4);
}

TEST(BroadPhase, RepeatedUpdatesOfTheSameStateGiveTheSamePairsAndMoveNothing) {
  SceneRandom random(11);
  RandomScene scene = makeRandomScene(random, 300, 1.5);
  BroadPhase broadPhase(0.05, kContactMargin);
  broadPhase.update(scene.bodies);
  const std::vector<BodyPair> first = broadPhase.pairs();
  for (int i = 0; i < 3; ++i) {
    broadPhase.update(scene.bodies);
    EXPECT_EQ(broadPhase.pairs(), first);
    EXPECT_EQ(broadPhase.movedProxyCount(), 0);
  }
}

TEST(BroadPhase, CorrectAfterRemovingAndAddingBodiesAndIndependentOfHistory) {
  SceneRandom random(23);
  RandomScene scene = makeRandomScene(random, 400, 1.5);
  BroadPhase broadPhase(0.05, kContactMargin);
  for (int round = 0; round < 30; ++round) {
    broadPhase.update(scene.bodies);
    ASSERT_EQ(broadPhase.pairs(), bruteForcePairs(scene.bodies, kContactMargin))
        << "round " << round;
    BroadPhase fresh(0.05, kContactMargin);
    fresh.update(scene.bodies);
    ASSERT_EQ(broadPhase.pairs(), fresh.pairs());

    // Remove a few bodies (planes included, now and then), add a few, move all.
    for (int k = 0; k < 15 && !scene.bodies.empty(); ++k) {
      const auto victim =
          static_cast<std::ptrdiff_t>(random.uniform(0, static_cast<double>(scene.bodies.size())));
      scene.bodies.erase(scene.bodies.begin() + victim);
      scene.velocities.erase(scene.velocities.begin() + victim);
    }
    for (int k = 0; k < 12; ++k) scene.addBox(random, 1.5);
    scene.renumber();
    scene.move();
  }
}

// Groups and masks of a few bits, and pairs excluded at random: the pairs
// are the definition's with the filters applied, whatever the history, and
// a change of filters (a body's, or the excluded set) takes effect at the
// next update.
TEST(BroadPhase, LeavesOutWhatTheFiltersRuleOutWhateverTheHistory) {
  SceneRandom random(41);
  RandomScene scene = makeRandomScene(random, 300, 1.0);
  const auto randomFilter = [&]() {
    CollisionFilter filter;
    filter.group = 1u << static_cast<int>(random.uniform(0, 3));     // one of three categories
    filter.mask = static_cast<uint32_t>(random.uniform(0, 8)) | 1u;  // the ground's and some others
    return filter;
  };
  BroadPhase broadPhase(0.05, kContactMargin);
  std::size_t filteredOut = 0;
  for (int round = 0; round < 20; ++round) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      if (scene.bodies[i].box && random.uniform(0, 1) < 0.3) scene.bodies[i].filter = randomFilter();
    // Exclude about a third of the pairs the filters still allow.
    std::vector<uint64_t> excluded;
    for (const BodyPair& pair : bruteForcePairs(scene.bodies, kContactMargin))
      if (random.uniform(0, 1) < 0.33)
        excluded.push_back(serialPairKey(scene.bodies[static_cast<std::size_t>(pair.a)].serial,
                                         scene.bodies[static_cast<std::size_t>(pair.b)].serial));
    std::sort(excluded.begin(), excluded.end());
    broadPhase.update(scene.bodies, excluded);
    const std::vector<BodyPair> expected = bruteForcePairs(scene.bodies, kContactMargin, excluded);
    ASSERT_EQ(broadPhase.pairs(), expected) << "round " << round;
    filteredOut += bruteForcePairs(scene.bodies, kContactMargin).size() - expected.size();
    BroadPhase fresh(0.05, kContactMargin);
    fresh.update(scene.bodies, excluded);
    ASSERT_EQ(fresh.pairs(), broadPhase.pairs()) << "round " << round;
    scene.move();
  }
  EXPECT_GT(filteredOut, 100u);  // the filters had pairs to leave out
}

TEST(BroadPhase, RebuildsWhenSerialsDoNotFollowOn) {
  SceneRandom random(5);
  RandomScene scene = makeRandomScene(random, 200, 1.0);
  BroadPhase broadPhase(0.05, kContactMargin);
  broadPhase.update(scene.bodies);
  // A body with a serial lower than known ones appears (not what a World does).
  BroadPhaseBody newcomer = scene.bodies[5];
  newcomer.serial = 0;
  newcomer.isStatic = false;
  std::vector<BroadPhaseBody> reordered{newcomer};
  reordered.insert(reordered.end(), scene.bodies.begin(), scene.bodies.end());
  scene.bodies = reordered;
  scene.renumber();
  broadPhase.update(scene.bodies);
  EXPECT_EQ(broadPhase.pairs(), bruteForcePairs(scene.bodies, kContactMargin));
  EXPECT_TRUE(broadPhase.tree().isValid());
}

// The same through a World.
TEST(BroadPhase, FindsThePairsOfAWorld) {
  auto world = World::fromDef(scenes::makePileScene(300, scenes::PileVariant::Settled));
  ASSERT_TRUE(world.ok()) << world.error().message;
  BroadPhase broadPhase(0.05, kContactMargin);
  testing::BodyCopies copies(*world);
  broadPhase.update(copies.bodies());
  // Three layers of 100 columns: the ground with the bottom cube of each
  // column, and each cube with the one on it; columns are 5 cm apart.
  std::vector<BodyPair> expected;
  for (int column = 0; column < 100; ++column) expected.push_back({0, 1 + column});
  for (int i = 1; i <= 200; ++i) expected.push_back({i, i + 100});
  std::sort(expected.begin(), expected.end(), [](const BodyPair& x, const BodyPair& y) {
    return std::pair(x.a, x.b) < std::pair(y.a, y.b);
  });
  EXPECT_EQ(broadPhase.pairs(), expected);

  // Remove a cube in the middle: its pairs go, the others are renumbered.
  ASSERT_TRUE(world->removeBody(world->findBody("box150")));
  copies.update(*world);
  broadPhase.update(copies.bodies());
  for (const BodyPair& pair : broadPhase.pairs()) {
    EXPECT_NE(world->bodies()[static_cast<std::size_t>(pair.a)].name(), "box150");
    EXPECT_NE(world->bodies()[static_cast<std::size_t>(pair.b)].name(), "box150");
  }
  EXPECT_EQ(broadPhase.pairs().size(), expected.size() - 2);
}

}  // namespace
}  // namespace rbsim
