// Whole-world free motion: gravity, wrenches through the World API, and the
// long-run health of the orientation.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/math/rotation_matrix.h"
#include "rbsim/physics/world.h"

namespace rbsim {
namespace {

World makeWorld(IntegratorKind kind, const Vec3& gravity) {
  WorldSettings settings;
  settings.dt = 1e-3;
  settings.gravity = gravity;
  settings.integrator = kind;
  return World(settings);
}

BodyId addBox(World& world, const std::string& name, double mass) {
  BodyDef def;
  def.name = name;
  def.shape = BoxShape{Vec3(0.1, 0.2, 0.3)};
  def.mass = mass;
  const auto id = world.createBody(def);
  EXPECT_TRUE(id.ok()) << (id.ok() ? "" : id.error().message);
  return *id;
}

TEST(FreeMotion, Rk4FreeFallIsExact) {
  World world = makeWorld(IntegratorKind::Rk4, Vec3(0, 0, -9.81));
  BodyDef def;
  def.name = "ball";
  def.shape = SphereShape{0.1};
  def.position = Vec3(0, 0, 100);
  def.linearVelocity = Vec3(2, 0, 0);
  const BodyId ball = *world.createBody(def);
  for (int i = 0; i < 3000; ++i) world.step();
  const double t = world.time();
  EXPECT_DOUBLE_EQ(t, 3.0);
  const BodyView body = world.body(ball);
  EXPECT_NEAR(body.position().z(), 100.0 - 0.5 * 9.81 * t * t, 1e-10);
  EXPECT_NEAR(body.position().x(), 2.0 * t, 1e-12);
  EXPECT_NEAR(body.linearVelocity().z(), -9.81 * t, 1e-11);
}

TEST(FreeMotion, WrenchLastsOneStepThenIsCleared) {
  World world = makeWorld(IntegratorKind::SemiImplicitEuler, Vec3::Zero());
  const BodyId box = addBox(world, "box", 2.0);
  world.applyWrench(box, {Vec3(4.0, 0, 0), Vec3(0, 0, 1.0), world.body(box).position(), Wrench::Frame::World});
  world.step();
  const Vec3 momentumAfterOne = world.body(box).linearMomentum();
  const Vec3 spinAfterOne = world.body(box).angularMomentum();
  EXPECT_NEAR(momentumAfterOne.x(), 4.0 * 1e-3, 1e-17);
  EXPECT_NEAR(spinAfterOne.z(), 1e-3, 1e-17);
  for (int i = 0; i < 10; ++i) world.step();
  EXPECT_EQ(world.body(box).linearMomentum(), momentumAfterOne);
  EXPECT_EQ(world.body(box).angularMomentum(), spinAfterOne);
}

TEST(FreeMotion, StaticBodiesNeverMove) {
  World world = makeWorld(IntegratorKind::Rk4, Vec3(0, 0, -9.81));
  BodyDef def;
  def.name = "anchor";
  def.shape = BoxShape{Vec3(1, 1, 1)};
  def.isStatic = true;
  def.position = Vec3(1, 2, 3);
  const BodyId anchor = *world.createBody(def);
  world.applyWrench(anchor, {Vec3(100, 0, 0), Vec3(0, 0, 100), Vec3::Zero(), Wrench::Frame::World});
  for (int i = 0; i < 100; ++i) world.step();
  EXPECT_EQ(world.body(anchor).position(), Vec3(1, 2, 3));
  EXPECT_EQ(world.body(anchor).linearVelocity(), Vec3::Zero());
  EXPECT_EQ(world.body(anchor).angularVelocity(), Vec3::Zero());
}

TEST(FreeMotion, QuaternionNormStaysOneOverAMillionSteps) {
  for (IntegratorKind kind : {IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4}) {
    World world = makeWorld(kind, Vec3::Zero());
    BodyDef def;
    def.name = "tumbler";
    def.shape = BoxShape{Vec3(0.1, 0.2, 0.3)};
    def.angularVelocity = Vec3(7.0, -3.0, 11.0);
    const BodyId id = *world.createBody(def);
    double worst = 0.0;
    for (int i = 0; i < 1000000; ++i) {
      world.step();
      worst = std::max(worst, std::abs(world.body(id).orientation().norm() - 1.0));
    }
    EXPECT_LT(worst, 1e-12) << integratorName(kind);
    EXPECT_LT(orthonormalityError(world.body(id).rotation()), 1e-12);
  }
}

TEST(FreeMotion, InertiaTensorFollowsTheRotation) {
  World world = makeWorld(IntegratorKind::Rk4, Vec3::Zero());
  BodyDef def;
  def.name = "box";
  def.shape = BoxShape{Vec3(0.1, 0.2, 0.3)};
  def.mass = 12.0;
  def.orientation = Quaternion::fromRollPitchYaw(0.5, -0.2, 1.1);
  def.angularVelocity = Vec3(1.0, 2.0, -0.5);
  const BodyView body = world.body(*world.createBody(def));
  // I(t) = R Ibody Rᵀ with Ibody the box's closed form; L = I ω.
  const Vec3 ibody(12.0 / 3 * (0.04 + 0.09), 12.0 / 3 * (0.01 + 0.09), 12.0 / 3 * (0.01 + 0.04));
  const Mat3 r = def.orientation.toRotationMatrix();
  const Mat3 inertia = r * ibody.asDiagonal() * r.transpose();
  EXPECT_LT((body.inertiaWorld() - inertia).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT((body.inverseInertiaWorld() * inertia - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT((body.angularMomentum() - inertia * def.angularVelocity).norm(), 1e-13);
  EXPECT_LT((body.angularVelocity() - def.angularVelocity).norm(), 1e-13);
  // Kinetic energy ½ ωᵀ I ω.
  EXPECT_NEAR(body.kineticEnergy(), 0.5 * def.angularVelocity.dot(inertia * def.angularVelocity),
              1e-13);
}

}  // namespace
}  // namespace rbsim
