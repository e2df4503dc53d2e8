// Box manifolds against closed forms: resting, stacked, tilted onto an edge
// or a corner, edges crossing; the reduction to four points; feature ids.
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "physics/collision/polygon_clipping.h"
#include "unit/collision/test_contacts_common.h"

namespace rbsim::testing {
namespace {

const Vec3 kX = Vec3::UnitX();
const Vec3 kY = Vec3::UnitY();
const Vec3 kZ = Vec3::UnitZ();

TEST(BoxPlane, RestingBoxSunkOneMillimetreGivesItsFourBottomCorners) {
  const Solid box = solid(BoxShape{Vec3(0.5, 0.3, 0.2)}, Vec3(1.0, 2.0, 0.2 - 0.001));
  const ContactManifold m = collidePlane(kZ, 0.0, box);
  EXPECT_EQ(m.normal, kZ);
  expectPoints(m,
               {Vec3(0.5, 1.7, -0.001), Vec3(1.5, 1.7, -0.001), Vec3(0.5, 2.3, -0.001),
                Vec3(1.5, 2.3, -0.001)},
               0.001);
}

TEST(BoxPlane, AGapWithinTheMarginGivesNegativeDepthsBeyondItNothing) {
  const ContactManifold near =
      collidePlane(kZ, 0.0, solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.0, 0.0, 0.503)));
  EXPECT_EQ(near.pointCount, 4);
  for (const double depth : sortedDepths(near)) EXPECT_NEAR(depth, -0.003, kTight);
  EXPECT_EQ(
      collidePlane(kZ, 0.0, solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.0, 0.0, 0.506))).pointCount,
      0);
}

TEST(BoxPlane, TiltedOntoAnEdgeGivesTwoPoints) {
  const double angle = kPi / 6;
  const double lowest = 0.5 * (std::sin(angle) + std::cos(angle));
  const Solid box = solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.0, 0.0, lowest - 0.001),
                          rotationAbout(kX, angle));
  const double y = 0.5 * (std::sin(angle) - std::cos(angle));
  expectPoints(collidePlane(kZ, 0.0, box), {Vec3(-0.5, y, -0.001), Vec3(0.5, y, -0.001)}, 0.001);
}

// A large box whose top face is the plane z = 0.
const Solid kFloor = solid(BoxShape{Vec3(2.0, 2.0, 0.5)}, Vec3(0.0, 0.0, -0.5));

TEST(BoxBox, RestingOnALargerBoxGivesFourPoints) {
  const Mat3 yaw = rotationAbout(kZ, 0.35);
  const Solid box = solid(BoxShape{Vec3(0.5, 0.4, 0.3)}, Vec3(0.2, -0.3, 0.3 - 0.001), yaw);
  const ContactManifold m = collide(kFloor, box);
  expectNear(m.normal, kZ, kTight);
  std::vector<Vec3> corners;
  for (const double x : {-0.5, 0.5}) {
    for (const double y : {-0.4, 0.4}) corners.push_back(box.pose.apply(Vec3(x, y, -0.3)));
  }
  expectPoints(m, corners, 0.001);
}

TEST(BoxBox, FaceToFaceCubesOfEqualSizeGiveAFiniteNormalAndFourPoints) {
  // libccd's EPA returns a NaN direction for exactly this (its issue #25).
  const Solid lower = solid(BoxShape{Vec3::Constant(0.5)}, Vec3::Zero());
  for (const double depth : {0.0, 0.002}) {
    const Solid upper = solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.0, 0.0, 1.0 - depth));
    const ContactManifold m = collide(lower, upper);
    EXPECT_EQ(m.normal, kZ);
    expectPoints(m,
                 {Vec3(-0.5, -0.5, 0.5 - depth), Vec3(0.5, -0.5, 0.5 - depth),
                  Vec3(0.5, 0.5, 0.5 - depth), Vec3(-0.5, 0.5, 0.5 - depth)},
                 depth);
    EXPECT_EQ(collide(upper, lower).normal, -kZ);
  }
}

TEST(BoxBox, TiltedOntoAnEdgeGivesTwoPoints) {
  const double angle = kPi / 6;
  const double lowest = 0.5 * (std::sin(angle) + std::cos(angle));
  const Solid box = solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.3, 0.1, lowest - 0.001),
                          rotationAbout(kX, angle));
  const ContactManifold m = collide(kFloor, box);
  expectNear(m.normal, kZ, kTight);
  const double y = 0.1 + 0.5 * (std::sin(angle) - std::cos(angle));
  expectPoints(m, {Vec3(-0.2, y, -0.001), Vec3(0.8, y, -0.001)}, 0.001);
}

TEST(BoxBox, OnOneCornerGivesOnePointWithTheFaceNormal) {
  // Turn the corner (−, −, −) straight down.
  const Mat3 cornerDown = Eigen::Quaterniond::FromTwoVectors(-Vec3::Ones(), -kZ).toRotationMatrix();
  const Solid box = solid(BoxShape{Vec3::Constant(0.5)},
                          Vec3(0.3, 0.1, 0.5 * std::sqrt(3.0) - 0.001), cornerDown);
  const ContactManifold m = collide(kFloor, box);
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, kZ, kTight);  // face–vertex: the face's normal
  expectPoints(m, {Vec3(0.3, 0.1, -0.001)}, 0.001);
}

