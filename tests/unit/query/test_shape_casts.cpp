// World::castShape and castShapeAll (rbsim/physics/shape_cast.h): each cast
// shape against each kind of solid, with touch fractions, points and
// normals worked by hand; starts in contact, misses, filters, all hits; and
// the tree's walk against a brute-force sweep over every body.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "physics/query/convex_sweep.h"
#include "rbsim/physics/world.h"
#include "unit/query/query_test_worlds.h"
#include "scenes/scene_random.h"

namespace rbsim {
namespace {

// The sweeps stop within 1e-7 of the solids' size of the touch and find
// it from there in closed form (query/convex_sweep.h): the distance
// travelled and the point to 1e-10 m here, and the normal to 1e-8 (a
// polytope's is the closest points' direction at that gap, good to about
// 1e-16 m over the gap), for solids of metre size.
constexpr double kTol = 1e-10;

BodyId addGround(World& world, double height = 0.0) {
  return testing::addQueryBody(world, "ground", PlaneShape{Vec3::UnitZ(), height}, Vec3::Zero(), Quaternion::identity(), true);
}

ShapeCast sweep(CastShape shape, const Vec3& from, const Vec3& to,
                const Quaternion& orientation = Quaternion::identity()) {
  return {std::move(shape), from, to, orientation};
}

// The touch at `fraction` of the sweep, on `body`, with this normal; the
// point is checked by the caller where the touch has one point.
void expectTouch(const std::optional<ShapeCastHit>& hit, BodyId body, const ShapeCast& cast, double fraction,
                 const Vec3& normal) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, body);
  const double length = (cast.to - cast.from).norm();
  EXPECT_NEAR(hit->fraction * length, fraction * length, kTol);
  EXPECT_NEAR(hit->distance, fraction * length, kTol);
  EXPECT_NEAR((hit->normal - normal).norm(), 0.0, 1e-8) << hit->normal.transpose();
  EXPECT_NEAR(hit->normal.norm(), 1.0, 1e-12);
}

void expectPoint(const std::optional<ShapeCastHit>& hit, const Vec3& point) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR((hit->point - point).norm(), 0.0, kTol) << hit->point.transpose();
}

TEST(ShapeCasts, SphereOntoAPlaneAndOntoASphere) {
  World world;
  const BodyId ground = addGround(world);
  // The sphere's bottom reaches z = 0 when its centre is at 0.5: 4.5 m of 10.
  ShapeCast cast = sweep(SphereShape{0.5}, {1, 2, 5}, {1, 2, -5});
  auto hit = world.castShape(cast);
  expectTouch(hit, ground, cast, 0.45, Vec3::UnitZ());
  expectPoint(hit, {1, 2, 0});

  World pair;
  const BodyId ball = testing::addQueryBody(pair, "ball", SphereShape{1.0}, Vec3::Zero(), Quaternion::identity(), true);
  // Centres 1.5 apart at first touch: x² + 0.3² = 1.5², x = −√2.16.
  cast = sweep(SphereShape{0.5}, {-5, 0.3, 0}, {5, 0.3, 0});
  hit = pair.castShape(cast);
  const double x = -std::sqrt(2.16);
  const Vec3 normal = Vec3(x, 0.3, 0) / 1.5;
  expectTouch(hit, ball, cast, (x + 5) / 10, normal);
  expectPoint(hit, normal);
}

