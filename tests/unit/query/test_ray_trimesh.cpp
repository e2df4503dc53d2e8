// Ray casts against a trimesh, with hit points and normals worked by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "physics/query/ray_triangle_mesh.h"
#include "rbsim/physics/world.h"
#include "unit/collision/triangle_mesh_test_meshes.h"

namespace rbsim {
namespace {

// The step (floor z = 0 for x < 0, wall x = 0 up to 0.5 facing −x, top
// z = 0.5 for x > 0; y in [−1, 1]) as a static body moved by (0, 0, 1) and
// turned a quarter about z (so the body's x is the world's y).
World stepWorld() {
  World world;
  BodyDef def;
  def.name = "step";
  def.shape = TriangleMeshShape{"step", std::make_shared<const TriangleMesh>(testing::stepMesh(0.5))};
  def.isStatic = true;
  def.position = Vec3(0, 0, 1);
  def.orientation = Quaternion::fromAxisAngle(Vec3::UnitZ(), 0.5 * M_PI);
  EXPECT_TRUE(world.createBody(def).ok());
  return world;
}

void expectNear(const Vec3& actual, const Vec3& expected) {
  EXPECT_LT((actual - expected).norm(), 1e-12) << actual.transpose() << " vs " << expected.transpose();
}

TEST(TrimeshRays, ADownwardRayHitsTheFloorOrTheTop) {
  const World world = stepWorld();
  // Body (−0.75, 0.3) is world (−0.3, −0.75): the floor, at world z = 1.
  const auto floor = world.castRay({Vec3(-0.3, -0.75, 3.0), Vec3(-0.3, -0.75, 0.0)});
  ASSERT_TRUE(floor);
  EXPECT_NEAR(floor->fraction, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(floor->distance, 2.0, 1e-12);
  expectNear(floor->point, Vec3(-0.3, -0.75, 1.0));
  expectNear(floor->normal, Vec3::UnitZ());
  EXPECT_TRUE(floor->piece == 0 || floor->piece == 1);
  // Body (0.5, 0.2) is world (−0.2, 0.5): the top, at world z = 1.5.
  const auto top = world.castRay({Vec3(-0.2, 0.5, 3.0), Vec3(-0.2, 0.5, 0.0)});
  ASSERT_TRUE(top);
  expectNear(top->point, Vec3(-0.2, 0.5, 1.5));
  expectNear(top->normal, Vec3::UnitZ());
  EXPECT_TRUE(top->piece == 4 || top->piece == 5);
}

TEST(TrimeshRays, AHorizontalRayHitsTheWallFromEitherSide) {
  const World world = stepWorld();
  // The wall is body x = 0 (world y = 0), facing body −x (world −y),
  // between world z = 1 and 1.5. From its front:
  const auto front = world.castRay({Vec3(0.25, -2.0, 1.2), Vec3(0.25, 2.0, 1.2)});
  ASSERT_TRUE(front);
  expectNear(front->point, Vec3(0.25, 0.0, 1.2));
  expectNear(front->normal, Vec3(0, -1, 0));
  EXPECT_NEAR(front->fraction, 0.5, 1e-12);
  EXPECT_TRUE(front->piece == 2 || front->piece == 3);
  // From behind (inside the step's solid, below the top): the same wall,
  // its normal turned to face the ray.
  const auto behind = world.castRay({Vec3(0.25, 1.0, 1.2), Vec3(0.25, -1.0, 1.2)});
  ASSERT_TRUE(behind);
  expectNear(behind->point, Vec3(0.25, 0.0, 1.2));
  expectNear(behind->normal, Vec3(0, 1, 0));
}

TEST(TrimeshRays, RaysThatPassTheMeshMissIt) {
  const World world = stepWorld();
  EXPECT_FALSE(world.castRay({Vec3(0, 0, 3), Vec3(0, 0, 1.6)}));       // stops short of the top
  EXPECT_FALSE(world.castRay({Vec3(3, 0, 3), Vec3(3, 0, 0)}));         // beside it (|y| > 1 in the body)
  EXPECT_FALSE(world.castRay({Vec3(0.5, -2, 2), Vec3(0.5, 2, 2)}));   // over it
  EXPECT_FALSE(world.castRayAny({Vec3(0.25, -2.0, 0.5), Vec3(0.25, 2.0, 0.5)}));  // under it
  EXPECT_EQ(world.castRayAll({Vec3(-0.3, -0.75, 3.0), Vec3(-0.3, -0.75, 0.0)}).size(), 1u);
}

TEST(TrimeshRays, SegmentTriangleFractionsByHand) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  // Through (0.5, 0.25, 0) from (0.5, 0.25, 4) down 8: t = 0.5.
  EXPECT_NEAR(*segmentTriangleFraction(Vec3(0.5, 0.25, 4), Vec3(0, 0, -8), a, b, c, 1.0), 0.5, 1e-15);
  // From below, slanted: (1, 1, −1) + t (−1, −1, 2) crosses z = 0 at t = 0.5, at (0.5, 0.5).
  EXPECT_NEAR(*segmentTriangleFraction(Vec3(1, 1, -1), Vec3(-1, -1, 2), a, b, c, 1.0), 0.5, 1e-15);
  // Outside the hypotenuse x + y = 2, in the plane, and too short.
  EXPECT_FALSE(segmentTriangleFraction(Vec3(1.5, 1.5, 1), Vec3(0, 0, -2), a, b, c, 1.0));
  EXPECT_FALSE(segmentTriangleFraction(Vec3(-1, 0.5, 0), Vec3(3, 0, 0), a, b, c, 1.0));
  EXPECT_FALSE(segmentTriangleFraction(Vec3(0.5, 0.25, 4), Vec3(0, 0, -8), a, b, c, 0.4));
}

}  // namespace
}  // namespace rbsim
