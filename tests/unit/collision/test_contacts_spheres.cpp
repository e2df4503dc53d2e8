// Sphere contacts against closed forms: the closest point of the other
// solid to the centre, the normal along it, depth = radius − distance.
#include <cmath>

#include "unit/collision/test_contacts_common.h"

namespace rbsim::testing {
namespace {

const Vec3 kX = Vec3::UnitX();
const Vec3 kZ = Vec3::UnitZ();

TEST(SphereSphere, OverlapAlongTheLineOfCentres) {
  const Vec3 direction = Vec3(1.0, 2.0, -2.0) / 3.0;
  const Solid a = solid(SphereShape{1.0}, Vec3(0.1, 0.2, 0.3));
  const Solid b = solid(SphereShape{0.5}, a.pose.translation + 1.4 * direction);
  const ContactManifold m = collide(a, b);
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, direction, kTight);
  EXPECT_NEAR(m.points[0].depth, 0.1, kTight);
  expectNear(m.points[0].pointA, a.pose.translation + 1.0 * direction, kTight);
  expectNear(m.points[0].pointB, a.pose.translation + 0.9 * direction, kTight);
}

TEST(SphereSphere, GapWithinTheMarginIsANegativeDepthBeyondItNothing) {
  const Solid a = solid(SphereShape{1.0}, Vec3::Zero());
  const ContactManifold near = collide(a, solid(SphereShape{0.5}, Vec3(1.503, 0.0, 0.0)));
  ASSERT_EQ(near.pointCount, 1);
  EXPECT_NEAR(near.points[0].depth, -0.003, kTight);
  const ContactManifold far = collide(a, solid(SphereShape{0.5}, Vec3(1.506, 0.0, 0.0)));
  EXPECT_EQ(far.pointCount, 0);
}

TEST(SpherePlane, DeepestPointBelowATiltedPlane) {
  const Vec3 normal = Vec3(0.0, 1.0, 1.0).normalized();
  const double offset = 1.0;
  // Centre 0.49 above the plane: 1 cm into it for a radius of 0.5.
  const Vec3 center =
      Vec3(0.3, 0.0, 0.0) + (offset - Vec3(0.3, 0.0, 0.0).dot(normal)) * normal + 0.49 * normal;
  const ContactManifold m = collidePlane(normal, offset, solid(SphereShape{0.5}, center));
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, normal, kTight);
  EXPECT_NEAR(m.points[0].depth, 0.01, kTight);
  expectNear(m.points[0].pointB, center - 0.5 * normal, kTight);
  expectNear(m.points[0].pointA, center - 0.49 * normal, kTight);
  EXPECT_EQ(
      collidePlane(normal, offset, solid(SphereShape{0.5}, center + 0.02 * normal)).pointCount, 0);
}

// Box of half extents 1 at the origin, rotated 30° about z; positions are
// given in the box's frame and mapped to the world.
class SphereBox : public ::testing::Test {
 protected:
  const Mat3 rotation = rotationAbout(kZ, kPi / 6.0);
  const Solid box = solid(BoxShape{Vec3::Ones()}, Vec3(0.5, -0.2, 0.1), rotation);
  Vec3 world(const Vec3& local) const { return box.pose.apply(local); }
  Vec3 worldDirection(const Vec3& local) const { return rotation * local.normalized(); }
};

TEST_F(SphereBox, FaceRegion) {
  const ContactManifold m = collide(box, solid(SphereShape{0.5}, world({0.2, 0.3, 1.4})));
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, worldDirection(kZ), kTight);
  EXPECT_NEAR(m.points[0].depth, 0.1, kTight);
  expectNear(m.points[0].pointA, world({0.2, 0.3, 1.0}), kTight);
  expectNear(m.points[0].pointB, world({0.2, 0.3, 0.9}), kTight);
}

TEST_F(SphereBox, EdgeRegion) {
  const double distance = 0.45;
  const Vec3 out = Vec3(1.0, 0.0, 1.0).normalized();
  const ContactManifold m =
      collide(box, solid(SphereShape{0.5}, world(Vec3(1.0, 0.2, 1.0) + distance * out)));
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, worldDirection(out), kTight);
  EXPECT_NEAR(m.points[0].depth, 0.05, kTight);
  expectNear(m.points[0].pointA, world({1.0, 0.2, 1.0}), kTight);
}

TEST_F(SphereBox, CornerRegionSeenFromTheSphere) {
  const Vec3 out = Vec3(1.0, -1.0, 1.0).normalized();
  const Vec3 corner(1.0, -1.0, 1.0);
  // Sphere first: the normal points from the sphere into the box.
  const ContactManifold m = collide(solid(SphereShape{0.5}, world(corner + 0.4 * out)), box);
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, -worldDirection(out), kTight);
  EXPECT_NEAR(m.points[0].depth, 0.1, kTight);
  expectNear(m.points[0].pointA, world(corner + 0.4 * out - 0.5 * out), kTight);
  expectNear(m.points[0].pointB, world(corner), kTight);
}

