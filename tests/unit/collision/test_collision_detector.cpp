#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "physics/world/contact_detection.h"
#include "rbsim/physics/world.h"
#include "scenes/pile_scene.h"
#include "support/body_copies.h"

namespace rbsim {
namespace {

// Detection of the world's bodies as they are now, on copies of them (a
// World hands out no internal Body).
void detectContacts(CollisionDetector& detector, const World& world) {
  const testing::BodyCopies copies(world);
  detectContacts(detector, copies.bodies(), world.settings());
}

BodyDef groundDef() {
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  return ground;
}

BodyDef boxDef(const std::string& name, const Vec3& position, bool isStatic = false) {
  BodyDef box;
  box.name = name;
  box.shape = BoxShape{Vec3::Constant(0.5)};
  box.position = position;
  box.isStatic = isStatic;
  return box;
}

// Two separate cubes of half-extent `half` centred at x = ±1 m: one mesh of
// two connected components, so a collider of two convex pieces.
MeshShape twinCubes(double half) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (const double cx : {-1.0, 1.0}) {
    const int base = static_cast<int>(mesh->vertices.size());
    for (int i = 0; i < 8; ++i)  // vertex i has (x, y, z) = bits (0, 1, 2) of i
      mesh->vertices.emplace_back(cx + (i & 1 ? half : -half), i & 2 ? half : -half,
                                  i & 4 ? half : -half);
    const int faces[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                              {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    for (const auto& f : faces) mesh->triangles.push_back({base + f[0], base + f[1], base + f[2]});
  }
  return MeshShape{"twin cubes", mesh};
}

TEST(CollisionDetector, ABoxOnTheGroundGivesOneManifoldOfFourPoints) {
  World world;
  ASSERT_TRUE(world.createBody(groundDef()));
  ASSERT_TRUE(world.createBody(boxDef("box", Vec3(0, 0, 0.499))));
  CollisionDetector detector;
  detectContacts(detector, world);
  ASSERT_EQ(detector.contacts().size(), 1u);
  const BodyContact& contact = detector.contacts().front();
  EXPECT_EQ(contact.bodyA, 0);
  EXPECT_EQ(contact.bodyB, 1);
  EXPECT_EQ(contact.manifold.pointCount, 4);
  EXPECT_EQ(detector.contactPointCount(), 4);
  EXPECT_TRUE(contact.manifold.normal.isApprox(Vec3::UnitZ(), 1e-9));  // ground -> box
  for (int i = 0; i < contact.manifold.pointCount; ++i)
    EXPECT_NEAR(contact.manifold.points[static_cast<std::size_t>(i)].depth, 0.001, 1e-9);
}

TEST(CollisionDetector, APlaneSecondInSerialOrderStillGivesANormalFromAToB) {
  World world;
  ASSERT_TRUE(world.createBody(boxDef("box", Vec3(0, 0, 0.499))));
  ASSERT_TRUE(world.createBody(groundDef()));
  CollisionDetector detector;
  detectContacts(detector, world);
  ASSERT_EQ(detector.contacts().size(), 1u);
  const BodyContact& contact = detector.contacts().front();
  EXPECT_EQ(contact.bodyA, 0);  // the box
  EXPECT_TRUE(contact.manifold.normal.isApprox(-Vec3::UnitZ(), 1e-9));
  for (int i = 0; i < contact.manifold.pointCount; ++i) {
    const ContactPoint& point = contact.manifold.points[static_cast<std::size_t>(i)];
    EXPECT_GT(point.pointB.z(),
              point.pointA.z());  // A (the box) reaches below the ground's surface
  }
}

TEST(CollisionDetector, SkipsStaticPairsAndSeparatedBodies) {
  World world;
  ASSERT_TRUE(world.createBody(groundDef()));
  ASSERT_TRUE(world.createBody(boxDef("fixed", Vec3(0, 0, 0.4), true)));  // static in the ground
  ASSERT_TRUE(world.createBody(boxDef("flying", Vec3(3, 0, 2))));
  CollisionDetector detector;
  detectContacts(detector, world);
  EXPECT_TRUE(detector.contacts().empty());
}

TEST(CollisionDetector, TheSettledPileGivesOneFourPointManifoldPerRestingFaceInOrder) {
  auto world = World::fromDef(scenes::makePileScene(300, scenes::PileVariant::Settled));
  ASSERT_TRUE(world.ok()) << world.error().message;
  CollisionDetector detector;
  detectContacts(detector, *world);
  // 100 cubes on the ground, 200 on other cubes.
  ASSERT_EQ(detector.contacts().size(), 300u);
  EXPECT_EQ(detector.contactPointCount(), 1200);
  for (std::size_t k = 1; k < detector.contacts().size(); ++k) {
    const BodyContact& p = detector.contacts()[k - 1];
    const BodyContact& c = detector.contacts()[k];
    EXPECT_LT(std::tuple(p.bodyA, p.bodyB, p.pieceA, p.pieceB),
              std::tuple(c.bodyA, c.bodyB, c.pieceA, c.pieceB));
  }
  for (const BodyContact& contact : detector.contacts())
    EXPECT_TRUE(contact.manifold.normal.isApprox(Vec3::UnitZ(), 1e-9));

  // Detecting again on the same state gives the same contacts.
  const std::vector<BodyContact> first = detector.contacts();
  detectContacts(detector, *world);
  ASSERT_EQ(detector.contacts().size(), first.size());
  for (std::size_t k = 0; k < first.size(); ++k) {
    EXPECT_EQ(detector.contacts()[k].bodyA, first[k].bodyA);
    EXPECT_EQ(detector.contacts()[k].bodyB, first[k].bodyB);
    EXPECT_EQ(detector.contacts()[k].manifold.normal, first[k].manifold.normal);
  }
}

TEST(CollisionDetector, ComparesOnlyThePiecesOfCompoundsThatMeet) {
  World world;
  ASSERT_TRUE(world.createBody(groundDef()));
  BodyDef twin;
  twin.name = "twin";
  twin.shape = twinCubes(0.25);
  twin.position = Vec3(0, 0, 0.249);
  const auto twinId = world.createBody(twin);
  ASSERT_TRUE(twinId) << twinId.error().message;
  ASSERT_EQ(world.body(*twinId).description().collider->pieces.size(), 2u);
  BodyDef small = boxDef("small", Vec3(1, 0, 0.25 + 0.1 - 0.001));
  small.shape = BoxShape{Vec3::Constant(0.1)};
  ASSERT_TRUE(world.createBody(small));

  CollisionDetector detector;
  detectContacts(detector, world);
  // Both cubes of the twin on the ground; the small box on one of them only.
  ASSERT_EQ(detector.contacts().size(), 3u);
  const auto& contacts = detector.contacts();
  EXPECT_EQ(
      std::tuple(contacts[0].bodyA, contacts[0].bodyB, contacts[0].pieceA, contacts[0].pieceB),
      std::tuple(0, 1, 0, 0));
  EXPECT_EQ(
      std::tuple(contacts[1].bodyA, contacts[1].bodyB, contacts[1].pieceA, contacts[1].pieceB),
      std::tuple(0, 1, 0, 1));
  EXPECT_EQ(std::tuple(contacts[2].bodyA, contacts[2].bodyB, contacts[2].pieceB),
            std::tuple(1, 2, 0));
  const Collider& collider = *world.body(*twinId).description().collider;
  const int touched = contacts[2].pieceA;
  EXPECT_GT(collider.pieces[static_cast<std::size_t>(touched)].bounds.center().x(), 0.0);
  for (const BodyContact& contact : contacts) EXPECT_EQ(contact.manifold.pointCount, 4);
}

// A convex mesh of `count` random points on a sphere of radius `radius`.
MeshShape randomConvexMesh(std::mt19937_64& random, int count, double radius) {
  std::normal_distribution<double> gauss;
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i)
    points.push_back(radius * Vec3(gauss(random), gauss(random), gauss(random)).normalized());
  auto mesh = convexHullMesh(points, "random mesh");
  EXPECT_TRUE(static_cast<bool>(mesh));
  return MeshShape{"random mesh", std::make_shared<TriangleMesh>(std::move(mesh).value())};
}

// What the narrow phase keeps of hull pairs between steps (their last
// separating direction) never changes its answer: a detector that keeps it
// and a new detector each step give the same contacts, bit for bit, along a
// pile of many-vertex mesh bodies falling and settling.
TEST(CollisionDetector, KeptSeparationsGiveTheContactsOfAFreshDetectorBitForBit) {
  std::mt19937_64 random(35);
  World world;
  ASSERT_TRUE(world.createBody(groundDef()));
  for (int i = 0; i < 12; ++i) {
    BodyDef body;
    body.name = "rock" + std::to_string(i);
    body.shape = randomConvexMesh(random, 150, 0.1);
    body.position = Vec3(0.21 * (i % 3), 0.21 * ((i / 3) % 2), 0.15 + 0.22 * (i / 6));
    body.angularVelocity = Vec3(0.3 * i, -0.2 * i, 0.1);
    ASSERT_TRUE(world.createBody(body));
  }
  CollisionDetector kept;
  std::size_t keptTotal = 0;
  std::size_t contactTotal = 0;
  for (int step = 0; step < 300; ++step) {
    world.step();
    const testing::BodyCopies copies(world);
    detectContacts(kept, copies.bodies(), world.settings());
    CollisionDetector fresh;
    detectContacts(fresh, copies.bodies(), world.settings());
    const std::vector<BodyContact>& a = kept.contacts();
    const std::vector<BodyContact>& b = fresh.contacts();
    ASSERT_EQ(a.size(), b.size()) << "step " << step;
    for (std::size_t k = 0; k < a.size(); ++k) {
      ASSERT_EQ(a[k].bodyA, b[k].bodyA);
      ASSERT_EQ(a[k].bodyB, b[k].bodyB);
      ASSERT_EQ(a[k].pieceA, b[k].pieceA);
      ASSERT_EQ(a[k].pieceB, b[k].pieceB);
      ASSERT_EQ(a[k].manifold.pointCount, b[k].manifold.pointCount) << "step " << step;
      ASSERT_EQ(a[k].manifold.normal, b[k].manifold.normal) << "step " << step;
      for (int p = 0; p < a[k].manifold.pointCount; ++p) {
        const ContactPoint& x = a[k].manifold.points[static_cast<std::size_t>(p)];
        const ContactPoint& y = b[k].manifold.points[static_cast<std::size_t>(p)];
        ASSERT_EQ(x.pointA, y.pointA);
        ASSERT_EQ(x.pointB, y.pointB);
        ASSERT_EQ(x.depth, y.depth);
        ASSERT_EQ(x.featureId, y.featureId);
      }
    }
    keptTotal += kept.keptSeparationCount();
    contactTotal += a.size();
  }
  // The comparison means something only if both were exercised.
  EXPECT_GT(keptTotal, 300u);
  EXPECT_GT(contactTotal, 300u);
}

// Filtered pairs never reach the narrow phase: the detector collides only
// the broad phase's pairs (collideRun walks pairs() and nothing else), and
// those leave out what the bodies' groups and masks, and the excluded pairs
// (a joint's, a robot's), rule out.
TEST(CollisionDetector, FilteredPairsNeverReachTheNarrowPhase) {
  World world;
  ASSERT_TRUE(world.createBody(groundDef()));
  // A column of four boxes, each 2 cm into the next; the top one's mask
  // leaves out the group of the one under it.
  for (int i = 0; i < 4; ++i) {
    BodyDef box = boxDef("box" + std::to_string(i), Vec3(0, 0, 0.49 + 0.98 * i));
    if (i == 2) box.collisionFilter = {2, CollisionFilter::kAllBits};
    if (i == 3) box.collisionFilter = {1, ~2u};
    ASSERT_TRUE(world.createBody(box));
  }
  const testing::BodyCopies copies(world);
  const auto serial = [&](const char* name) { return world.body(world.findBody(name)).serial(); };
  const auto pairsOf = [&](const CollisionDetector& detector) {
    std::vector<std::pair<int32_t, int32_t>> pairs;
    for (const BodyPair& pair : detector.broadPhase().pairs())
      pairs.emplace_back(copies.bodies()[static_cast<std::size_t>(pair.a)].serial(),
                         copies.bodies()[static_cast<std::size_t>(pair.b)].serial());
    return pairs;
  };
  const auto contactPairsOf = [&](const CollisionDetector& detector) {
    std::vector<std::pair<int32_t, int32_t>> pairs;
    for (const BodyContact& contact : detector.contacts())
      pairs.emplace_back(copies.bodies()[static_cast<std::size_t>(contact.bodyA)].serial(),
                         copies.bodies()[static_cast<std::size_t>(contact.bodyB)].serial());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
  };
  TaskPool caller(1);
  DetectionStep step = detectionStep(world.settings());

  CollisionDetector unfiltered;
  step.excludedPairs = {};
  unfiltered.detect(copies.bodies(), step, caller);
  // The ground with box0, then box0-box1, box1-box2; box2-box3 is filtered.
  using Pairs = std::vector<std::pair<int32_t, int32_t>>;
  const Pairs column{{serial("ground"), serial("box0")}, {serial("box0"), serial("box1")},
                     {serial("box1"), serial("box2")}};
  EXPECT_EQ(pairsOf(unfiltered), column);
  EXPECT_EQ(contactPairsOf(unfiltered), column);

  // Exclude box0-box1 (as a joint between them would).
  const std::vector<uint64_t> excluded{serialPairKey(serial("box1"), serial("box0"))};
  CollisionDetector filtered;
  step.excludedPairs = excluded;
  filtered.detect(copies.bodies(), step, caller);
  const Pairs left{{serial("ground"), serial("box0")}, {serial("box1"), serial("box2")}};
  EXPECT_EQ(pairsOf(filtered), left);
  EXPECT_EQ(contactPairsOf(filtered), left);
  // The same detector, the exclusion taken back: the pair is collided anew.
  step.excludedPairs = {};
  filtered.detect(copies.bodies(), step, caller);
  EXPECT_EQ(contactPairsOf(filtered), column);
}

}  // namespace
}  // namespace rbsim