TEST(ShapeCasts, BoxesFaceDownAndTurnedOntoAnEdge) {
  World world;
  const BodyId block = testing::addQueryBody(world, "block", BoxShape{Vec3::Ones()}, Vec3::Zero(), Quaternion::identity(), true);
  // A box of half size 0.5 comes down on the block's top (z = 1): its centre at 1.5.
  ShapeCast cast = sweep(BoxShape{Vec3::Constant(0.5)}, {0.2, 0.1, 3}, {0.2, 0.1, -3});
  auto hit = world.castShape(cast);
  expectTouch(hit, block, cast, 0.25, Vec3::UnitZ());
  // Face on face: any point of the overlap of the two faces.
  EXPECT_NEAR(hit->point.z(), 1.0, 1e-10);
  EXPECT_LE(std::abs(hit->point.x() - 0.2), 0.5 + 1e-10);
  EXPECT_LE(std::abs(hit->point.y() - 0.1), 0.5 + 1e-10);

  // Turned 45° about y, the box stands on an edge 0.5 √2 below its centre.
  World plane;
  const BodyId ground = addGround(plane);
  const Quaternion turned = Quaternion::fromAxisAngle(Vec3::UnitY(), std::numbers::pi / 4);
  cast = sweep(BoxShape{Vec3::Constant(0.5)}, {0, 0, 2}, {0, 0, -2}, turned);
  hit = plane.castShape(cast);
  expectTouch(hit, ground, cast, (2 - 0.5 * std::sqrt(2.0)) / 4, Vec3::UnitZ());
  EXPECT_NEAR(hit->point.x(), 0.0, 1e-10);  // on the edge, which runs along y
  EXPECT_NEAR(hit->point.z(), 0.0, 1e-9);

  // The same turned box onto the block: its lower edge onto the top face.
  cast = sweep(BoxShape{Vec3::Constant(0.5)}, {0, 0, 4}, {0, 0, 0}, turned);
  hit = world.castShape(cast);
  expectTouch(hit, block, cast, (3 - 0.5 * std::sqrt(2.0)) / 4, Vec3::UnitZ());
  EXPECT_NEAR(hit->point.x(), 0.0, 1e-10);
  EXPECT_NEAR(hit->point.z(), 1.0, 1e-10);
}

TEST(ShapeCasts, SphereOntoABoxEdge) {
  World world;
  const BodyId block = testing::addQueryBody(world, "block", BoxShape{Vec3::Ones()}, Vec3::Zero(), Quaternion::identity(), true);
  // A sphere of radius 0.5 along x at height 1.3 meets the top edge
  // (x = −1, z = 1): (x + 1)² + 0.3² = 0.5², so x = −1.4.
  const ShapeCast cast = sweep(SphereShape{0.5}, {-5, 0, 1.3}, {5, 0, 1.3});
  const auto hit = world.castShape(cast);
  expectTouch(hit, block, cast, 0.36, Vec3(-0.8, 0, 0.6));
  expectPoint(hit, {-1, 0, 1});
}

TEST(ShapeCasts, CapsuleAndCylinder) {
  World world;
  const BodyId wall = testing::addQueryBody(world, "wall", BoxShape{Vec3(0.5, 2, 2)}, {5, 0, 0}, Quaternion::identity(), true);
  // An upright capsule of radius 0.25 reaches the wall's face x = 4.5
  // with its axis at x = 4.25; the touch is along its side.
  ShapeCast cast = sweep(CapsuleShape{0.25, 1.0}, {0, 0, 0}, {10, 0, 0});
  auto hit = world.castShape(cast);
  expectTouch(hit, wall, cast, 0.425, -Vec3::UnitX());
  EXPECT_NEAR(hit->point.x(), 4.5, 1e-10);
  EXPECT_LE(std::abs(hit->point.z()), 1.0 + 1e-10);
  // Lying along x, the capsule's cap leads: its tip reaches 4.5 with the
  // centre at 4.5 − 1.25; the point is the tip's.
  const Quaternion lying = Quaternion::fromAxisAngle(Vec3::UnitY(), std::numbers::pi / 2);
  cast = sweep(CapsuleShape{0.25, 1.0}, {0, 0.3, 0.2}, {10, 0.3, 0.2}, lying);
  hit = world.castShape(cast);
  expectTouch(hit, wall, cast, 0.325, -Vec3::UnitX());
  expectPoint(hit, {4.5, 0.3, 0.2});

  World plane;
  const BodyId ground = addGround(plane, 1.0);
  // An upright cylinder lands on its cap (half length 0.5 below the
  // centre), a lying one on its rim (radius 0.3 below).
  cast = sweep(CylinderShape{0.3, 0.5}, {0, 0, 5}, {0, 0, -5});
  expectTouch(plane.castShape(cast), ground, cast, 0.35, Vec3::UnitZ());
  cast = sweep(CylinderShape{0.3, 0.5}, {0, 0, 5}, {0, 0, -5},
               Quaternion::fromAxisAngle(Vec3::UnitX(), std::numbers::pi / 2));
  hit = plane.castShape(cast);
  expectTouch(hit, ground, cast, 0.37, Vec3::UnitZ());
  EXPECT_NEAR(hit->point.x(), 0.0, 1e-12);  // the rim's lowest line runs along y
  EXPECT_NEAR(hit->point.z(), 1.0, 1e-9);
}