TEST_F(SphereBox, CentreInsideLeavesThroughTheNearestFace) {
  const ContactManifold m = collide(box, solid(SphereShape{0.5}, world({0.2, 0.0, 0.9})));
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, worldDirection(kZ), kTight);
  EXPECT_NEAR(m.points[0].depth, 0.6, kTight);
  expectNear(m.points[0].pointA, world({0.2, 0.0, 1.0}), kTight);
}

TEST(SphereCapsule, ClosestPointOfTheCore) {
  const Solid capsule = solid(CapsuleShape{0.25, 1.0}, Vec3::Zero(), rotationAbout(kX, kPi / 2));
  // The capsule's core runs along y; the sphere sits beside it in x.
  const ContactManifold m = collide(capsule, solid(SphereShape{0.5}, Vec3(0.7, 0.5, 0.0)));
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, kX, kTight);
  EXPECT_NEAR(m.points[0].depth, 0.05, kTight);
  expectNear(m.points[0].pointA, Vec3(0.25, 0.5, 0.0), kTight);
  // Past the end of the core: the cap's centre is the closest core point.
  const Vec3 out = Vec3(0.0, 1.0, 1.0).normalized();
  const ContactManifold cap =
      collide(capsule, solid(SphereShape{0.5}, Vec3(0.0, -1.0, 0.0) - 0.7 * out));
  ASSERT_EQ(cap.pointCount, 1);
  expectNear(cap.normal, -out, kTight);
  EXPECT_NEAR(cap.points[0].depth, 0.05, kTight);
}

TEST(SphereCylinder, SideCapAndRim) {
  const Solid cylinder = solid(CylinderShape{0.5, 1.0}, Vec3(0.0, 0.0, 1.0));
  const ContactManifold side = collide(cylinder, solid(SphereShape{0.2}, Vec3(0.0, 0.68, 1.5)));
  ASSERT_EQ(side.pointCount, 1);
  expectNear(side.normal, Vec3::UnitY(), kTight);
  EXPECT_NEAR(side.points[0].depth, 0.02, kTight);
  expectNear(side.points[0].pointA, Vec3(0.0, 0.5, 1.5), kTight);

  const ContactManifold cap = collide(cylinder, solid(SphereShape{0.2}, Vec3(0.3, 0.1, 2.19)));
  ASSERT_EQ(cap.pointCount, 1);
  expectNear(cap.normal, kZ, kTight);
  EXPECT_NEAR(cap.points[0].depth, 0.01, kTight);
  expectNear(cap.points[0].pointA, Vec3(0.3, 0.1, 2.0), kTight);

  const Vec3 out = Vec3(1.0, 0.0, -1.0).normalized();
  const ContactManifold rim =
      collide(cylinder, solid(SphereShape{0.2}, Vec3(0.5, 0.0, 0.0) + 0.15 * out));
  ASSERT_EQ(rim.pointCount, 1);
  expectNear(rim.normal, out, kTight);
  EXPECT_NEAR(rim.points[0].depth, 0.05, kTight);
  expectNear(rim.points[0].pointA, Vec3(0.5, 0.0, 0.0), kTight);
}

TEST(SphereCylinder, CentreInsideLeavesThroughTheNearerOfCapAndSide) {
  const Solid cylinder = solid(CylinderShape{0.5, 1.0}, Vec3(0.0, 0.0, 1.0));
  const ContactManifold side = collide(cylinder, solid(SphereShape{0.2}, Vec3(0.0, 0.45, 1.2)));
  ASSERT_EQ(side.pointCount, 1);
  expectNear(side.normal, Vec3::UnitY(), kTight);
  EXPECT_NEAR(side.points[0].depth, 0.25, kTight);
  expectNear(side.points[0].pointA, Vec3(0.0, 0.5, 1.2), kTight);

  const ContactManifold cap = collide(cylinder, solid(SphereShape{0.2}, Vec3(0.1, 0.0, 1.95)));
  ASSERT_EQ(cap.pointCount, 1);
  expectNear(cap.normal, kZ, kTight);
  EXPECT_NEAR(cap.points[0].depth, 0.25, kTight);
  expectNear(cap.points[0].pointA, Vec3(0.1, 0.0, 2.0), kTight);
}

TEST(SphereHull, SameAsTheBoxRoutineForACubeHull) {
  const Mat3 rotation = rotationAbout(Vec3(1.0, 2.0, 3.0), 0.7);
  const Solid box = solid(BoxShape{Vec3(1.0, 0.5, 0.25)}, Vec3(0.1, 0.2, 0.3), rotation);
  const Solid hull = solid(cubeHull(Vec3(1.0, 0.5, 0.25)), Vec3(0.1, 0.2, 0.3), rotation);
  for (const Vec3& local :
       {Vec3(0.2, 0.1, 0.6), Vec3(1.2, 0.6, 0.0), Vec3(1.1, -0.6, 0.3), Vec3(0.3, 0.1, 0.1)}) {
    const Solid sphere = solid(SphereShape{0.4}, box.pose.apply(local));
    const ContactManifold expected = collide(box, sphere);
    ASSERT_EQ(expected.pointCount, 1) << local.transpose();
    expectSameManifold(collide(hull, sphere), expected);
    expectSameManifold(collide(sphere, hull), collide(sphere, box));
  }
}

}  // namespace
}  // namespace rbsim::testing
