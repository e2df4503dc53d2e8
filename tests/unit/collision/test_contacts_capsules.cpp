// Capsule contacts against closed forms: the core's closest points plus the
// radii; two points where the core lies parallel to a segment or a face.
#include <cmath>

#include "unit/collision/test_contacts_common.h"

namespace rbsim::testing {
namespace {

const Vec3 kX = Vec3::UnitX();
const Vec3 kY = Vec3::UnitY();
const Vec3 kZ = Vec3::UnitZ();

// The capsule's z axis turned onto world x (or y).
const Mat3 kAlongX = rotationAbout(kY, kPi / 2);
const Mat3 kAlongY = rotationAbout(kX, kPi / 2);

TEST(CapsuleCapsule, ParallelGivesTwoPointsAtTheEndsOfTheOverlap) {
  const Solid a = solid(CapsuleShape{0.25, 1.0}, Vec3::Zero(), kAlongX);
  const Solid b = solid(CapsuleShape{0.25, 0.5}, Vec3(0.7, 0.0, 0.45), kAlongX);
  const ContactManifold m = collide(a, b);
  expectNear(m.normal, kZ, kTight);
  // B's core covers x in [0.2, 1.2], A's [-1, 1]: the overlap is [0.2, 1].
  expectPoints(m, {Vec3(0.2, 0.0, 0.2), Vec3(1.0, 0.0, 0.2)}, 0.05);
}

TEST(CapsuleCapsule, CrossingGivesOnePointAtTheClosestPoints) {
  const Solid a = solid(CapsuleShape{0.25, 1.0}, Vec3::Zero(), kAlongX);
  const Solid b = solid(CapsuleShape{0.25, 1.0}, Vec3(0.3, 0.2, 0.45), kAlongY);
  const ContactManifold m = collide(a, b);
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, kZ, kTight);
  expectPoints(m, {Vec3(0.3, 0.0, 0.2)}, 0.05);
}

TEST(CapsulePlane, LyingGivesBothEndsStandingOne) {
  const ContactManifold lying =
      collidePlane(kZ, 0.0, solid(CapsuleShape{0.3, 0.8}, Vec3(0.1, 0.2, 0.298), kAlongY));
  expectNear(lying.normal, kZ, kTight);
  expectPoints(lying, {Vec3(0.1, -0.6, -0.002), Vec3(0.1, 1.0, -0.002)}, 0.002);

  const ContactManifold standing =
      collidePlane(kZ, 0.0, solid(CapsuleShape{0.3, 0.8}, Vec3(0.1, 0.2, 1.099)));
  expectPoints(standing, {Vec3(0.1, 0.2, -0.001)}, 0.001);
}

// A box of half extents 1 at the origin, top face at z = 1.
const Solid kBox = solid(BoxShape{Vec3::Ones()}, Vec3::Zero());

TEST(CapsuleBox, LyingOnTheTopFaceGivesTwoPoints) {
  const ContactManifold m =
      collide(kBox, solid(CapsuleShape{0.25, 0.5}, Vec3(0.2, 0.3, 1.24), kAlongX));
  expectNear(m.normal, kZ, kTight);
  expectPoints(m, {Vec3(-0.3, 0.3, 0.99), Vec3(0.7, 0.3, 0.99)}, 0.01);
}

TEST(CapsuleBox, LyingAcrossAFaceEdgeKeepsThePartOverTheFace) {
  // Half of the core hangs over the edge x = 1: only the end over the face
  // and the cut at the edge remain.
  const ContactManifold m =
      collide(kBox, solid(CapsuleShape{0.25, 0.5}, Vec3(1.0, 0.3, 1.24), kAlongX));
  expectNear(m.normal, kZ, kTight);
  expectPoints(m, {Vec3(0.5, 0.3, 0.99), Vec3(1.0, 0.3, 0.99)}, 0.01);
}

TEST(CapsuleBox, SunkWithTheCoreInsideClipsToTheFace) {
  // Core 5 cm below the top face: depth = 0.25 + 0.05.
  const ContactManifold m =
      collide(kBox, solid(CapsuleShape{0.25, 0.5}, Vec3(0.2, 0.3, 0.95), kAlongX));
  expectNear(m.normal, kZ, kTight);
  expectPoints(m, {Vec3(-0.3, 0.3, 0.7), Vec3(0.7, 0.3, 0.7)}, 0.3);
}

TEST(CapsuleBox, StandingGivesOnePoint) {
  const ContactManifold m = collide(kBox, solid(CapsuleShape{0.25, 0.5}, Vec3(0.2, 0.3, 1.74)));
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, kZ, kTight);
  expectPoints(m, {Vec3(0.2, 0.3, 0.99)}, 0.01);
}

TEST(CapsuleBox, LyingAlongAnEdgeGivesTwoPointsOnTheEdge) {
  const Vec3 out = Vec3(1.0, 0.0, 1.0).normalized();
  const Solid capsule = solid(CapsuleShape{0.25, 0.5}, Vec3(1.0, 0.1, 1.0) + 0.23 * out, kAlongY);
  const ContactManifold m = collide(kBox, capsule);
  expectNear(m.normal, out, kTight);
  expectPoints(m, {Vec3(1.0, -0.4, 1.0) - 0.02 * out, Vec3(1.0, 0.6, 1.0) - 0.02 * out}, 0.02);
  // Seen from the capsule: the same contact, reversed.
  const ContactManifold reversed = collide(capsule, kBox);
  expectNear(reversed.normal, -out, kTight);
  EXPECT_EQ(reversed.pointCount, 2);
}

TEST(CapsuleBox, CrossingAnEdgeGivesOnePointOnIt) {
  const Vec3 out = Vec3(1.0, 0.0, 1.0).normalized();
  // Core along x - z, perpendicular to both the edge (along y) and `out`.
  const Mat3 across = rotationAbout(kY, -kPi / 4);
  const ContactManifold m =
      collide(kBox, solid(CapsuleShape{0.25, 0.5}, Vec3(1.0, 0.1, 1.0) + 0.23 * out, across));
  ASSERT_EQ(m.pointCount, 1);
  expectNear(m.normal, out, kTight);
  expectPoints(m, {Vec3(1.0, 0.1, 1.0) - 0.02 * out}, 0.02);
}

}  // namespace
}  // namespace rbsim::testing
