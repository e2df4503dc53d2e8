// Trimesh bodies in stepping worlds, each against the same world with an
// analytic plane (or box) in its place: a floor made of triangles must act
// as the plane it lies in.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "physics/collision/collider.h"
#include "physics/collision/time_of_impact.h"
#include "unit/collision/triangle_mesh_test_meshes.h"
#include "unit/solver/contact_test_worlds.h"
#include "unit/world/terrain_test_worlds.h"

namespace rbsim {
namespace {

BodyId addTrimesh(World& world, TriangleMesh mesh, const Quaternion& orientation = Quaternion::identity(),
                  const Vec3& position = Vec3::Zero()) {
  BodyDef def;
  def.name = "terrain";
  def.shape = TriangleMeshShape{"test grid", std::make_shared<const TriangleMesh>(std::move(mesh))};
  def.isStatic = true;
  def.orientation = orientation;
  def.position = position;
  auto id = world.createBody(def);
  EXPECT_TRUE(id.ok()) << (id.ok() ? "" : id.error().message);
  return *id;
}

Collider buildColliderForTest(const Shape& shape) {
  auto collider = buildCollider(shape, Transform::identity(), "test");
  EXPECT_TRUE(collider) << (collider ? "" : collider.error().message);
  return std::move(collider).value();
}

class TrimeshWorlds : public ::testing::TestWithParam<ContactSolverKind> {};

TEST_P(TrimeshWorlds, ASphereRollsDownATriangleSlopeAsDownAPlane) {
  // A 20 × 20 grid of triangle pairs, 5 m across, tilted by 0.2 rad about y.
  const Quaternion tilt = Quaternion::fromAxisAngle(Vec3::UnitY(), 0.2);
  World onMesh(testing::terrainSettings(GetParam(), 0.0, 0.6));
  World onPlane(testing::terrainSettings(GetParam(), 0.0, 0.6));
  addTrimesh(onMesh, testing::flatGrid(20, 2.5), tilt);
  testing::addGroundPlane(onPlane, tilt);
  const double radius = 0.1;
  // Resting on the slope at local (1.5, 0.13): it rolls down towards −x.
  const Vec3 start = tilt.toRotationMatrix() * Vec3(1.5, 0.13, radius);
  const BodyId ballOnMesh = testing::addSphere(onMesh, "ball", radius, start);
  const BodyId ballOnPlane = testing::addSphere(onPlane, "ball", radius, start);
  double largest = 0.0;
  for (int i = 0; i < 1000; ++i) {  // 1 s
    onMesh.step();
    onPlane.step();
    largest = std::max(largest, (onMesh.body(ballOnMesh).position() -
                                 onPlane.body(ballOnPlane).position()).norm());
  }
  const Vec3 travelled = onPlane.body(ballOnPlane).position() - start;
  // It did roll: (5/7) g sin θ t² / 2 = 0.694 m for a rolling ball.
  EXPECT_NEAR(travelled.norm(), 5.0 / 7.0 * 9.81 * std::sin(0.2) / 2.0, 0.02);
  EXPECT_LT(largest, 1e-6) << "the ball on triangles left the ball on the plane by " << largest << " m";
}

TEST_P(TrimeshWorlds, ABoxSlidesAcrossATriangleFloorWithoutBumping) {
  // A 10 × 10 grid of triangle pairs, 1 m cells; the box crosses cell edges
  // and diagonals at an angle.
  World onMesh(testing::terrainSettings(GetParam(), 0.0, 0.2));
  World onPlane(testing::terrainSettings(GetParam(), 0.0, 0.2));
  addTrimesh(onMesh, testing::flatGrid(10, 5.0));
  testing::addGroundPlane(onPlane);
  const Vec3 half(0.2, 0.15, 0.1);
  const Vec3 start(-3.0, -0.37, 0.1);
  const Vec3 velocity(3.0, 0.8, 0.0);
  const BodyId onMeshBox = testing::addBox(onMesh, "box", half, start, Quaternion::identity(), velocity);
  const BodyId onPlaneBox = testing::addBox(onPlane, "box", half, start, Quaternion::identity(), velocity);
  double largestHeightGap = 0.0;
  for (int i = 0; i < 2000; ++i) {  // 2 s: slides about 2.4 m, then rests
    onMesh.step();
    onPlane.step();
    largestHeightGap = std::max(largestHeightGap, std::abs(onMesh.body(onMeshBox).position().z() -
                                                           onPlane.body(onPlaneBox).position().z()));
  }
  EXPECT_GT(onPlane.body(onPlaneBox).position().x() - start.x(), 2.0) << "it slid across several cells";
  EXPECT_LT(largestHeightGap, 1e-6);
  // Sideways the two part by millimetres: the solver applies friction at
  // each manifold's centroid (patch friction), and a face split over
  // several triangles is several patches at other centroids.
  EXPECT_LT((onMesh.body(onMeshBox).position() - onPlane.body(onPlaneBox).position()).norm(), 0.01);
}

TEST_P(TrimeshWorlds, ABallBouncesOnATriangleFloorAsOnAPlane) {
  World onMesh(testing::terrainSettings(GetParam(), 0.8, 0.0));
  World onPlane(testing::terrainSettings(GetParam(), 0.8, 0.0));
  addTrimesh(onMesh, testing::flatGrid(4, 2.0));
  testing::addGroundPlane(onPlane);
  const Vec3 start(0.31, -0.17, 1.0);
  const BodyId meshBall = testing::addSphere(onMesh, "ball", 0.1, start);
  const BodyId planeBall = testing::addSphere(onPlane, "ball", 0.1, start);
  double apexMesh = 0.0, apexPlane = 0.0;
  bool bounced = false;
  for (int i = 0; i < 1500; ++i) {
    onMesh.step();
    onPlane.step();
    if (onPlane.body(planeBall).linearVelocity().z() > 0.0) bounced = true;
    if (bounced) {
      apexMesh = std::max(apexMesh, onMesh.body(meshBall).position().z());
      apexPlane = std::max(apexPlane, onPlane.body(planeBall).position().z());
    }
  }
  ASSERT_TRUE(bounced);
  // e² of the 0.9 m drop, above the radius (within the step's discretisation).
  EXPECT_NEAR(apexPlane - 0.1, 0.64 * 0.9, 0.01);
  EXPECT_NEAR(apexMesh, apexPlane, 1e-9);
}

// A box resting across many triangles of a floor is one patch: one
// manifold of four points, its bottom corners, as on a plane (the
// triangles' coplanar manifolds merged, triangle_mesh_contacts.h).
TEST_P(TrimeshWorlds, ABoxOnManyTrianglesIsOnePatchOfItsFourCorners) {
  World onMesh(testing::terrainSettings(GetParam(), 0.0, 0.5));
  World onPlane(testing::terrainSettings(GetParam(), 0.0, 0.5));
  addTrimesh(onMesh, testing::flatGrid(40, 2.0));  // cells of 0.1 m: the box spans a dozen triangles
  testing::addGroundPlane(onPlane);
  const Vec3 start(0.03, -0.02, 0.1);
  testing::addBox(onMesh, "box", Vec3(0.15, 0.1, 0.1), start);
  testing::addBox(onPlane, "box", Vec3(0.15, 0.1, 0.1), start);
  for (int i = 0; i < 200; ++i) {
    onMesh.step();
    onPlane.step();
  }
  ASSERT_EQ(onMesh.contacts().size(), 1u);
  ASSERT_EQ(onPlane.contacts().size(), 1u);
  const SolvedManifold& patch = onMesh.contacts()[0];
  ASSERT_EQ(patch.pointCount, 4);
  for (int p = 0; p < 4; ++p) {
    const Vec3& point = patch.points[p].point;
    EXPECT_NEAR(std::abs(point.x() - start.x()), 0.15, 1e-6) << p;
    EXPECT_NEAR(std::abs(point.y() - start.y()), 0.1, 1e-6) << p;
    EXPECT_NEAR(point.z(), 0.0, 1e-4) << p;
  }
  // It carries the box's weight, as the plane's does.
  double load = 0.0, planeLoad = 0.0;
  for (int p = 0; p < 4; ++p) {
    load += patch.points[p].normalImpulse;
    planeLoad += onPlane.contacts()[0].points[p].normalImpulse;
  }
  EXPECT_NEAR(load, planeLoad, 1e-9 * planeLoad);
}

TEST_P(TrimeshWorlds, ABoxRestsInTheCornerOfAStep) {
  // Floor z = 0 for x < 0, a 0.5 m wall at x = 0, the top beyond: the box
  // slides 5 cm into the concave corner, pushed by a tilt of gravity
  // (1 m/s² along x, more than friction's 0.05 × 9.81 holds), and rests there.
  WorldSettings settings = testing::terrainSettings(GetParam(), 0.0, 0.05);
  settings.gravity = Vec3(1.0, 0.0, -9.81);
  World world(settings);
  addTrimesh(world, testing::stepMesh(0.5));
  const Vec3 half(0.2, 0.2, 0.2);
  const BodyId box = testing::addBox(world, "box", half, Vec3(-0.25, 0.1, 0.21));
  for (int i = 0; i < 1500; ++i) world.step();
  const BodyView body = world.body(box);
  const Vec3 settled = body.position();
  for (int i = 0; i < 500; ++i) world.step();
  // Against the wall and on the floor, level, and still for the last 0.5 s.
  EXPECT_NEAR(body.position().x(), -0.2, 1e-3);
  EXPECT_NEAR(body.position().z(), 0.2, 1e-3);
  EXPECT_NEAR(body.position().y(), 0.1, 1e-5);
  EXPECT_LT((body.position() - settled).norm(), 1e-6);
  EXPECT_LT(body.linearVelocity().norm(), 1e-4);
  EXPECT_LT(body.angularVelocity().norm(), 1e-4);
  EXPECT_LT(std::abs(body.orientation().w) - 1.0, 1e-9);
  EXPECT_GT(std::abs(body.orientation().w), 1.0 - 1e-6);
}

TEST_P(TrimeshWorlds, ACompoundAndACylinderLandOnTrianglesAsOnAPlane) {
  // A dumbbell (two spheres and a rod, as compound parts) and a standing
  // cylinder dropped 5 cm onto a grid, against the same on a plane.
  World onMesh(testing::terrainSettings(GetParam(), 0.0, 0.5));
  World onPlane(testing::terrainSettings(GetParam(), 0.0, 0.5));
  addTrimesh(onMesh, testing::flatGrid(6, 3.0));
  testing::addGroundPlane(onPlane);
  BodyDef dumbbell;
  dumbbell.name = "dumbbell";
  const Quaternion alongX = Quaternion::fromAxisAngle(Vec3::UnitY(), 0.5 * M_PI);
  dumbbell.shape = CompoundShape{{
      CompoundPart{SphereShape{0.1}, Vec3(-0.4, 0, 0), Quaternion::identity(), {}},
      CompoundPart{SphereShape{0.1}, Vec3(0.4, 0, 0), Quaternion::identity(), {}},
      CompoundPart{CapsuleShape{0.03, 0.3}, Vec3::Zero(), alongX, {}},
  }};
  dumbbell.position = Vec3(0.13, 0.21, 0.15);
  BodyDef can;
  can.name = "can";
  can.shape = CylinderShape{0.1, 0.2};
  can.position = Vec3(-1.3, -0.6, 0.25);
  for (World* world : {&onMesh, &onPlane}) {
    ASSERT_TRUE(world->createBody(dumbbell).ok());
    ASSERT_TRUE(world->createBody(can).ok());
  }
  for (int i = 0; i < 1000; ++i) {
    onMesh.step();
    onPlane.step();
  }
  for (const char* name : {"dumbbell", "can"}) {
    const Vec3 meshAt = onMesh.body(onMesh.findBody(name)).position();
    const Vec3 planeAt = onPlane.body(onPlane.findBody(name)).position();
    // Heights as on the plane; sideways within 10 µm (the soft step's
    // friction acts per manifold, and the cylinder's cap is split between
    // two triangles: a few µm of creep while it settles).
    EXPECT_LT(std::abs(meshAt.z() - planeAt.z()), 1e-6) << name;
    EXPECT_LT((meshAt - planeAt).norm(), 1e-5) << name << ": " << (meshAt - planeAt).transpose();
    EXPECT_LT(onMesh.body(onMesh.findBody(name)).linearVelocity().norm(), 1e-4) << name;
  }
  EXPECT_NEAR(onMesh.body(onMesh.findBody("dumbbell")).position().z(), 0.1, 1e-3);
  EXPECT_NEAR(onMesh.body(onMesh.findBody("can")).position().z(), 0.2, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, TrimeshWorlds,
                         ::testing::Values(ContactSolverKind::SoftStep,
                                           ContactSolverKind::SequentialImpulses),
                         [](const ::testing::TestParamInfo<ContactSolverKind>& solver) {
                           return solver.param == ContactSolverKind::SoftStep ? "SoftStep"
                                                                               : "SequentialImpulses";
                         });

// A 1 cm sphere at 500 m/s towards a wall that is two triangles (a 2 m
// square at x = 0.5 facing −x), no gravity: as the box-wall shot of
// test_continuous_collision, it must stop at the wall.
double farthestShot(ContactModel model, bool continuous) {
  WorldSettings settings = testing::contactSettings(0.0, 0.0);
  settings.gravity = Vec3::Zero();
  settings.contact.model = model;
  World world(settings);
  TriangleMesh wall;
  wall.vertices = {{0.5, -1, -1}, {0.5, 1, -1}, {0.5, 1, 1}, {0.5, -1, 1}};
  wall.triangles = {{0, 2, 1}, {0, 3, 2}};  // fronts facing −x
  addTrimesh(world, wall);
  BodyDef bullet;
  bullet.name = "bullet";
  bullet.shape = SphereShape{0.01};
  bullet.position = Vec3(0.2, 0.013, -0.007);
  bullet.linearVelocity = Vec3(500.0, 0, 0);
  bullet.continuousCollision = continuous;
  const BodyId id = *world.createBody(bullet);
  double farthest = 0.0;
  for (int i = 0; i < 10; ++i) {
    world.step();
    farthest = std::max(farthest, world.body(id).position().x());
  }
  return farthest;
}

TEST(TrimeshContinuousCollision, AFastSphereDoesNotTunnelThroughATriangleWall) {
  // The impulse model's contacts reach as far as the sphere moves in a
  // step; its impact is found on the triangle, at the time of impact.
  for (const bool continuous : {false, true}) {
    EXPECT_LT(farthestShot(ContactModel::Impulse, continuous), 0.49 + 1e-6) << continuous;
    EXPECT_GT(farthestShot(ContactModel::Impulse, continuous), 0.49 - 1e-3) << continuous;
  }
  // The penalty model has no speculative reach: it tunnels.
  EXPECT_GT(farthestShot(ContactModel::Penalty, false), 0.6);
}

TEST(TrimeshContinuousCollision, ConservativeAdvancementFindsTheTriangleWall) {
  // The sweep of continuous collision (conservativeAdvancement, through the
  // distance to the mesh): the sphere of radius 0.01 from x = 0.2 at 0.5 m
  // per step touches the wall x = 0.5 at fraction (0.5 − 0.01 − 0.2) / 0.5.
  TriangleMesh wall;
  wall.vertices = {{0.5, -1, -1}, {0.5, 1, -1}, {0.5, 1, 1}, {0.5, -1, 1}};
  wall.triangles = {{0, 2, 1}, {0, 3, 2}};
  const auto mesh = buildColliderForTest(TriangleMeshShape{"wall", std::make_shared<const TriangleMesh>(wall)});
  const auto ball = buildColliderForTest(SphereShape{0.01});
  RigidState start;
  start.position = Vec3(0.2, 0.013, -0.007);
  const SweptMotion motion = SweptMotion::fromVelocities(start, Vec3(500, 0, 0), Vec3::Zero(), 1e-3);
  RigidState fixed;
  const SweptMotion still = SweptMotion::fromVelocities(fixed, Vec3::Zero(), Vec3::Zero(), 1e-3);
  const TimeOfImpact impact = conservativeAdvancement(ball, motion, mesh, still, CcdSettings{});
  ASSERT_EQ(impact.status, ImpactStatus::Hit);
  EXPECT_NEAR(impact.fraction, 0.58, 3e-4);  // stops within 0.1 mm (CcdSettings::tolerance)
  EXPECT_LT((impact.normal - Vec3(1, 0, 0)).norm(), 1e-9);
}

TEST(TrimeshBodies, OnlyAStaticBodyMayBeATrimeshAndItsTrianglesAreChecked) {
  World world;
  BodyDef def;
  def.name = "ramp";
  def.shape = TriangleMeshShape{"ramp.obj", std::make_shared<const TriangleMesh>(testing::flatGrid(1, 1.0))};
  const auto dynamic = world.createBody(def);
  ASSERT_FALSE(dynamic.ok());
  EXPECT_NE(dynamic.error().message.find("body 'ramp'"), std::string::npos);
  EXPECT_NE(dynamic.error().message.find("a trimesh can only be a static body"), std::string::npos);

  TriangleMesh bad = testing::flatGrid(1, 1.0);
  bad.triangles.push_back({0, 0, 1});
  def.shape = TriangleMeshShape{"ramp.obj", std::make_shared<const TriangleMesh>(bad)};
  def.isStatic = true;
  const auto degenerate = world.createBody(def);
  ASSERT_FALSE(degenerate.ok());
  EXPECT_NE(degenerate.error().message.find("ramp.obj"), std::string::npos);
  EXPECT_NE(degenerate.error().message.find("triangle 2"), std::string::npos);
}

TEST(TrimeshBodies, ACheckpointKeepsTheTrimesh) {
  World world;
  addTrimesh(world, testing::stepMesh(0.5));
  testing::addSphere(world, "ball", 0.1, Vec3(-1.0, 0.0, 0.3));
  for (int i = 0; i < 100; ++i) world.step();
  const auto bytes = world.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  auto copy = World::decodeSnapshot(*bytes, world.settings());
  ASSERT_TRUE(copy.ok()) << copy.error().message;
  const auto* shape =
      std::get_if<TriangleMeshShape>(&copy->body(copy->findBody("terrain")).description().shape);
  ASSERT_NE(shape, nullptr);
  EXPECT_EQ(shape->mesh->triangles.size(), 6u);
  for (int i = 0; i < 100; ++i) {
    world.step();
    copy->step();
  }
  EXPECT_EQ(world.body(world.findBody("ball")).position(), copy->body(copy->findBody("ball")).position());
}

}  // namespace
}  // namespace rbsim