TEST(ShapeCasts, MeshAndCompoundReportTheirPieceAndPart) {
  World world;
  // A tetrahedron as a triangle mesh: its slanted face x + y + z = 1.
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const BodyId tetra = testing::addQueryBody(world, "tetra", MeshShape{"tetra", mesh}, {10, 0, 0}, Quaternion::identity(), true);
  // A sphere of radius 0.1 coming down at (10.2, 0.2) meets the slanted
  // face when its centre is 0.1 above the plane: x + y + z = 1 + 0.1 √3.
  ShapeCast cast = sweep(SphereShape{0.1}, {10.2, 0.2, 5}, {10.2, 0.2, -5});
  auto hit = world.castShape(cast);
  const double centreZ = 1 + 0.1 * std::sqrt(3.0) - 0.4;
  expectTouch(hit, tetra, cast, (5 - centreZ) / 10, Vec3(1, 1, 1).normalized());
  expectPoint(hit, Vec3(10.2, 0.2, centreZ) - 0.1 * Vec3(1, 1, 1).normalized());

  // Two spheres and a box in a compound turned 90° about z: part 0 at
  // (0, −1, 0), part 1 at (0, 1, 0), the box (its x half extent along y) at (0, 0, 2).
  CompoundShape compound;
  compound.parts.push_back({SphereShape{0.5}, {-1, 0, 0}, Quaternion::identity(), {}});
  compound.parts.push_back({SphereShape{0.5}, {1, 0, 0}, Quaternion::identity(), {}});
  compound.parts.push_back({BoxShape{Vec3(0.5, 0.25, 0.25)}, {0, 0, 2}, Quaternion::identity(), {}});
  const BodyId body = testing::addQueryBody(world, "compound", compound, Vec3::Zero(),
                          Quaternion::fromAxisAngle(Vec3::UnitZ(), std::numbers::pi / 2), true);
  cast = sweep(BoxShape{Vec3::Constant(0.1)}, {0, -5, 2}, {0, 5, 2});
  hit = world.castShape(cast);
  expectTouch(hit, body, cast, (5 - 0.5 - 0.1) / 10, -Vec3::UnitY());
  EXPECT_EQ(hit->part, 2);
  EXPECT_EQ(hit->piece, 2);
  cast = sweep(SphereShape{0.2}, {-5, 1, 0}, {5, 1, 0});
  hit = world.castShape(cast);
  expectTouch(hit, body, cast, (5 - 0.7) / 10, -Vec3::UnitX());
  EXPECT_EQ(hit->part, 1);
  expectPoint(hit, {-0.5, 1, 0});
}

// A trimesh: a floor of two triangles at z = 0 and a wall leaning over it,
// each triangle seen from both sides as rays see them; the piece is the triangle.
TEST(ShapeCasts, TrimeshTriangles) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0},  // the floor
                    {3, -2, 0}, {3, 2, 0}, {4, 2, 2}};               // a slope rising along +x
  mesh->triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}};
  World world;
  const BodyId ground = testing::addQueryBody(world, "ground", TriangleMeshShape{"floor", mesh}, {0, 0, 1},
                            Quaternion::identity(), true);
  // Straight down onto the floor (at z = 1 in the world): the second triangle.
  ShapeCast cast = sweep(SphereShape{0.25}, {-1, 1, 5}, {-1, 1, -5});
  auto hit = world.castShape(cast);
  expectTouch(hit, ground, cast, (4 - 0.25) / 10, Vec3::UnitZ());
  EXPECT_EQ(hit->piece, 1);
  expectPoint(hit, {-1, 1, 1});
  // From below: the floor is seen from behind too.
  cast = sweep(BoxShape{Vec3::Constant(0.1)}, {0.5, -0.5, -3}, {0.5, -0.5, 3});
  hit = world.castShape(cast);
  expectTouch(hit, ground, cast, (4 - 0.1) / 6, -Vec3::UnitZ());
  EXPECT_EQ(hit->piece, 0);
  // Along x just above the floor, onto the slope 2 (x − 3) − z = 0 (in the
  // mesh's frame): a sphere of radius 0.25 with its centre at z = 0.5 there
  // touches it when its centre is 0.25 from the plane, 6.5 − 2x = 0.25 √5,
  // whose unit normal towards the sphere is (−2, 0, 1)/√5.
  cast = sweep(SphereShape{0.25}, {0, 0, 1.5}, {5, 0, 1.5});
  hit = world.castShape(cast);
  const Vec3 normal = Vec3(-2, 0, 1) / std::sqrt(5.0);
  const double centreX = 3.25 - 0.125 * std::sqrt(5.0);
  expectTouch(hit, ground, cast, centreX / 5, normal);
  EXPECT_EQ(hit->piece, 2);
  expectPoint(hit, Vec3(centreX, 0, 1.5) - 0.25 * normal);
}

