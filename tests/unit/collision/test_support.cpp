// Support functions and bounds of the convex geometries, against the closed
// forms of their support functions h(d) = max over the solid of d·x.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry_test_helpers.h"
#include "physics/collision/convex_geometry.h"

namespace rbsim {
namespace {

using testing::randomUnit;

double hullSupportValue(const ConvexHull& hull, const Vec3& d) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Vec3& v : hull.vertices) best = std::max(best, d.dot(v));
  return best;
}

// h(d) for each shape, written from its definition.
double supportValue(const ConvexGeometry& geometry, const Vec3& d) {
  const double radial = std::hypot(d.x(), d.y());
  if (const auto* s = std::get_if<SphereShape>(&geometry)) return s->radius * d.norm();
  if (const auto* b = std::get_if<BoxShape>(&geometry)) return b->halfExtents.dot(d.cwiseAbs());
  if (const auto* c = std::get_if<CapsuleShape>(&geometry))
    return c->halfLength * std::abs(d.z()) + c->radius * d.norm();
  if (const auto* c = std::get_if<CylinderShape>(&geometry))
    return c->halfLength * std::abs(d.z()) + c->radius * radial;
  return hullSupportValue(*std::get<std::shared_ptr<const ConvexHull>>(geometry), d);
}

// Whether x belongs to the solid (with a tolerance).
bool contains(const ConvexGeometry& geometry, const Vec3& x, double tol = 1e-12) {
  if (const auto* s = std::get_if<SphereShape>(&geometry)) return x.norm() <= s->radius + tol;
  if (const auto* b = std::get_if<BoxShape>(&geometry))
    return (x.cwiseAbs() - b->halfExtents).maxCoeff() <= tol;
  if (const auto* c = std::get_if<CapsuleShape>(&geometry)) {
    const Vec3 core(0, 0, std::clamp(x.z(), -c->halfLength, c->halfLength));
    return (x - core).norm() <= c->radius + tol;
  }
  if (const auto* c = std::get_if<CylinderShape>(&geometry))
    return std::hypot(x.x(), x.y()) <= c->radius + tol && std::abs(x.z()) <= c->halfLength + tol;
  return testing::insideHull(*std::get<std::shared_ptr<const ConvexHull>>(geometry), Transform{}, x,
                             tol);
}

std::vector<ConvexGeometry> allGeometries() {
  scenes::SceneRandom random(3);
  return {SphereShape{0.7}, BoxShape{Vec3(0.5, 1.0, 0.25)}, CapsuleShape{0.3, 0.8},
          CylinderShape{0.4, 0.9},
          testing::hullOf(testing::randomPoints(random, 30, Vec3(1.0, 0.5, 0.7)))};
}

TEST(Support, MatchesTheClosedFormSupportFunction) {
  scenes::SceneRandom random(5);
  for (const auto& geometry : allGeometries()) {
    for (int i = 0; i < 200; ++i) {
      const Vec3 d = randomUnit(random) * random.uniform(0.01, 10.0);
      const Vec3 s = supportPoint(geometry, d);
      EXPECT_TRUE(contains(geometry, s)) << s.transpose();
      EXPECT_NEAR(d.dot(s), supportValue(geometry, d), 1e-12 * d.norm());
    }
    // Axis-aligned directions are where ties (box faces, cylinder caps) sit.
    for (int axis = 0; axis < 3; ++axis) {
      for (double sign : {-1.0, 1.0}) {
        const Vec3 d = sign * Vec3::Unit(axis);
        EXPECT_NEAR(d.dot(supportPoint(geometry, d)), supportValue(geometry, d), 1e-12);
      }
    }
  }
}

TEST(Support, ZeroAndNanDirectionsGiveAFinitePointOfTheSolid) {
  for (const auto& geometry : allGeometries()) {
    for (const Vec3& d :
         {Vec3(Vec3::Zero()), Vec3(std::nan(""), 0.0, 1.0), Vec3(Vec3::Constant(std::nan("")))}) {
      const Vec3 s = supportPoint(geometry, d);
      EXPECT_TRUE(s.allFinite());
      EXPECT_TRUE(contains(geometry, s));
      EXPECT_TRUE(coreSupportPoint(geometry, d).allFinite());
    }
  }
}

