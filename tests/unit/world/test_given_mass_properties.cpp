// Bodies whose mass properties are given as data (BodyDef::inertia and
// centerOfMass): the body frame comes from the given tensor, the collider
// stays where the shape is, and checkpoints carry them bit for bit.
#include <gtest/gtest.h>

#include <memory>

#include "meshio/mesh_io.h"
#include "rbsim/physics/world.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

// diag(1, 2, 3) kg·m² turned by Q into the config frame's axes: the tensor
// a CAD tool reports for a part whose principal axes are not the frame's.
const Quaternion kPrincipalTurn = Quaternion::fromRollPitchYaw(0.4, -0.3, 1.1);
const Vec3 kCenter(0.3, -0.1, 0.2);  // m, config frame

Mat3 turnedTensor() {
  const Mat3 q = kPrincipalTurn.toRotationMatrix();
  const Mat3 turned = q * Vec3(1.0, 2.0, 3.0).asDiagonal() * q.transpose();
  return 0.5 * (turned + turned.transpose());  // exactly symmetric, as a config file writes it
}

BodyDef givenBody(const std::string& name) {
  BodyDef def;
  def.name = name;
  def.shape = SphereShape{0.5};
  def.mass = 7.0;
  def.inertia = turnedTensor();
  def.centerOfMass = kCenter;
  def.position = Vec3(1.0, 2.0, 3.0);
  def.orientation = Quaternion::fromAxisAngle(Vec3(1, 1, 0), 0.7);
  return def;
}

WorldSettings freeSettings() {
  WorldSettings settings;
  settings.dt = 1e-3;
  settings.gravity = Vec3::Zero();
  return settings;
}

TEST(GivenMassProperties, PrincipalMomentsAxesAndCentreOfMassInTheWorld) {
  World world(freeSettings());
  const BodyDef def = givenBody("part");
  const auto id = world.createBody(def);
  ASSERT_TRUE(id.ok()) << id.error().message;
  const BodyView body = world.body(*id);
  EXPECT_TRUE(body.description().massPropertiesGiven);
  EXPECT_EQ(body.mass(), 7.0);
  EXPECT_EQ(body.description().massProperties.centerOfMass, kCenter);
  EXPECT_EQ(body.description().massProperties.inertia, turnedTensor());
  // The volume is still the shape's: 4/3 π r³.
  EXPECT_NEAR(body.description().massProperties.volume, 4.0 / 3.0 * 3.141592653589793 * 0.125,
              1e-15);
  const Vec3 moments = body.dynamics().inertiaBody;
  EXPECT_NEAR(moments.x(), 1.0, 1e-13);
  EXPECT_NEAR(moments.y(), 2.0, 1e-13);
  EXPECT_NEAR(moments.z(), 3.0, 1e-13);
  // The centre of mass in the world: the config frame's pose applied to it.
  const Mat3 frame = def.orientation.normalized().toRotationMatrix();
  EXPECT_LT((body.position() - (def.position + frame * kCenter)).norm(), 1e-15);
  // Body axes in the world are the config frame's turned by Q (up to sign).
  const Mat3 expectedAxes = frame * kPrincipalTurn.toRotationMatrix();
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_NEAR(std::abs(body.rotation().col(axis).dot(expectedAxes.col(axis))), 1.0, 1e-13)
        << axis;
  EXPECT_LT((body.inertiaWorld() - frame * turnedTensor() * frame.transpose()).norm(), 1e-13);
  // The shape's origin (the sphere's centre) is where the config put it.
  const Vec3 shapeOrigin = body.bodyToWorld(body.description().shapeTranslation);
  EXPECT_LT((shapeOrigin - def.position).norm(), 1e-15);
}

TEST(GivenMassProperties, TheShapeCollidesWhereItIsNotAtTheCentreOfMass) {
  // A sphere of radius 0.5 centred at x = 0.6 overlaps a wall from x = 1 by
  // 0.1 m; its centre of mass, 0.5 m behind the centre, is 0.9 m from it.
  World world(freeSettings());
  BodyDef wall;
  wall.name = "wall";
  wall.isStatic = true;
  wall.shape = BoxShape{Vec3(0.5, 2.0, 2.0)};
  wall.position = Vec3(1.5, 0.0, 0.0);
  ASSERT_TRUE(world.createBody(wall).ok());
  BodyDef ball;
  ball.name = "ball";
  ball.shape = SphereShape{0.5};
  ball.mass = 1.0;
  ball.inertia = Mat3(Vec3(0.1, 0.2, 0.2).asDiagonal());
  ball.centerOfMass = Vec3(-0.5, 0.0, 0.0);
  ball.position = Vec3(0.6, 0.0, 0.0);
  const auto id = world.createBody(ball);
  ASSERT_TRUE(id.ok()) << id.error().message;
  EXPECT_NEAR(world.body(*id).position().x(), 0.1, 1e-15);
  world.step();
  ASSERT_EQ(world.contacts().size(), 1u);
  const SolvedManifold& contact = world.contacts()[0];
  ASSERT_GE(contact.pointCount, 1);
  EXPECT_NEAR(contact.points[0].depth, 0.1, 1e-9);
  EXPECT_NEAR(std::abs(contact.normal.x()), 1.0, 1e-12);
}

