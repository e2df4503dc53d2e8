// Triangle–convex contacts against hand-worked answers: the one-sided rule,
// the closest features, and the internal-edge correction.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/collision/triangle_contacts.h"
#include "physics/collision/triangle_mesh_contacts.h"
#include "unit/collision/triangle_mesh_test_meshes.h"

namespace rbsim {
namespace {

// The triangle (0,0,0), (1,0,0), (0,1,0), front +z, edges as given.
ContactTriangle unitTriangle(uint8_t activeEdges) {
  ContactTriangle t;
  t.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  t.normal = Vec3::UnitZ();
  t.activeEdges = activeEdges;
  return t;
}

ContactSettings margin(double m) {
  ContactSettings settings;
  settings.margin = m;
  return settings;
}

TEST(TriangleContacts, ASphereOverTheFaceTouchesItAlongTheFaceNormal) {
  const ConvexGeometry sphere = SphereShape{0.1};
  ContactManifold out;
  ASSERT_TRUE(collideTriangleConvex(unitTriangle(0x7), {&sphere, Transform{Mat3::Identity(), Vec3(0.25, 0.25, 0.09)}},
                                    margin(0.0), out));
  ASSERT_EQ(out.pointCount, 1);
  EXPECT_EQ(out.normal, Vec3::UnitZ());
  EXPECT_NEAR(out.points[0].depth, 0.01, 1e-15);
  EXPECT_LT((out.points[0].pointA - Vec3(0.25, 0.25, 0.0)).norm(), 1e-15);
  EXPECT_LT((out.points[0].pointB - Vec3(0.25, 0.25, -0.01)).norm(), 1e-15);
}

TEST(TriangleContacts, ASphereBesideAnActiveEdgeTouchesItAlongTheEdgeNormal) {
  // Beside edge 0 (y = 0), at 45° below the face plane's level... above it:
  // centre (0.5, −0.06, 0.08), 0.1 from the edge point (0.5, 0, 0).
  const ConvexGeometry sphere = SphereShape{0.11};
  ContactManifold out;
  ASSERT_TRUE(collideTriangleConvex(unitTriangle(0x7), {&sphere, Transform{Mat3::Identity(), Vec3(0.5, -0.06, 0.08)}},
                                    margin(0.0), out));
  ASSERT_EQ(out.pointCount, 1);
  EXPECT_LT((out.normal - Vec3(0.0, -0.6, 0.8)).norm(), 1e-15);
  EXPECT_NEAR(out.points[0].depth, 0.01, 1e-15);
  EXPECT_LT((out.points[0].pointA - Vec3(0.5, 0.0, 0.0)).norm(), 1e-15);
}

TEST(TriangleContacts, AnInactiveEdgeGivesTheFaceNormalAndLeavesPointsBeyondItToTheNeighbour) {
  const ConvexGeometry sphere = SphereShape{0.11};
  ContactManifold out;
  // The same sphere beside an inactive edge: its lowest point lies beyond
  // the edge (y < 0), over the neighbour, which holds the contact.
  EXPECT_FALSE(collideTriangleConvex(unitTriangle(0x6), {&sphere, Transform{Mat3::Identity(), Vec3(0.5, -0.06, 0.08)}},
                                     margin(0.0), out));
  // Straddling the edge, centre right above it: the face normal.
  ASSERT_TRUE(collideTriangleConvex(unitTriangle(0x6), {&sphere, Transform{Mat3::Identity(), Vec3(0.5, 0.0, 0.1)}},
                                    margin(0.0), out));
  EXPECT_EQ(out.normal, Vec3::UnitZ());
  EXPECT_NEAR(out.points[0].depth, 0.01, 1e-15);
}

TEST(TriangleContacts, NothingTouchesATriangleFromBehind) {
  const ConvexGeometry sphere = SphereShape{0.1};
  const ConvexGeometry box = BoxShape{Vec3(0.1, 0.1, 0.1)};
  ContactManifold out;
  EXPECT_FALSE(collideTriangleConvex(unitTriangle(0x7), {&sphere, Transform{Mat3::Identity(), Vec3(0.25, 0.25, -0.09)}},
                                     margin(0.0), out));
  EXPECT_FALSE(collideTriangleConvex(unitTriangle(0x7), {&box, Transform{Mat3::Identity(), Vec3(0.25, 0.25, -0.09)}},
                                     margin(0.0), out));
  // From the front, the same box touches with its four bottom corners.
  ASSERT_TRUE(collideTriangleConvex(unitTriangle(0x7), {&box, Transform{Mat3::Identity(), Vec3(0.25, 0.25, 0.09)}},
                                    margin(0.0), out));
  EXPECT_EQ(out.normal, Vec3::UnitZ());
  ASSERT_EQ(out.pointCount, 4);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(out.points[static_cast<std::size_t>(k)].depth, 0.01, 1e-15);
}

TEST(TriangleContacts, ABoxPushingUpThroughAFloorFromBelowIsNotPulledThrough) {
  // The box's top 1 cm above an interior floor triangle, its bottom 1 m
  // below: from behind, no contact (correcting its normal onto the
  // front would lift it by a metre).
  const ConvexGeometry box = BoxShape{Vec3(0.1, 0.1, 0.5)};
  ContactManifold out;
  EXPECT_FALSE(collideTriangleConvex(unitTriangle(0x0), {&box, Transform{Mat3::Identity(), Vec3(0.25, 0.25, -0.49)}},
                                     margin(0.0), out));
}

TEST(TriangleContacts, ABoxOverlappingAnInteriorEdgeBySliverIsPushedUpNotSideways) {
  // A 1 m box sunk 1 cm into a flat floor, reaching 2 mm past the
  // triangle's edge x = 0 (its +x face at x = 0.002). Along x the overlap
  // is 2 mm, shallower than the 1 cm along z: the geometry alone says
  // "push the box out along −x" (the ghost collision that makes boxes
  // bump on triangle floors); the floor's edge there is interior.
  const ConvexGeometry box = BoxShape{Vec3(0.5, 0.5, 0.5)};
  const PlacedConvex placed{&box, Transform{Mat3::Identity(), Vec3(-0.498, 0.3, 0.49)}};
  ContactManifold raw;
  ASSERT_TRUE(collideTriangleConvex(unitTriangle(0x0), placed, margin(0.0), raw, false));
  EXPECT_LT((raw.normal - Vec3(-1, 0, 0)).norm(), 1e-15) << "the edge's own normal";

  ContactManifold corrected;
  ASSERT_TRUE(collideTriangleConvex(unitTriangle(0x0), placed, margin(0.0), corrected));
  EXPECT_EQ(corrected.normal, Vec3::UnitZ());
  ASSERT_GE(corrected.pointCount, 1);
  for (int k = 0; k < corrected.pointCount; ++k) {
    EXPECT_NEAR(corrected.points[static_cast<std::size_t>(k)].depth, 0.01, 1e-15);
    EXPECT_LE(corrected.points[static_cast<std::size_t>(k)].pointA.x(), 0.002 + 1e-15);
  }
  // With the edge active (a border), the edge normal stays.
  ContactManifold border;
  ASSERT_TRUE(collideTriangleConvex(unitTriangle(0x4), placed, margin(0.0), border));
  EXPECT_LT((border.normal - Vec3(-1, 0, 0)).norm(), 1e-15);
}

TEST(TriangleContacts, ASphereOnASharedEdgeOfAGridIsOnePointOnce) {
  auto collider = buildTriangleMeshCollider(testing::flatGrid(2, 1.0), Transform::identity(), "grid");
  ASSERT_TRUE(collider);
  const ConvexGeometry sphere = SphereShape{0.1};
  // Right above the grid's centre vertex, where six... four cells meet.
  std::vector<TriangleManifold> found;
  collideTriangleMeshPiece(**collider, Transform::identity(),
                           {&sphere, Transform{Mat3::Identity(), Vec3(0.0, 0.0, 0.09)}}, margin(0.0), found);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].manifold.pointCount, 1);
  EXPECT_EQ(found[0].manifold.normal, Vec3::UnitZ());
  EXPECT_NEAR(found[0].manifold.points[0].depth, 0.01, 1e-15);
}