TEST(Support, CoresOfSphereAndCapsuleArePointAndSegment) {
  scenes::SceneRandom random(9);
  const SphereShape sphere{0.7};
  const CapsuleShape capsule{0.3, 0.8};
  EXPECT_EQ(coreRadius(sphere), 0.7);
  EXPECT_EQ(coreRadius(capsule), 0.3);
  EXPECT_EQ(coreRadius(BoxShape{}), 0.0);
  EXPECT_EQ(coreRadius(CylinderShape{}), 0.0);
  for (int i = 0; i < 50; ++i) {
    const Vec3 d = randomUnit(random);
    EXPECT_EQ(coreSupportPoint(sphere, d), Vec3::Zero());
    EXPECT_EQ(coreSupportPoint(capsule, d), Vec3(0, 0, d.z() >= 0 ? 0.8 : -0.8));
    // The solid is its core grown by the radius: s(d) = core(d) + r d/|d|.
    EXPECT_NEAR((supportPoint(capsule, d) - coreSupportPoint(capsule, d) - 0.3 * d).norm(), 0.0,
                1e-15);
    const BoxShape box{Vec3(1, 2, 3)};
    EXPECT_EQ(coreSupportPoint(box, d), supportPoint(box, d));
  }
}

TEST(Support, LocalBoundsOfEachShape) {
  const auto expectBox = [](const Aabb& box, const Vec3& lo, const Vec3& hi) {
    EXPECT_NEAR((box.min - lo).norm(), 0.0, 1e-15) << box.min.transpose();
    EXPECT_NEAR((box.max - hi).norm(), 0.0, 1e-15) << box.max.transpose();
  };
  expectBox(geometryBounds(SphereShape{0.7}), Vec3::Constant(-0.7), Vec3::Constant(0.7));
  expectBox(geometryBounds(BoxShape{Vec3(1, 2, 3)}), Vec3(-1, -2, -3), Vec3(1, 2, 3));
  expectBox(geometryBounds(CapsuleShape{0.3, 0.8}), Vec3(-0.3, -0.3, -1.1), Vec3(0.3, 0.3, 1.1));
  expectBox(geometryBounds(CylinderShape{0.4, 0.9}), Vec3(-0.4, -0.4, -0.9), Vec3(0.4, 0.4, 0.9));
  const auto hull = testing::hullOf({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0), Vec3(0, 0, -1)});
  expectBox(geometryBounds(hull), Vec3(0, 0, -1), Vec3(2, 3, 0));
  EXPECT_NEAR(geometrySize(BoxShape{Vec3(1, 2, 2)}), 3.0, 1e-15);
  EXPECT_TRUE(contains(hull, interiorPoint(hull), -1e-6)) << "strictly inside";
}

TEST(Support, PlacedBoundsAreTightForRotatedShapes) {
  scenes::SceneRandom random(13);
  for (int trial = 0; trial < 20; ++trial) {
    const Transform pose = Transform::fromPose(
        Vec3(random.uniform(-5, 5), random.uniform(-5, 5), 1.0), random.rotation());
    const Mat3& r = pose.rotation;
    const Vec3& c = pose.translation;
    const Vec3 axis = r.col(2);
    // Closed forms: Arvo's |R| h for a box; a sphere keeps its radius; a
    // capsule is its end points grown by r; a cylinder's rim circle spans
    // R·sqrt(1 − a_i²) along axis i.
    const Vec3 h(0.5, 1.0, 0.25);
    const Vec3 boxHalf = r.cwiseAbs() * h;
    const Vec3 capsuleHalf = 0.8 * axis.cwiseAbs() + Vec3::Constant(0.3);
    Vec3 cylinderHalf;
    for (int i = 0; i < 3; ++i)
      cylinderHalf[i] = 0.9 * std::abs(axis[i]) + 0.4 * std::sqrt(1.0 - axis[i] * axis[i]);
    const std::vector<std::pair<ConvexGeometry, Vec3>> cases = {
        {SphereShape{0.7}, Vec3::Constant(0.7)},
        {BoxShape{h}, boxHalf},
        {CapsuleShape{0.3, 0.8}, capsuleHalf},
        {CylinderShape{0.4, 0.9}, cylinderHalf}};
    for (const auto& [geometry, half] : cases) {
      const Aabb box = placedBounds(geometry, pose);
      EXPECT_NEAR((box.min - (c - half)).norm(), 0.0, 1e-12);
      EXPECT_NEAR((box.max - (c + half)).norm(), 0.0, 1e-12);
    }
    // A hull: the box of its transformed vertices.
    const auto hull = testing::hullOf(testing::randomPoints(random, 20, Vec3::Ones()));
    Aabb expected;
    for (const Vec3& v : hull->vertices) expected.include(pose.apply(v));
    const Aabb box = placedBounds(hull, pose);
    EXPECT_NEAR((box.min - expected.min).norm(), 0.0, 1e-12);
    EXPECT_NEAR((box.max - expected.max).norm(), 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace rbsim
