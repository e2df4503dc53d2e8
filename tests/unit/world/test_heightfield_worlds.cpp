// Heightfield terrain in stepping worlds: the trimesh a grid of heights
// becomes (meshio/height_grid.h, as a world file's `type: heightfield`
// loads it) against an analytic plane where the terrain is a plane: a ball
// bounces on its flat part as on the ground, and rolls down a sloped grid
// as down the same slope, with both contact solvers.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "meshio/height_grid.h"
#include "unit/solver/contact_test_worlds.h"
#include "unit/world/terrain_test_worlds.h"

namespace rbsim {
namespace {

// A rows × columns grid of cells `cell` m wide, of heights height(x, y).
template <class Height>
BodyId addTerrain(World& world, int samples, double cell, Height&& height) {
  HeightGrid grid;
  grid.rows = grid.columns = samples;
  const double middle = 0.5 * (samples - 1);
  for (int r = 0; r < samples; ++r)
    for (int c = 0; c < samples; ++c) grid.values.push_back(height((c - middle) * cell, (r - middle) * cell));
  BodyDef def;
  def.name = "terrain";
  def.shape = TriangleMeshShape{"inline heights", std::make_shared<const TriangleMesh>(heightGridMesh(grid, cell, cell, 1.0, 0.0))};
  def.isStatic = true;
  const auto id = world.createBody(def);
  EXPECT_TRUE(id.ok()) << (id.ok() ? "" : id.error().message);
  return *id;
}

class HeightfieldWorlds : public ::testing::TestWithParam<ContactSolverKind> {};

TEST_P(HeightfieldWorlds, ABallBouncesOnTheFlatPartAsOnAPlane) {
  World onTerrain(testing::terrainSettings(GetParam(), 0.8, 0.0));
  World onPlane(testing::terrainSettings(GetParam(), 0.8, 0.0));
  // 17 × 17 samples 0.25 m apart; a hill of 0.5 m in the corner x, y > 1,
  // flat (z = 0) everywhere else.
  addTerrain(onTerrain, 17, 0.25, [](double x, double y) { return x > 1.0 && y > 1.0 ? 0.5 : 0.0; });
  testing::addGroundPlane(onPlane);
  const Vec3 start(-0.43, 0.29, 1.0);
  const BodyId onHeights = testing::addSphere(onTerrain, "ball", 0.1, start);
  const BodyId onGround = testing::addSphere(onPlane, "ball", 0.1, start);
  double apexTerrain = 0.0, apexPlane = 0.0, largest = 0.0;
  bool bounced = false;
  for (int i = 0; i < 1500; ++i) {
    onTerrain.step();
    onPlane.step();
    if (onPlane.body(onGround).linearVelocity().z() > 0.0) bounced = true;
    if (bounced) {
      apexTerrain = std::max(apexTerrain, onTerrain.body(onHeights).position().z());
      apexPlane = std::max(apexPlane, onPlane.body(onGround).position().z());
    }
    largest = std::max(largest, (onTerrain.body(onHeights).position() - onPlane.body(onGround).position()).norm());
  }
  ASSERT_TRUE(bounced);
  // e² of the 0.9 m drop, above the radius (within the step's discretisation).
  EXPECT_NEAR(apexPlane - 0.1, 0.64 * 0.9, 0.01);
  EXPECT_NEAR(apexTerrain, apexPlane, 1e-9);
  EXPECT_LT(largest, 1e-9);
}

TEST_P(HeightfieldWorlds, ABallRollsDownASlopedGridAsDownTheSlope) {
  // Heights 0.2 x: the plane through the origin tilted by atan(0.2) about
  // −y (rising along +x); the plane's normal is the tilt of +z.
  const double slope = 0.2;
  const double angle = std::atan(slope);
  World onTerrain(testing::terrainSettings(GetParam(), 0.0, 0.6));
  World onPlane(testing::terrainSettings(GetParam(), 0.0, 0.6));
  addTerrain(onTerrain, 41, 0.125, [&](double x, double) { return slope * x; });
  const Quaternion tilt = Quaternion::fromAxisAngle(-Vec3::UnitY(), angle);
  testing::addGroundPlane(onPlane, tilt);
  const double radius = 0.1;
  // Resting on the slope at (1.5, 0.13) along it: it rolls down towards −x.
  const Vec3 start = tilt.toRotationMatrix() * Vec3(1.5 / std::cos(angle), 0.13, radius);
  const BodyId onHeights = testing::addSphere(onTerrain, "ball", radius, start);
  const BodyId onGround = testing::addSphere(onPlane, "ball", radius, start);
  double largest = 0.0;
  for (int i = 0; i < 1000; ++i) {  // 1 s
    onTerrain.step();
    onPlane.step();
    largest = std::max(largest, (onTerrain.body(onHeights).position() - onPlane.body(onGround).position()).norm());
  }
  const Vec3 travelled = onPlane.body(onGround).position() - start;
  // It did roll: (5/7) g sin θ t² / 2 for a rolling ball.
  EXPECT_NEAR(travelled.norm(), 5.0 / 7.0 * 9.81 * std::sin(angle) / 2.0, 0.02);
  EXPECT_LT(largest, 1e-6) << "the ball on the heightfield left the ball on the plane by " << largest << " m";
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, HeightfieldWorlds,
                         ::testing::Values(ContactSolverKind::SoftStep, ContactSolverKind::SequentialImpulses),
                         [](const ::testing::TestParamInfo<ContactSolverKind>& info) {
                           return info.param == ContactSolverKind::SoftStep ? "SoftStep" : "SequentialImpulses";
                         });

}  // namespace
}  // namespace rbsim