TEST(ShapeCasts, StartsInContactMissesAndStandingStill) {
  World world;
  const BodyId block = testing::addQueryBody(world, "block", BoxShape{Vec3::Ones()}, Vec3::Zero(), Quaternion::identity(), true);
  // Starting inside: touched at 0, the normal against the sweep.
  ShapeCast cast = sweep(SphereShape{0.2}, {0.5, 0, 0}, {5, 0, 0});
  auto hit = world.castShape(cast);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, block);
  EXPECT_EQ(hit->fraction, 0.0);
  EXPECT_NEAR((hit->normal - Vec3(-1, 0, 0)).norm(), 0.0, 1e-15);
  // Starting on the surface and leaving it: a touch at 0 too.
  cast = sweep(BoxShape{Vec3::Constant(0.5)}, {0, 0, 1.5}, {0, 0, 5});
  hit = world.castShape(cast);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->fraction, 0.0);
  // Passing beside, stopping short, moving away: nothing.
  EXPECT_FALSE(world.castShape(sweep(SphereShape{0.5}, {-5, 1.6, 0}, {5, 1.6, 0})));
  EXPECT_FALSE(world.castShape(sweep(SphereShape{0.5}, {-5, 0, 0}, {-1.6, 0, 0})));
  EXPECT_FALSE(world.castShape(sweep(SphereShape{0.5}, {-2, 0, 0}, {-5, 0, 0})));
  // Just reaching: the sweep ends 1 mm past the touch.
  hit = world.castShape(sweep(SphereShape{0.5}, {-5, 0, 0}, {-1.499, 0, 0}));
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->fraction * (5 - 1.499), 3.5, kTol);
  // from == to: an overlap test where the shape stands.
  EXPECT_TRUE(world.castShape(sweep(SphereShape{0.5}, {1.4, 0, 0}, {1.4, 0, 0})));
  EXPECT_FALSE(world.castShape(sweep(SphereShape{0.5}, {1.6, 0, 0}, {1.6, 0, 0})));
  // Not finite: nothing. A bad size: an error naming it.
  const double nan = std::nan("");
  EXPECT_FALSE(world.castShape(sweep(SphereShape{0.5}, {nan, 0, 0}, {1, 0, 0})));
  EXPECT_THROW(world.castShape(sweep(SphereShape{-1}, {0, 0, 0}, {1, 0, 0})), std::invalid_argument);
  EXPECT_THROW(world.castShape(sweep(BoxShape{Vec3(1, nan, 1)}, {0, 0, 0}, {1, 0, 0})), std::invalid_argument);
  EXPECT_THROW(world.castShape(sweep(CylinderShape{0.5, 0.0}, {0, 0, 0}, {1, 0, 0})), std::invalid_argument);
  EXPECT_NO_THROW(world.castShape(sweep(CapsuleShape{0.5, 0.0}, {0, 0, 0}, {1, 0, 0})));
}

TEST(ShapeCasts, FiltersAndAllTouches) {
  World world;
  const BodyId ground = addGround(world);
  // The near box in category 2 (and colliding with all), the others in 1.
  BodyDef nearDef;
  nearDef.name = "near";
  nearDef.shape = BoxShape{Vec3::Constant(0.5)};
  nearDef.position = {2, 0, 0.5};
  nearDef.isStatic = true;
  nearDef.collisionFilter = {2, CollisionFilter::kAllBits};
  const BodyId near = *world.createBody(nearDef);
  const BodyId far = testing::addQueryBody(world, "far", BoxShape{Vec3::Constant(0.5)}, {5, 0, 0.5}, Quaternion::identity(), true);
  // A sphere rolling along the ground (touching it from the start) towards the boxes.
  const ShapeCast cast = sweep(SphereShape{0.25}, {0, 0, 0.25}, {10, 0, 0.25});
  auto hit = world.castShape(cast);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, ground);
  EXPECT_EQ(hit->fraction, 0.0);
  const std::vector<ShapeCastHit> all = world.castShapeAll(cast);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].body, ground);
  EXPECT_EQ(all[1].body, near);
  EXPECT_NEAR(all[1].fraction * 10, 1.25, kTol);
  EXPECT_EQ(all[2].body, far);
  EXPECT_NEAR(all[2].fraction * 10, 4.25, kTol);
  // Lifted off the ground, excluding the near box: the far one.
  const ShapeCast lifted = sweep(SphereShape{0.25}, {0, 0, 0.5}, {10, 0, 0.5});
  RayFilter filter;
  filter.excluded = near;
  expectTouch(world.castShape(lifted, filter), far, lifted, 0.425, -Vec3::UnitX());
  // By group and mask: a cast that sees only category 2.
  RayFilter categoryTwo;
  categoryTwo.filter = {1, 2};
  expectTouch(world.castShape(cast, categoryTwo), near, cast, 0.125, -Vec3::UnitX());
}