TEST(GivenMassProperties, CreateBodyRefusesWhatTheConfigRefuses) {
  World world(freeSettings());
  BodyDef def = givenBody("a");
  def.mass.reset();
  EXPECT_NE(world.createBody(def).error().message.find("needs the body's mass"), std::string::npos);
  def = givenBody("b");
  def.isStatic = true;
  EXPECT_NE(world.createBody(def).error().message.find("static body has no mass properties"),
            std::string::npos);
  def = givenBody("c");
  def.inertia.reset();
  EXPECT_NE(world.createBody(def).error().message.find("centre of mass needs an inertia"),
            std::string::npos);
  def = givenBody("d");
  (*def.inertia)(0, 1) += 0.1;
  EXPECT_NE(world.createBody(def).error().message.find("must be symmetric"), std::string::npos);
  def = givenBody("e");
  def.inertia = Mat3(Vec3(1.0, 1.0, 2.5).asDiagonal());
  EXPECT_NE(world.createBody(def).error().message.find("at most the sum"), std::string::npos);
  EXPECT_EQ(world.bodyCount(), 0);
}

TEST(GivenMassProperties, CheckpointRoundTripIsBitIdentical) {
  WorldSettings settings;
  settings.dt = 1e-3;
  World original(settings);
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  ASSERT_TRUE(original.createBody(ground).ok());
  BodyDef part = givenBody("part");
  part.position = Vec3(0.0, 0.0, 0.6);
  part.angularVelocity = Vec3(0.5, 3.0, -1.0);
  ASSERT_TRUE(original.createBody(part).ok());
  // A mesh and a compound may have given mass properties too.
  auto cube = loadMesh(std::string(rbsim::test_support::kTestDataDir) + "/meshes/cube.obj");
  ASSERT_TRUE(cube.ok());
  BodyDef mesh = givenBody("mesh");
  mesh.shape = MeshShape{"cube.obj", std::make_shared<const TriangleMesh>(std::move(cube).value())};
  mesh.position = Vec3(2.0, 0.0, 1.0);
  ASSERT_TRUE(original.createBody(mesh).ok());
  BodyDef compound = givenBody("compound");
  CompoundShape parts;
  parts.parts.push_back(
      {BoxShape{Vec3(0.2, 0.05, 0.05)}, Vec3::Zero(), Quaternion::identity(), {}});
  parts.parts.push_back({SphereShape{0.1}, Vec3(0.3, 0, 0), Quaternion::identity(), {}});
  compound.shape = parts;
  compound.position = Vec3(-2.0, 0.0, 0.5);
  ASSERT_TRUE(original.createBody(compound).ok());
  for (int i = 0; i < 500; ++i) original.step();
  ASSERT_GT(original.contactPointCount(), 0) << "something landed";

  const auto bytes = original.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  auto restored = World::decodeSnapshot(*bytes, settings);
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  for (const char* name : {"part", "mesh", "compound"}) {
    const BodyDescription& a = original.body(original.findBody(name)).description();
    const BodyDescription& b = restored->body(restored->findBody(name)).description();
    EXPECT_TRUE(b.massPropertiesGiven) << name;
    EXPECT_EQ(b.massProperties.inertia, a.massProperties.inertia) << name;
    EXPECT_EQ(b.massProperties.centerOfMass, a.massProperties.centerOfMass) << name;
    EXPECT_EQ(b.shapeRotation, a.shapeRotation) << name;
  }
  EXPECT_FALSE(restored->body(restored->findBody("ground")).description().massPropertiesGiven);
  EXPECT_EQ(*restored->encodeSnapshot(), *bytes);
  for (int i = 0; i < 500; ++i) {
    original.step();
    restored->step();
    ASSERT_EQ(restored->stateHash(), original.stateHash()) << "step " << original.stepCount();
  }
}

}  // namespace
}  // namespace rbsim
