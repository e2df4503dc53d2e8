// Contact classification by relative normal velocity (Baraff, "Rigid Body
// Simulation", SIGGRAPH course notes), and the symmetry of collideConvex
// under swapping its solids, over every pair of geometry types.
#include <vector>

#include "rbsim/physics/contacts.h"
#include "unit/collision/test_contacts_common.h"

namespace rbsim::testing {
namespace {

const Vec3 kZ = Vec3::UnitZ();

TEST(ClassifyContact, CollidingRestingSeparatingByRelativeNormalVelocity) {
  const double epsilon = 0.01;  // m/s
  EXPECT_EQ(classifyContact(-0.5, epsilon), ContactKind::Colliding);
  EXPECT_EQ(classifyContact(-0.0101, epsilon), ContactKind::Colliding);
  EXPECT_EQ(classifyContact(-0.01, epsilon), ContactKind::Resting);
  EXPECT_EQ(classifyContact(0.0, epsilon), ContactKind::Resting);
  EXPECT_EQ(classifyContact(0.01, epsilon), ContactKind::Resting);
  EXPECT_EQ(classifyContact(0.0101, epsilon), ContactKind::Separating);
  EXPECT_EQ(classifyContact(2.0, epsilon), ContactKind::Separating);
}

TEST(ClassifyContact, ABoxFallingOntoTheFloorCollidesAndOneLiftedSeparates) {
  // v_rel = n · (vB − vA) at the contact, with the manifold's normal (floor -> box).
  const Solid floor = solid(BoxShape{Vec3(2.0, 2.0, 0.5)}, Vec3(0.0, 0.0, -0.5));
  const Solid box = solid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.0, 0.0, 0.499));
  const ContactManifold m = collide(floor, box);
  ASSERT_EQ(m.pointCount, 4);
  const Vec3 falling(0.3, 0.0, -2.0);  // m/s, the box's; the floor is still
  EXPECT_EQ(classifyContact(m.normal.dot(falling), 0.01), ContactKind::Colliding);
  EXPECT_EQ(classifyContact(m.normal.dot(Vec3(0.3, 0.0, 0.0)), 0.01), ContactKind::Resting);
  EXPECT_EQ(classifyContact(m.normal.dot(Vec3(0.0, 0.0, 1.0)), 0.01), ContactKind::Separating);
}

// One solid of each type near the origin, and a second of each type placed
// to overlap it at a generic (non-tied) angle.
std::vector<Solid> firstSolids() {
  const Mat3 r = rotationAbout(Vec3(1.0, 2.0, 3.0), 0.3);
  return {solid(SphereShape{0.5}, Vec3::Zero()),
          solid(BoxShape{Vec3(0.5, 0.4, 0.45)}, Vec3::Zero(), r),
          solid(CapsuleShape{0.3, 0.3}, Vec3::Zero(), r),
          solid(CylinderShape{0.4, 0.4}, Vec3::Zero(), r),
          solid(cubeHull(Vec3(0.5, 0.4, 0.45)), Vec3::Zero(), r)};
}
std::vector<Solid> secondSolids() {
  const Mat3 r = rotationAbout(Vec3(-2.0, 1.0, 0.5), 0.5);
  const Vec3 p(0.15, -0.1, 0.7);
  return {solid(SphereShape{0.4}, p, r), solid(BoxShape{Vec3(0.3, 0.35, 0.4)}, p, r),
          solid(CapsuleShape{0.25, 0.3}, p, r), solid(CylinderShape{0.3, 0.35}, p, r),
          solid(cubeHull(Vec3(0.3, 0.35, 0.4)), p, r)};
}

TEST(CollideConvex, SwappingTheSolidsFlipsTheNormalAndKeepsTheDepthsForEveryPair) {
  const std::vector<Solid> firsts = firstSolids();
  const std::vector<Solid> seconds = secondSolids();
  for (std::size_t i = 0; i < firsts.size(); ++i) {
    for (std::size_t j = 0; j < seconds.size(); ++j) {
      SCOPED_TRACE(::testing::Message() << "types " << i << " and " << j);
      expectSymmetric(firsts[i], seconds[j], 1e-6);
    }
  }
}

TEST(CollideConvex, NormalPointsFromAToBAndDepthsMatchThePoints) {
  const std::vector<Solid> firsts = firstSolids();
  const std::vector<Solid> seconds = secondSolids();
  for (const Solid& a : firsts) {
    for (const Solid& b : seconds) {
      const ContactManifold m = collide(a, b);
      ASSERT_GT(m.pointCount, 0);
      EXPECT_NEAR(m.normal.norm(), 1.0, 1e-12);
      // B lies above A here, so a normal from A to B points up.
      EXPECT_GT(m.normal.dot(kZ), 0.0);
      for (int k = 0; k < m.pointCount; ++k) {
        const ContactPoint& p = m.points[static_cast<std::size_t>(k)];
        EXPECT_GT(p.depth, 0.0);
        EXPECT_NEAR(p.depth, m.normal.dot(p.pointA - p.pointB), 1e-9);
      }
    }
  }
}

}  // namespace
}  // namespace rbsim::testing