TEST(BoxBox, CrossingEdgesGiveTheCrossProductOfTheEdgesAndTheirClosestPoints) {
  // A's top edge runs along x at z = √2/2; B's bottom edge along y at
  // x = 0.1, 1 cm lower than that.
  const double depth = 0.01;
  const double half = std::sqrt(0.5);
  const Solid a = solid(BoxShape{Vec3::Constant(0.5)}, Vec3::Zero(), rotationAbout(kX, kPi / 4));
  const Solid b = solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.1, 0.2, 2.0 * half - depth),
                        rotationAbout(kY, kPi / 4));
  const ContactManifold m = collide(a, b);
  ASSERT_EQ(m.pointCount, 1);
  const Vec3 edgeA = a.pose.rotation.col(0);  // the edges' directions
  const Vec3 edgeB = b.pose.rotation.col(1);
  expectNear(m.normal, edgeA.cross(edgeB).normalized(), kTight);
  expectNear(m.normal, kZ, kTight);
  expectPoints(m, {Vec3(0.1, 0.0, half - depth)}, depth);
  EXPECT_NEAR(m.points[0].pointA.z(), half, kTight);
}

TEST(BoxBox, ClippingToAnOctagonIsReducedToFourKeepingTheDeepest) {
  // Equal cubes, the upper one turned 45° about z: its bottom face clipped
  // by the lower one's top face is an octagon. A small tilt about y makes
  // the depth 1 mm + x tan(tilt), so the deepest points sit at x = 0.5.
  const double tilt = 0.002;
  const Mat3 rotation = rotationAbout(kY, tilt) * rotationAbout(kZ, kPi / 4);
  const Solid lower = solid(BoxShape{Vec3::Constant(0.5)}, Vec3::Zero());
  const Solid upper = solid(BoxShape{Vec3::Constant(0.5)},
                            Vec3(0.0, 0.0, 0.5 + 0.5 / std::cos(tilt) - 0.001), rotation);
  const ContactManifold m = collide(lower, upper);
  ASSERT_EQ(m.pointCount, 4);
  expectNear(m.normal, kZ, kTight);
  double deepest = 0.0;
  double leftmost = 1.0;
  for (int i = 0; i < 4; ++i) {
    const ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    EXPECT_NEAR(p.depth, 0.001 + p.pointA.x() * std::tan(tilt), kTight);
    EXPECT_NEAR(std::max(std::abs(p.pointA.x()), std::abs(p.pointA.y())), 0.5, kTight);
    deepest = std::max(deepest, p.depth);
    leftmost = std::min(leftmost, p.pointA.x());
  }
  EXPECT_NEAR(deepest, 0.001 + 0.5 * std::tan(tilt), kTight);
  EXPECT_NEAR(leftmost, -0.5, kTight);  // the point farthest from the deepest
  // The octagon's corners are (±0.5, ±(√2 − 1)/2) and (±(√2 − 1)/2, ±0.5):
  // the deepest, the farthest from it and the two farthest from that
  // diagonal enclose 2 − √2 (the tilt moves them by ~1e-6).
  std::vector<Vec3> quad;
  for (int i = 0; i < 4; ++i) quad.push_back(m.points[static_cast<std::size_t>(i)].pointA);
  std::sort(quad.begin(), quad.end(), [](const Vec3& p, const Vec3& q) {
    return std::atan2(p.y(), p.x()) < std::atan2(q.y(), q.x());
  });
  double area = 0.0;
  for (std::size_t i = 0; i < 4; ++i) area += 0.5 * quad[i].cross(quad[(i + 1) % 4]).z();
  EXPECT_NEAR(area, 2.0 - std::sqrt(2.0), 1e-5);
}

TEST(ReduceContacts, KeepsTheDeepestAndTheLargestQuadrilateral) {
  // A regular hexagon of radius 1, vertex 0 deepest: the best four are 0,
  // its opposite 3, and one vertex on each side: area √3.
  std::vector<ContactPoint> hexagon;
  for (int k = 0; k < 6; ++k) {
    ContactPoint p;
    p.pointB = Vec3(std::cos(k * kPi / 3), std::sin(k * kPi / 3), 0.0);
    p.pointA = p.pointB;
    p.depth = k == 0 ? 0.02 : 0.01;
    p.featureId = static_cast<uint32_t>(k);
    hexagon.push_back(p);
  }
  ContactManifold m;
  reduceContacts(hexagon, kZ, m);
  ASSERT_EQ(m.pointCount, 4);
  std::set<uint32_t> ids;
  for (int i = 0; i < 4; ++i) ids.insert(m.points[static_cast<std::size_t>(i)].featureId);
  EXPECT_TRUE(ids.count(0) == 1 && ids.count(3) == 1);
  EXPECT_TRUE(ids.count(1) + ids.count(2) == 1 && ids.count(4) + ids.count(5) == 1);
}