// The tree's walk (boxes grown by the swept shape's) finds what a sweep
// against every body finds, for every cast shape, in a field of turned
// bodies.
TEST(ShapeCasts, TheTreeFindsWhatEveryBodyWouldGive) {
  World world;
  struct Placed {
    BodyId id;
    ConvexGeometry geometry;
    Transform pose;
  };
  std::vector<Placed> placed;
  scenes::SceneRandom random(0xCA57);
  for (int i = 0; i < 300; ++i) {
    const Vec3 position(random.uniform(-5, 5), random.uniform(-5, 5), random.uniform(-5, 5));
    const Quaternion orientation = random.rotation();
    const double size = random.uniform(0.05, 0.4);
    Shape shape;
    ConvexGeometry geometry;
    switch (i % 3) {
      case 0: shape = SphereShape{size}; geometry = SphereShape{size}; break;
      case 1: shape = BoxShape{Vec3(size, 0.5 * size, 0.3)}; geometry = BoxShape{Vec3(size, 0.5 * size, 0.3)}; break;
      default: shape = CapsuleShape{0.5 * size, size}; geometry = CapsuleShape{0.5 * size, size}; break;
    }
    const BodyId id = testing::addQueryBody(world, "b" + std::to_string(i), shape, position, orientation, true);
    placed.push_back({id, geometry, Transform::fromPose(position, orientation)});
  }
  const CastShape shapes[] = {SphereShape{0.2}, BoxShape{Vec3(0.3, 0.1, 0.2)}, CapsuleShape{0.1, 0.3},
                              CylinderShape{0.15, 0.25}};
  int touches = 0;
  for (int i = 0; i < 400; ++i) {
    const Vec3 from(random.uniform(-6, 6), random.uniform(-6, 6), random.uniform(-6, 6));
    const Vec3 to(random.uniform(-6, 6), random.uniform(-6, 6), random.uniform(-6, 6));
    const ShapeCast cast = sweep(shapes[i % 4], from, to, random.rotation());
    const ConvexGeometry swept = std::visit([](const auto& s) { return ConvexGeometry(s); }, cast.shape);
    const Transform start = Transform::fromPose(from, cast.orientation);
    std::optional<double> nearest;
    BodyId nearestBody;
    for (const Placed& body : placed) {
      const auto touch = sweepAgainstConvex(swept, start, to - from, {&body.geometry, body.pose}, 1.0);
      if (touch && (!nearest || touch->fraction < *nearest)) {
        nearest = touch->fraction;
        nearestBody = body.id;
      }
    }
    const auto hit = world.castShape(cast);
    ASSERT_EQ(hit.has_value(), nearest.has_value()) << "cast " << i;
    if (!hit) continue;
    ++touches;
    EXPECT_NEAR(hit->fraction, *nearest, 1e-7) << "cast " << i;
    // Every touch castShapeAll reports is the brute force's for its body.
    for (const ShapeCastHit& each : world.castShapeAll(cast)) {
      const Placed& body = placed[static_cast<std::size_t>(std::stoi(world.body(each.body).name().substr(1)))];
      const auto touch = sweepAgainstConvex(swept, start, to - from, {&body.geometry, body.pose}, 1.0);
      ASSERT_TRUE(touch.has_value());
      EXPECT_NEAR(each.fraction, touch->fraction, 1e-7);
    }
  }
  EXPECT_GT(touches, 100);
}

}  // namespace
}  // namespace rbsim
