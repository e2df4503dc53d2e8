// Compound bodies in a stepping world: every part collides as a piece of the
// one body, contacts of several pieces act together, and the right piece
// touches.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

constexpr double kSphereRadius = 0.1;  // m
constexpr double kHalfSpan = 0.4;      // m, from the middle to each sphere's centre

// Two spheres joined by a thin rod along x: parts 0 (−x sphere), 1 (+x
// sphere), 2 (rod, thinner than the spheres so it never touches a flat floor).
BodyDef dumbbell(const Vec3& position) {
  const Quaternion alongX = Quaternion::fromAxisAngle(Vec3::UnitY(), 0.5 * std::numbers::pi);
  BodyDef def;
  def.name = "dumbbell";
  def.shape = CompoundShape{{
      CompoundPart{SphereShape{kSphereRadius}, Vec3(-kHalfSpan, 0, 0), Quaternion::identity(), {}},
      CompoundPart{SphereShape{kSphereRadius}, Vec3(kHalfSpan, 0, 0), Quaternion::identity(), {}},
      CompoundPart{CapsuleShape{0.03, kHalfSpan - kSphereRadius}, Vec3::Zero(), alongX, {}},
  }};
  def.density = 2000.0;
  def.position = position;
  return def;
}

// The dumbbell's pieces in the last step's contacts.
std::set<int> touchingPieces(const World& world, BodyView body) {
  std::set<int> pieces;
  for (const SolvedManifold& m : world.contacts()) {
    if (m.serialA == body.serial()) pieces.insert(m.pieceA);
    if (m.serialB == body.serial()) pieces.insert(m.pieceB);
  }
  return pieces;
}

TEST(CompoundBodies, ADumbbellRestsOnTheGroundOnBothSpheres) {
  World world(testing::contactSettings(0.0, 0.5));
  testing::addGround(world);
  // Dropped from 5 cm above the ground.
  const BodyId id = *world.createBody(dumbbell(Vec3(0.0, 0.0, kSphereRadius + 0.05)));
  const BodyView body = world.body(id);
  for (int i = 0; i < 2000; ++i) world.step();  // 2 s

  EXPECT_EQ(touchingPieces(world, body), (std::set<int>{0, 1})) << "both spheres, not the rod";
  // Resting at the spheres' radius, level, still (the solver leaves at most
  // its slop of penetration, 0.5 mm).
  EXPECT_NEAR(body.position().z(), kSphereRadius, 1e-3);
  EXPECT_LT(std::abs(body.bodyToWorld(Vec3(kHalfSpan, 0, 0)).z() -
                     body.bodyToWorld(Vec3(-kHalfSpan, 0, 0)).z()),
            1e-6);
  EXPECT_LT(body.linearVelocity().norm(), 1e-6);
  EXPECT_LT(body.angularVelocity().norm(), 1e-6);
  EXPECT_LE(testing::deepestContact(world), 1e-3);
}

TEST(CompoundBodies, AFallingCompoundHitsABoxWithThePieceAboveIt) {
  World world(testing::contactSettings(0.0, 0.5));
  // A static block under the +x sphere only; its top face is at z = 0.4 m.
  BodyDef block;
  block.name = "block";
  block.shape = BoxShape{Vec3(0.2, 0.2, 0.2)};
  block.position = Vec3(kHalfSpan, 0.0, 0.2);
  block.isStatic = true;
  ASSERT_TRUE(world.createBody(block).ok());
  const BodyId id = *world.createBody(dumbbell(Vec3(0.0, 0.0, 0.4 + kSphereRadius + 0.02)));
  const BodyView body = world.body(id);

  int firstContactStep = -1;
  for (int i = 0; i < 200 && firstContactStep < 0; ++i) {
    world.step();
    if (!world.contacts().empty()) firstContactStep = i;
  }
  ASSERT_GE(firstContactStep, 0) << "the dumbbell never reached the block";
  EXPECT_EQ(touchingPieces(world, body), std::set<int>{1})
      << "only the +x sphere is above the block";
  for (const SolvedManifold& m : world.contacts()) {
    EXPECT_NEAR(std::abs(m.normal.z()), 1.0, 1e-9);
    for (int p = 0; p < m.pointCount; ++p) {
      EXPECT_NEAR(m.points[p].point.x(), kHalfSpan, 1e-6);
      // Found within the contact margin, before they touch.
      EXPECT_NEAR(m.points[p].point.z(), 0.4, world.settings().contact.detection.margin);
    }
  }

  // Held at +x only, it tips over the block's edge: the −x end drops
  // (a negative turn about y).
  for (int i = 0; i < 100; ++i) world.step();
  EXPECT_LT(body.angularVelocity().y(), -0.1);
  EXPECT_LT(body.bodyToWorld(Vec3(-kHalfSpan, 0, 0)).z(),
            body.bodyToWorld(Vec3(kHalfSpan, 0, 0)).z() - 0.01);
}

}  // namespace
}  // namespace rbsim