TEST(ReduceContacts, AFlatPatchKeepsItsPointsWhateverTheirDepthsDifferBy) {
  // An irregular octagon (two squares turned 0.3 rad apart), nearly flat:
  // depths that differ by micrometres, as a soft contact's springs leave
  // them, must not decide which four points are kept, or a resting body's
  // manifold swaps points from one step to the next.
  std::vector<ContactPoint> octagon;
  for (int k = 0; k < 8; ++k) {
    const double angle = k * kPi / 4 + (k % 2 == 0 ? 0.0 : 0.3);
    const double radius = 1.0 + 0.05 * std::sin(2.0 * k);
    ContactPoint p;
    p.pointB = Vec3(radius * std::cos(angle), radius * std::sin(angle), 0.0);
    p.pointA = p.pointB;
    p.featureId = static_cast<uint32_t>(k);
    octagon.push_back(p);
  }
  const auto keptIds = [&](double depthScale, int tilt) {
    for (int k = 0; k < 8; ++k) {
      // Three tilts of the patch: the deepest corner moves around it.
      octagon[static_cast<std::size_t>(k)].depth =
          1e-5 + depthScale * std::cos(k * kPi / 4 - tilt * 2.1);
    }
    ContactManifold m;
    reduceContacts(octagon, kZ, m);
    std::set<uint32_t> ids;
    for (int i = 0; i < m.pointCount; ++i) ids.insert(m.points[static_cast<std::size_t>(i)].featureId);
    return ids;
  };
  const std::set<uint32_t> level = keptIds(0.0, 0);
  ASSERT_EQ(level.size(), 4u);
  for (int tilt = 0; tilt < 3; ++tilt) {
    EXPECT_EQ(keptIds(1e-6, tilt), level) << "tilt " << tilt;
    EXPECT_EQ(keptIds(4e-6, tilt), level) << "tilt " << tilt;
  }
  // A patch tilted by more than the flat spread (10 µm) keeps its deepest point.
  for (int tilt = 0; tilt < 3; ++tilt) {
    const std::set<uint32_t> ids = keptIds(1e-3, tilt);
    const auto deepest = std::max_element(octagon.begin(), octagon.end(), [](const ContactPoint& a, const ContactPoint& b) {
      return a.depth < b.depth;
    });
    EXPECT_EQ(ids.count(deepest->featureId), 1u) << "tilt " << tilt;
  }
}

TEST(BoxBox, FeatureIdsPersistWhileTheBoxSlidesAndAreDistinct) {
  const auto ids = [](const ContactManifold& m) {
    std::set<uint32_t> result;
    for (int i = 0; i < m.pointCount; ++i) {
      result.insert(m.points[static_cast<std::size_t>(i)].featureId);
    }
    return result;
  };
  const Mat3 yaw = rotationAbout(kZ, 0.3);
  const ContactManifold before =
      collide(kFloor, solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.0, 0.0, 0.499), yaw));
  const ContactManifold after =
      collide(kFloor, solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.01, 0.002, 0.4985), yaw));
  ASSERT_EQ(before.pointCount, 4);
  EXPECT_EQ(ids(before).size(), 4u);
  EXPECT_EQ(ids(before), ids(after));

  // An overhanging box, whose points are cuts of its face by the floor's
  // sides, keeps its ids too.
  const ContactManifold overhangBefore =
      collide(kFloor, solid(BoxShape{Vec3::Constant(0.5)}, Vec3(1.8, 0.0, 0.499), yaw));
  const ContactManifold overhangAfter =
      collide(kFloor, solid(BoxShape{Vec3::Constant(0.5)}, Vec3(1.81, 0.01, 0.499), yaw));
  EXPECT_EQ(ids(overhangBefore).size(), static_cast<std::size_t>(overhangBefore.pointCount));
  EXPECT_EQ(ids(overhangBefore), ids(overhangAfter));
}

TEST(BoxBox, SwappingTheBoxesFlipsTheNormalAndKeepsTheDepths) {
  const Solid a = solid(BoxShape{Vec3(0.6, 0.4, 0.3)}, Vec3(0.0, 0.0, 0.0),
                        rotationAbout(Vec3(1.0, 1.0, 0.0), 0.2));
  const Solid b = solid(BoxShape{Vec3(0.3, 0.5, 0.2)}, Vec3(0.1, 0.2, 0.52),
                        rotationAbout(Vec3(0.0, 1.0, 1.0), 0.4));
  expectSymmetric(a, b);
  expectSymmetric(kFloor, solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.2, 0.0, 0.499)));
}

TEST(BoxBox, ApartByMoreThanTheMarginGivesNothing) {
  EXPECT_EQ(collide(kFloor, solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.0, 0.0, 0.506))).pointCount,
            0);
  const ContactManifold near =
      collide(kFloor, solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.0, 0.0, 0.504)));
  ASSERT_EQ(near.pointCount, 4);
  EXPECT_NEAR(near.points[0].depth, -0.004, kTight);
}

}  // namespace
}  // namespace rbsim::testing
