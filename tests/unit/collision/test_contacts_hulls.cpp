// Hull manifolds: a cube built as a hull must give what the box routine
// gives for the same geometry (two independent paths: Gauss-map SAT over
// hand-numbered faces against the 15-axis box test), and a tetrahedron's
// manifolds follow the face–vertex rule.
#include <cmath>
#include <vector>

#include "unit/collision/test_contacts_common.h"

namespace rbsim::testing {
namespace {

const Vec3 kX = Vec3::UnitX();
const Vec3 kY = Vec3::UnitY();
const Vec3 kZ = Vec3::UnitZ();

struct Pose {
  Vec3 position;
  Mat3 rotation;
};

// Poses of a cube of half extent 0.5 on another at the origin: resting,
// turned, turned into an octagon with a tilt, on an edge, on a corner,
// overhanging, edge across edge.
std::vector<Pose> cubeOnCubePoses() {
  const double half = std::sqrt(0.5);
  const Mat3 cornerDown = Eigen::Quaterniond::FromTwoVectors(-Vec3::Ones(), -kZ).toRotationMatrix();
  return {
      {Vec3(0.1, 0.2, 0.999), Mat3::Identity()},
      {Vec3(0.1, 0.2, 0.999), rotationAbout(kZ, 0.3)},
      {Vec3(0.0, 0.0, 0.5 + 0.5 / std::cos(0.002) - 0.001),
       rotationAbout(kY, 0.002) * rotationAbout(kZ, kPi / 4)},
      {Vec3(0.1, 0.2, 0.5 + 0.5 * (std::sin(0.5) + std::cos(0.5)) - 0.001), rotationAbout(kX, 0.5)},
      {Vec3(0.1, 0.2, 0.5 + 0.5 * std::sqrt(3.0) - 0.001), cornerDown},
      {Vec3(0.7, 0.3, 0.998), rotationAbout(kZ, 0.2)},
      {Vec3(0.1, 0.2, 2.0 * half - 0.01), rotationAbout(kY, kPi / 4)},
  };
}

TEST(HullHull, CubeHullsGiveTheBoxManifold) {
  const Vec3 h = Vec3::Constant(0.5);
  const Mat3 lowerRotation = rotationAbout(kX, 0.0);
  for (const bool edgeUp : {false, true}) {
    // The last pose needs the lower cube's edge up.
    const Mat3 lower = edgeUp ? rotationAbout(kX, kPi / 4) : lowerRotation;
    for (const Pose& pose : cubeOnCubePoses()) {
      const Solid boxA = solid(BoxShape{h}, Vec3::Zero(), lower);
      const Solid boxB = solid(BoxShape{h}, pose.position, pose.rotation);
      const Solid hullA = solid(cubeHull(h), Vec3::Zero(), lower);
      const Solid hullB = solid(cubeHull(h), pose.position, pose.rotation);
      const ContactManifold expected = collide(boxA, boxB);
      if (expected.pointCount == 0) continue;
      SCOPED_TRACE(::testing::Message()
                   << "at " << pose.position.transpose() << " edge up " << edgeUp);
      expectSameManifold(collide(hullA, hullB), expected);
      expectSameManifold(collide(boxA, hullB), expected);
      expectSameManifold(collide(hullA, boxB), expected);
    }
  }
}

TEST(HullHull, EdgeAcrossEdgeFollowsTheCrossProductRule) {
  const double half = std::sqrt(0.5);
  const Solid a = solid(cubeHull(Vec3::Constant(0.5)), Vec3::Zero(), rotationAbout(kX, kPi / 4));
  const Solid b = solid(cubeHull(Vec3::Constant(0.5)), Vec3(0.1, 0.2, 2.0 * half - 0.01),
                        rotationAbout(kY, kPi / 4));
  const ContactManifold m = collide(a, b);
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, kZ, kTight);
  expectPoints(m, {Vec3(0.1, 0.0, half - 0.01)}, 0.01);
}

// A tetrahedron with its apex 0.6 below a horizontal triangle of
// circumradius 1 (the hull frame's origin at the triangle's centre).
std::shared_ptr<const ConvexHull> tetrahedron() {
  const std::vector<Vec3> vertices{Vec3(0.0, 0.0, -0.6), Vec3(1.0, 0.0, 0.0),
                                   Vec3(-0.5, std::sqrt(0.75), 0.0),
                                   Vec3(-0.5, -std::sqrt(0.75), 0.0)};
  return makeHull(vertices, {{1, 2, 3}, {0, 1, 2}, {0, 2, 3}, {0, 3, 1}});
}

const Solid kCube = solid(cubeHull(Vec3::Constant(0.5)), Vec3::Zero());

TEST(HullHull, TetrahedronOnItsApexGivesOnePointWithTheCubeFaceNormal) {
  const Solid tet = solid(tetrahedron(), Vec3(0.1, 0.2, 0.5 + 0.6 - 0.001));
  const ContactManifold m = collide(kCube, tet);
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, kZ, kTight);
  expectPoints(m, {Vec3(0.1, 0.2, 0.499)}, 0.001);
}

