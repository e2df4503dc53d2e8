// The bounded hull–hull search (collideHulls on hulls of many edges) against
// the exhaustive separating-axis test it replaces, on random pairs, and
// against closed forms on hand-worked pairs of many-vertex hulls.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "physics/collision/box_features.h"
#include "physics/collision/contact_routines.h"
#include "physics/collision/convex_hull.h"
#include "physics/collision/gjk.h"
#include "test_contacts_common.h"

namespace rbsim::testing {
namespace {

constexpr double kMargin = 0.005;  // m: the default contact margin

// A hull of `count` random points on an ellipsoid with semi-axes `axes`.
std::shared_ptr<const ConvexHull> randomHull(std::mt19937_64& random, int count,
                                             const Vec3& axes) {
  std::normal_distribution<double> gauss;
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    const Vec3 direction = Vec3(gauss(random), gauss(random), gauss(random)).normalized();
    points.push_back(direction.cwiseProduct(axes));
  }
  auto hull = buildConvexHull(points, "random hull");
  EXPECT_TRUE(static_cast<bool>(hull));
  return std::make_shared<const ConvexHull>(std::move(hull).value());
}

Mat3 randomRotation(std::mt19937_64& random) {
  std::normal_distribution<double> gauss;
  return Eigen::Quaterniond(gauss(random), gauss(random), gauss(random), gauss(random))
      .normalized()
      .toRotationMatrix();
}

// How far apart the two placed hulls are along the unit `direction`
// (from A to B): min over B of d·y minus max over A of d·x.
double separationAlong(const ConvexHull& a, const Transform& poseA, const ConvexHull& b,
                       const Transform& poseB, const Vec3& direction) {
  double highestA = -INFINITY;
  for (const Vec3& v : a.vertices) highestA = std::max(highestA, direction.dot(poseA.apply(v)));
  double lowestB = INFINITY;
  for (const Vec3& v : b.vertices) lowestB = std::min(lowestB, direction.dot(poseB.apply(v)));
  return lowestB - highestA;
}

struct PairResult {
  ContactManifold bounded;
  ContactManifold exhaustive;
  bool boundedTouching = false;
  bool exhaustiveTouching = false;
};

PairResult collideBothWays(const ConvexHull& a, const Transform& poseA, const ConvexHull& b,
                           const Transform& poseB) {
  PairResult result;
  const ContactSettings settings{kMargin};
  result.boundedTouching = collideHulls(a, poseA, b, poseB, settings, result.bounded);
  result.exhaustiveTouching =
      collideHullsExhaustive(a, poseA, b, poseB, settings, result.exhaustive);
  return result;
}

double gjkDistanceOf(const std::shared_ptr<const ConvexHull>& a, const Transform& poseA,
                     const std::shared_ptr<const ConvexHull>& b, const Transform& poseB) {
  const ConvexGeometry geometryA = a;
  const ConvexGeometry geometryB = b;
  return gjkDistance({&geometryA, poseA}, {&geometryB, poseB}).distance;
}

struct Tally {
  int pairs = 0;
  int touching = 0;
  int boundedOnlyApart = 0;  // the exhaustive test's speculative points of a pair beyond the margin
};

// Places B along a random direction from A so that the hulls are `gap`
// apart along it, in a random orientation, and compares the two paths.
void compareRandomPair(std::mt19937_64& random, const std::shared_ptr<const ConvexHull>& a,
                       const std::shared_ptr<const ConvexHull>& b, double gap, Tally& tally) {
  std::normal_distribution<double> gauss;
  const Transform poseA{randomRotation(random), Vec3(gauss(random), gauss(random), gauss(random))};
  const Mat3 rotationB = randomRotation(random);
  const Vec3 direction = Vec3(gauss(random), gauss(random), gauss(random)).normalized();
  Transform poseB{rotationB, poseA.translation};
  poseB.translation += (gap - separationAlong(*a, poseA, *b, poseB, direction)) * direction;

  const PairResult result = collideBothWays(*a, poseA, *b, poseB);
  ++tally.pairs;
  const std::string where = "gap " + std::to_string(gap) + ", hulls of " +
                            std::to_string(a->vertices.size()) + " and " +
                            std::to_string(b->vertices.size()) + " vertices";
  if (result.exhaustiveTouching && !result.boundedTouching) {
    // The one difference allowed: the exhaustive test can keep a point
    // within the margin along a face normal of a pair whose nearest
    // features are farther apart than the margin. GJK must show that.
    EXPECT_GT(gjkDistanceOf(a, poseA, b, poseB), kMargin) << where;
    ++tally.boundedOnlyApart;
    return;
  }
  ASSERT_EQ(result.boundedTouching, result.exhaustiveTouching) << where;
  // Hulls that overlap always touch (on hulls of many small faces the
  // face chosen with hysteresis can miss the other hull's deepest part;
  // the contact then comes from the next feature).
  if (gjkDistanceOf(a, poseA, b, poseB) == 0.0) EXPECT_TRUE(result.exhaustiveTouching) << where;
  if (!result.exhaustiveTouching) return;
  ++tally.touching;
  ASSERT_EQ(result.bounded.pointCount, result.exhaustive.pointCount) << where;
  expectNear(result.bounded.normal, result.exhaustive.normal, 1e-9);
  for (int i = 0; i < result.exhaustive.pointCount; ++i) {
    const ContactPoint& want = result.exhaustive.points[static_cast<std::size_t>(i)];
    const ContactPoint& got = result.bounded.points[static_cast<std::size_t>(i)];
    EXPECT_NEAR(got.depth, want.depth, 1e-9) << where;
    expectNear(got.pointA, want.pointA, 1e-9);
    expectNear(got.pointB, want.pointB, 1e-9);
    EXPECT_EQ(got.featureId, want.featureId) << where;
  }
}

TEST(HullSearch, AgreesWithTheExhaustiveTestOnRandomPairs) {
  std::mt19937_64 random(20261207);
  // Gaps along a random direction, m: apart beyond the margin, within it,
  // and overlapping (the true separation is at least the gap).
  const std::vector<double> gaps = {0.02, 0.004, 0.001, -0.0002, -0.002, -0.01, -0.03};
  Tally tally;
  for (const int count : {40, 120, 300}) {
    for (int trial = 0; trial < 100; ++trial) {
      const auto a = randomHull(random, count, Vec3(0.1, 0.07, 0.05));
      const auto b = randomHull(random, count, Vec3(0.06, 0.08, 0.1));
      for (const double gap : gaps) compareRandomPair(random, a, b, gap, tally);
    }
  }
  // A few at the size of a robot link's mesh: the exhaustive test is slow there.
  for (int trial = 0; trial < 6; ++trial) {
    const auto a = randomHull(random, 576, Vec3(0.1, 0.1, 0.2));
    const auto b = randomHull(random, 576, Vec3(0.08, 0.12, 0.1));
    for (const double gap : gaps) compareRandomPair(random, a, b, gap, tally);
  }
  // A box against a many-vertex hull takes the bounded search too.
  for (int trial = 0; trial < 60; ++trial) {
    const auto a = std::make_shared<const ConvexHull>(boxHull(Vec3(0.2, 0.1, 0.05)));
    const auto b = randomHull(random, 200, Vec3(0.05, 0.08, 0.06));
    for (const double gap : gaps) compareRandomPair(random, a, b, gap, tally);
  }
  // Most pairs of the gaps within the margin must touch, or the test shows little.
  EXPECT_GT(tally.touching, tally.pairs / 3);
  // The allowed difference is rare.
  EXPECT_LT(tally.boundedOnlyApart, tally.pairs / 50);
  RecordProperty("pairs", tally.pairs);
  RecordProperty("touching", tally.touching);
}

// A hull of a sphere of radius r: `rings` latitude rings of `segments`
// points, and the two poles.
std::shared_ptr<const ConvexHull> sphereHull(double radius, int rings, int segments) {
  std::vector<Vec3> points = {Vec3(0, 0, radius), Vec3(0, 0, -radius)};
  for (int i = 1; i <= rings; ++i) {
    const double polar = kPi * i / (rings + 1);
    for (int j = 0; j < segments; ++j) {
      const double azimuth = 2.0 * kPi * (j + 0.5 * (i % 2)) / segments;
      points.push_back(radius * Vec3(std::sin(polar) * std::cos(azimuth),
                                     std::sin(polar) * std::sin(azimuth), std::cos(polar)));
    }
  }
  auto hull = buildConvexHull(points, "sphere hull");
  EXPECT_TRUE(static_cast<bool>(hull));
  return std::make_shared<const ConvexHull>(std::move(hull).value());
}

TEST(HullSearch, SphereHullOnABoxTouchesAtItsPole) {
  // 23 rings of 25 points and the poles: 577 vertices. Its lowest point is
  // the south pole, so resting on the box's top face (z = 0.05) with its
  // centre at 0.05 + r − depth the pole sinks by depth; the incident face
  // is a triangle of the pole and two vertices of the lowest ring, which
  // sit r (1 − cos(π/24)) higher and, within the margin, are points too.
  const double radius = 0.1;
  const auto ball = sphereHull(radius, 23, 25);
  ASSERT_EQ(ball->vertices.size(), 577u);
  const double ringRise = radius * (1.0 - std::cos(kPi / 24.0));
  const auto box = std::make_shared<const ConvexHull>(boxHull(Vec3(0.3, 0.2, 0.05)));
  const Transform poseBox{Mat3::Identity(), Vec3::Zero()};
  for (const double depth : {0.003, 0.0, -0.002}) {
    const Vec3 pole(0.01, -0.02, 0.05 - depth);
    const Transform poseBall{Mat3::Identity(), pole + Vec3(0, 0, radius)};
    ContactManifold manifold;
    ASSERT_TRUE(collideHulls(*box, poseBox, *ball, poseBall, ContactSettings{kMargin}, manifold))
        << "depth " << depth;
    ASSERT_EQ(manifold.pointCount, 3);
    expectNear(manifold.normal, Vec3::UnitZ(), kTight);
    const ContactPoint& deepest = nearestPoint(manifold, pole);
    expectNear(deepest.pointB, pole, kTight);
    EXPECT_NEAR(deepest.depth, depth, kTight);
    for (int i = 0; i < manifold.pointCount; ++i) {
      const ContactPoint& point = manifold.points[static_cast<std::size_t>(i)];
      if (&point == &deepest) continue;
      EXPECT_NEAR(point.depth, depth - ringRise, kTight);
      EXPECT_NEAR(point.pointB.z(), 0.05 - depth + ringRise, kTight);
      expectNear(point.pointA, Vec3(point.pointB.x(), point.pointB.y(), 0.05), kTight);
    }
  }
  // Lifted clear of the margin: nothing.
  ContactManifold manifold;
  EXPECT_FALSE(collideHulls(*box, poseBox, *ball,
                            Transform{Mat3::Identity(), Vec3(0, 0, 0.05 + radius + 0.0051)},
                            ContactSettings{kMargin}, manifold));
}

// A prism along x whose cross-section is a regular `sides`-gon of
// circumradius r with a flat side at the top (+z) and bottom (−z), and
// length 2·half.
std::shared_ptr<const ConvexHull> prismAlongX(double radius, int sides, double half) {
  std::vector<Vec3> points;
  for (int k = 0; k < sides; ++k) {
    // A vertex at angle π/2 ± π/sides puts a flat side across the top.
    const double angle = kPi / 2.0 + kPi / sides + 2.0 * kPi * k / sides;
    for (const double x : {-half, half})
      points.push_back(Vec3(x, radius * std::cos(angle), radius * std::sin(angle)));
  }
  auto hull = buildConvexHull(points, "prism");
  EXPECT_TRUE(static_cast<bool>(hull));
  return std::make_shared<const ConvexHull>(std::move(hull).value());
}

TEST(HullSearch, CrossedPrismsTouchOverTheSquareWhereTheirFlatSidesCross) {
  // Two 200-sided prisms (400 vertices each), one along x and one along y
  // above it, flat sides facing: the contact is the crossing square of
  // their flat sides, 2 r sin(π/n) wide, at the depth they overlap.
  const int sides = 200;
  const double radius = 0.05;
  const auto lower = prismAlongX(radius, sides, 0.3);
  const auto upper = prismAlongX(radius, sides, 0.3);
  const double apothem = radius * std::cos(kPi / sides);
  const double halfSide = radius * std::sin(kPi / sides);
  const Mat3 alongY = rotationAbout(Vec3::UnitZ(), kPi / 2.0);
  for (const double depth : {0.0005, 0.002}) {
    const Transform poseLower{Mat3::Identity(), Vec3::Zero()};
    const Transform poseUpper{alongY, Vec3(0, 0, 2.0 * apothem - depth)};
    ContactManifold manifold;
    ASSERT_TRUE(
        collideHulls(*lower, poseLower, *upper, poseUpper, ContactSettings{kMargin}, manifold));
    expectNear(manifold.normal, Vec3::UnitZ(), kTight);
    const double top = apothem;
    expectPoints(manifold,
                 {Vec3(halfSide, halfSide, top - depth), Vec3(-halfSide, halfSide, top - depth),
                  Vec3(-halfSide, -halfSide, top - depth), Vec3(halfSide, -halfSide, top - depth)},
                 depth);
  }
}

}  // namespace
}  // namespace rbsim::testing
