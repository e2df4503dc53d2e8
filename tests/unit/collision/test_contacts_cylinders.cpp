// Cylinder manifolds: against a plane by the dedicated routine, against
// other solids by signed distance plus clipping of the support features.
// A cylinder standing must rest on more than one point, one lying on two.
#include <cmath>
#include <vector>

#include "unit/collision/test_contacts_common.h"

namespace rbsim::testing {
namespace {

const Vec3 kX = Vec3::UnitX();
const Vec3 kZ = Vec3::UnitZ();
const CylinderShape kCylinder{0.3, 0.5};
const Mat3 kLying = rotationAbout(kX, kPi / 2);  // axis along world y

// Every point is `depth` deep, on the rim circle of radius 0.3 around the
// vertical axis through `axis`, with its plane point straight above it.
void expectOnRim(const ContactManifold& m, const Vec3& axis, double depth, double tolerance) {
  for (int i = 0; i < m.pointCount; ++i) {
    const ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    EXPECT_NEAR(p.depth, depth, tolerance);
    EXPECT_NEAR(std::hypot(p.pointB.x() - axis.x(), p.pointB.y() - axis.y()), 0.3, tolerance);
    expectNear(p.pointA, p.pointB + p.depth * m.normal, tolerance);
  }
}

TEST(CylinderPlane, StandingGivesAtLeastThreePointsOnTheRim) {
  const ContactManifold m = collidePlane(kZ, 0.0, solid(kCylinder, Vec3(0.1, 0.2, 0.5 - 0.001)));
  EXPECT_EQ(m.normal, kZ);
  EXPECT_GE(m.pointCount, 3);
  expectOnRim(m, Vec3(0.1, 0.2, 0.0), 0.001, kTight);
}

TEST(CylinderPlane, LyingGivesTheTwoEndsOfItsLowestLine) {
  const ContactManifold m = collidePlane(kZ, 0.0, solid(kCylinder, Vec3(0.1, 0.2, 0.299), kLying));
  expectPoints(m, {Vec3(0.1, -0.3, -0.001), Vec3(0.1, 0.7, -0.001)}, 0.001);
}

TEST(CylinderPlane, TiltedOnItsRimGivesOnePoint) {
  const double angle = kPi / 6;
  const double r = kCylinder.radius;
  const double h = kCylinder.halfLength;
  const Solid tilted =
      solid(kCylinder, Vec3(0.0, 0.0, r * std::sin(angle) + h * std::cos(angle) - 0.001),
            rotationAbout(kX, angle));
  expectPoints(collidePlane(kZ, 0.0, tilted),
               {Vec3(0.0, -r * std::cos(angle) + h * std::sin(angle), -0.001)}, 0.001);
}

// A large box whose top face is the plane z = 0.
const Solid kFloor = solid(BoxShape{Vec3(2.0, 2.0, 0.5)}, Vec3(0.0, 0.0, -0.5));

// Signed distance (GJK/EPA) is accurate to about its tolerance; the
// clipped depths are measured from an exact face, so they are tighter.
constexpr double kDistanceTolerance = 1e-6;

TEST(CylinderBox, StandingOnABoxGivesAtLeastThreePoints) {
  const ContactManifold m = collide(kFloor, solid(kCylinder, Vec3(0.1, 0.2, 0.5 - 0.001)));
  EXPECT_EQ(m.normal, kZ);
  EXPECT_GE(m.pointCount, 3);
  expectOnRim(m, Vec3(0.1, 0.2, 0.0), 0.001, kTight);
}

TEST(CylinderBox, LyingOnABoxGivesTwoPoints) {
  const ContactManifold m = collide(kFloor, solid(kCylinder, Vec3(0.1, 0.2, 0.299), kLying));
  expectNear(m.normal, kZ, kTight);
  expectPoints(m, {Vec3(0.1, -0.3, -0.001), Vec3(0.1, 0.7, -0.001)}, 0.001, kDistanceTolerance);
}

TEST(CylinderBox, BoxStandingOnACylinderCapGivesFourPoints) {
  // A small box on the cylinder's top cap: its whole bottom face touches.
  const Solid cylinder = solid(kCylinder, Vec3::Zero());
  const Solid box = solid(BoxShape{Vec3(0.1, 0.1, 0.1)}, Vec3(0.05, 0.0, 0.6 - 0.001));
  const ContactManifold m = collide(cylinder, box);
  EXPECT_EQ(m.normal, kZ);
  expectPoints(m,
               {Vec3(-0.05, -0.1, 0.499), Vec3(0.15, -0.1, 0.499), Vec3(0.15, 0.1, 0.499),
                Vec3(-0.05, 0.1, 0.499)},
               0.001, kTight);
}

TEST(CylinderCylinder, StackedGivesAtLeastThreePoints) {
  const ContactManifold m =
      collide(solid(kCylinder, Vec3::Zero()), solid(kCylinder, Vec3(0.05, 0.0, 1.0 - 0.001)));
  expectNear(m.normal, kZ, kTight);
  EXPECT_GE(m.pointCount, 3);
  for (int i = 0; i < m.pointCount; ++i) {
    EXPECT_NEAR(m.points[static_cast<std::size_t>(i)].depth, 0.001, kTight);
  }
}

TEST(CylinderCylinder, SideBySideGivesTwoPoints) {
  // Two lying cylinders, axes along y, 1 mm into each other along x; B is
  // shifted by 0.1 along y, so they overlap for y in [−0.4, 0.5]. EPA's
  // direction on curved sides is good to about 1e-3 rad, hence the looser
  // positions.
  const ContactManifold m = collide(solid(kCylinder, Vec3::Zero(), kLying),
                                    solid(kCylinder, Vec3(0.599, 0.1, 0.0), kLying));
  expectNear(m.normal, kX, 1e-3);
  ASSERT_EQ(m.pointCount, 2);
  for (const double y : {-0.4, 0.5}) {
    const ContactPoint& p = nearestPoint(m, Vec3(0.299, y, 0.0));
    expectNear(p.pointB, Vec3(0.299, y, 0.0), 1e-3);
    expectNear(p.pointA, Vec3(0.3, y, 0.0), 1e-3);
    EXPECT_NEAR(p.depth, 0.001, kDistanceTolerance);
  }
}

TEST(CylinderCapsule, CapsuleLyingOnTheCapGivesTwoPoints) {
  const Solid cylinder = solid(kCylinder, Vec3::Zero());
  const Solid capsule =
      solid(CapsuleShape{0.1, 0.15}, Vec3(0.0, 0.05, 0.599), rotationAbout(Vec3::UnitY(), kPi / 2));
  const ContactManifold m = collide(cylinder, capsule);
  EXPECT_EQ(m.normal, kZ);
  expectPoints(m, {Vec3(-0.15, 0.05, 0.499), Vec3(0.15, 0.05, 0.499)}, 0.001, kTight);
}

TEST(CylinderSymmetry, SwappingFlipsTheNormalAndKeepsTheDepths) {
  const Solid cylinder =
      solid(kCylinder, Vec3(0.1, 0.2, 0.45), rotationAbout(Vec3(1.0, 2.0, 0.0), 0.4));
  expectSymmetric(kFloor, cylinder, kDistanceTolerance);
  expectSymmetric(kFloor, solid(kCylinder, Vec3(0.1, 0.2, 0.499)), kDistanceTolerance);
  expectSymmetric(
      solid(kCylinder, Vec3::Zero()),
      solid(cubeHull(Vec3::Constant(0.2)), Vec3(0.1, 0.0, 0.69), rotationAbout(kZ, 0.3)),
      kDistanceTolerance);
  expectSymmetric(solid(kCylinder, Vec3::Zero()),
                  solid(CapsuleShape{0.1, 0.3}, Vec3(0.35, 0.0, 0.2), rotationAbout(kX, 0.5)),
                  kDistanceTolerance);
}

}  // namespace
}  // namespace rbsim::testing