TEST(HullHull, TetrahedronOnAFaceGivesItsThreeCorners) {
  // Upside down: the triangle at the bottom, 0.2 inside the cube's top face.
  const Solid tet = solid(tetrahedron(), Vec3(0.0, 0.0, 0.5 - 0.001), rotationAbout(kX, kPi));
  const ContactManifold m = collide(tet, kCube);
  expectNear(m.normal, -kZ, kTight);  // from the tetrahedron into the cube
  // Seen from the cube the tetrahedron's triangle is clipped by its sides.
  const ContactManifold fromCube = collide(kCube, tet);
  expectNear(fromCube.normal, kZ, kTight);
  ASSERT_GE(fromCube.pointCount, 3);
  for (int i = 0; i < fromCube.pointCount; ++i) {
    EXPECT_NEAR(fromCube.points[static_cast<std::size_t>(i)].depth, 0.001, kTight);
  }
  const Solid small = solid(tetrahedron(), Vec3(0.0, 0.0, 0.5 - 0.001), rotationAbout(kX, kPi));
  const Solid big = solid(cubeHull(Vec3::Constant(2.0)), Vec3(0.0, 0.0, -1.5));
  expectPoints(collide(big, small),
               {Vec3(1.0, 0.0, 0.499), Vec3(-0.5, std::sqrt(0.75), 0.499),
                Vec3(-0.5, -std::sqrt(0.75), 0.499)},
               0.001);
}

TEST(HullPlane, TetrahedronVerticesBelowThePlane) {
  const ContactManifold onFace =
      collidePlane(kZ, 0.0, solid(tetrahedron(), Vec3(0.0, 0.0, -0.001), rotationAbout(kX, kPi)));
  expectPoints(onFace,
               {Vec3(1.0, 0.0, -0.001), Vec3(-0.5, std::sqrt(0.75), -0.001),
                Vec3(-0.5, -std::sqrt(0.75), -0.001)},
               0.001);
  const ContactManifold onApex = collidePlane(kZ, 0.0, solid(tetrahedron(), Vec3(0.3, 0.0, 0.599)));
  expectPoints(onApex, {Vec3(0.3, 0.0, -0.001)}, 0.001);
}

TEST(HullCapsule, CubeHullGivesTheBoxManifold) {
  const Vec3 out = Vec3(1.0, 0.0, 1.0).normalized();
  const Mat3 alongY = rotationAbout(kX, kPi / 2);
  const Solid box = solid(BoxShape{Vec3::Constant(0.5)}, Vec3::Zero());
  for (const Solid& capsule :
       {solid(CapsuleShape{0.25, 0.3}, Vec3(0.1, 0.0, 0.74), alongY),
        solid(CapsuleShape{0.25, 0.3}, Vec3(0.5, 0.1, 0.5) + 0.23 * out, alongY),
        solid(CapsuleShape{0.25, 0.3}, Vec3(0.1, 0.2, 1.0)),
        solid(CapsuleShape{0.25, 0.3}, Vec3(0.1, 0.2, 0.6), rotationAbout(kX, 1.0))}) {
    const ContactManifold expected = collide(box, capsule);
    ASSERT_GT(expected.pointCount, 0);
    expectSameManifold(collide(kCube, capsule), expected);
    expectSymmetric(kCube, capsule);
  }
}

}  // namespace
}  // namespace rbsim::testing
