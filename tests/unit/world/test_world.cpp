// Creating, finding and removing bodies; placement of the body frame.
#include <gtest/gtest.h>

#include "rbsim/physics/world.h"

namespace rbsim {
namespace {

BodyDef sphereDef(const std::string& name) {
  BodyDef def;
  def.name = name;
  def.shape = SphereShape{0.2};
  return def;
}

TEST(World, CreateFindAndRemoveKeepCreationOrder) {
  World world;
  const BodyId a = *world.createBody(sphereDef("a"));
  const BodyId b = *world.createBody(sphereDef("b"));
  const BodyId c = *world.createBody(sphereDef("c"));
  EXPECT_EQ(world.findBody("b"), b);
  EXPECT_TRUE(world.findBody("nobody").isNull());
  EXPECT_TRUE(world.removeBody(b));
  EXPECT_FALSE(world.isValid(b));
  EXPECT_FALSE(world.removeBody(b));  // stale handle
  ASSERT_EQ(world.bodyCount(), 2);
  EXPECT_EQ(world.bodies()[0].name(), "a");
  EXPECT_EQ(world.bodies()[1].name(), "c");
  EXPECT_EQ(world.body(c).name(), "c");
  // The freed slot is reused with a new generation: the old handle stays dead.
  const BodyId d = *world.createBody(sphereDef("d"));
  EXPECT_EQ(d.index, b.index);
  EXPECT_NE(d.generation, b.generation);
  EXPECT_FALSE(world.isValid(b));
  EXPECT_EQ(world.bodies()[2].name(), "d");
  EXPECT_EQ(world.body(a).name(), "a");
}

TEST(World, RejectsBadBodies) {
  World world;
  ASSERT_TRUE(world.createBody(sphereDef("x")).ok());
  const auto duplicate = world.createBody(sphereDef("x"));
  ASSERT_FALSE(duplicate.ok());
  EXPECT_NE(duplicate.error().message.find("already exists"), std::string::npos);

  BodyDef unnamed = sphereDef("");
  EXPECT_FALSE(world.createBody(unnamed).ok());

  BodyDef both = sphereDef("both");
  both.mass = 1.0;
  both.density = 10.0;
  EXPECT_NE(world.createBody(both).error().message.find("not both"), std::string::npos);

  BodyDef negative = sphereDef("negative");
  negative.mass = -1.0;
  EXPECT_FALSE(world.createBody(negative).ok());

  BodyDef flatSphere = sphereDef("flat");
  flatSphere.shape = SphereShape{0.0};
  EXPECT_FALSE(world.createBody(flatSphere).ok());

  BodyDef dynamicPlane = sphereDef("floor");
  dynamicPlane.shape = PlaneShape{};
  EXPECT_NE(world.createBody(dynamicPlane).error().message.find("static"), std::string::npos);

  BodyDef nan = sphereDef("nan");
  nan.position.x() = std::nan("");
  EXPECT_FALSE(world.createBody(nan).ok());
  EXPECT_EQ(world.bodyCount(), 1);
}

TEST(World, MassOrDensityDecideTheMass) {
  World world;
  BodyDef byMass = sphereDef("by_mass");
  byMass.mass = 3.0;
  EXPECT_EQ(world.body(*world.createBody(byMass)).mass(), 3.0);
  BodyDef byDensity = sphereDef("by_density");
  byDensity.density = 500.0;
  EXPECT_NEAR(world.body(*world.createBody(byDensity)).mass(),
              500.0 * 4.0 / 3.0 * M_PI * 0.008, 1e-12);
  BodyDef byDefault = sphereDef("default");
  EXPECT_NEAR(world.body(*world.createBody(byDefault)).mass(),
              BodyDef::kDefaultDensity * 4.0 / 3.0 * M_PI * 0.008, 1e-10);
}

TEST(World, BodyFrameSitsAtTheShapePoseForPrimitives) {
  World world;
  BodyDef def;
  def.name = "cylinder";
  def.shape = CylinderShape{0.1, 0.4};
  def.position = Vec3(1, 2, 3);
  def.orientation = Quaternion::fromRollPitchYaw(0.1, 0.2, 0.3);
  def.linearVelocity = Vec3(0.5, 0, 0);
  const BodyView body = world.body(*world.createBody(def));
  EXPECT_EQ(body.position(), def.position);
  EXPECT_LT((body.rotation() - def.orientation.toRotationMatrix()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((body.linearVelocity() - def.linearVelocity).norm(), 1e-15);
  EXPECT_EQ(body.description().shapeTranslation, Vec3::Zero());
}

TEST(World, TotalMomentumOfFreeBodiesIsConservedWithoutForces) {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  World world(settings);
  for (int i = 0; i < 5; ++i) {
    BodyDef def;
    def.name = "b" + std::to_string(i);
    def.shape = BoxShape{Vec3(0.1 + 0.05 * i, 0.2, 0.1)};
    def.position = Vec3(i, -i, 2 * i);
    def.linearVelocity = Vec3(1, i, -0.5 * i);
    def.angularVelocity = Vec3(i, 1, 2);
    ASSERT_TRUE(world.createBody(def).ok());
  }
  const Vec3 p0 = world.totalLinearMomentum();
  const Vec3 l0 = world.totalAngularMomentum();
  for (int i = 0; i < 2000; ++i) world.step();
  EXPECT_LT((world.totalLinearMomentum() - p0).norm(), 1e-12 * p0.norm());
  // Angular momentum about the origin: L_spin + x × P, with x moving along P.
  EXPECT_LT((world.totalAngularMomentum() - l0).norm(), 1e-10 * l0.norm());
}

}  // namespace
}  // namespace rbsim