TEST(TriangleContacts, ACylinderStandingOnATriangleTouchesWithItsCap) {
  const ConvexGeometry cylinder = CylinderShape{0.1, 0.2};
  ContactManifold out;
  ASSERT_TRUE(collideTriangleConvex(unitTriangle(0x7), {&cylinder, Transform{Mat3::Identity(), Vec3(0.3, 0.3, 0.19)}},
                                    margin(0.0), out));
  EXPECT_LT((out.normal - Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_GE(out.pointCount, 3);
  for (int k = 0; k < out.pointCount; ++k) EXPECT_NEAR(out.points[static_cast<std::size_t>(k)].depth, 0.01, 1e-9);
}

TEST(TriangleContacts, ACapsuleLyingOnATriangleTouchesAtBothEnds) {
  // Along x, radius 0.05, its core 0.04 above the face: 1 cm deep.
  const ConvexGeometry capsule = CapsuleShape{0.05, 0.1};
  const Mat3 alongX = Quaternion::fromAxisAngle(Vec3::UnitY(), 0.5 * M_PI).toRotationMatrix();
  ContactManifold out;
  ASSERT_TRUE(collideTriangleConvex(unitTriangle(0x7), {&capsule, Transform{alongX, Vec3(0.3, 0.2, 0.04)}},
                                    margin(0.0), out));
  EXPECT_LT((out.normal - Vec3::UnitZ()).norm(), 1e-12);
  ASSERT_EQ(out.pointCount, 2);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(out.points[static_cast<std::size_t>(k)].depth, 0.01, 1e-9);
}

}  // namespace
}  // namespace rbsim
