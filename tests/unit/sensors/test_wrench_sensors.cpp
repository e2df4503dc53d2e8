// Contact and force–torque sensors at rest: a box on the ground carries its
// weight through its contacts, a pendulum's hinge holds its bob's weight.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "unit/sensors/sensor_test_support.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addGround;
using testing::sensorOn;
using testing::settingsWith;
using testing::stepAndReadOne;

constexpr double kG = 9.81;

class ContactSensorWithSolver : public ::testing::TestWithParam<ContactSolverKind> {};

TEST_P(ContactSensorWithSolver, ReadsTheWeightOfABoxRestingOnTheGroundAndItsFourCorners) {
  WorldSettings settings = settingsWith(1e-3, Vec3(0, 0, -kG));
  settings.contact.solver.kind = GetParam();
  settings.contact.sleeping = false;
  World world(settings);
  addGround(world);
  BodyDef box;
  box.name = "box";
  box.mass = 3.0;
  box.shape = BoxShape{Vec3(0.2, 0.15, 0.1)};
  box.position = Vec3(0, 0, 0.1);
  addBody(world, box);
  SensorDef contact = sensorOn("box", SensorType::Contact, 1000.0);
  contact.position = Vec3(0, 0, -0.1);  // at the middle of the bottom face
  SensorSuite suite({contact}, 1e-3);
  ContactReading reading;
  for (int i = 0; i < 1000; ++i) reading = stepAndReadOne<ContactReading>(world, suite);
  EXPECT_EQ(reading.contacts, 4);
  EXPECT_NEAR(reading.force.z(), 3.0 * kG, 1e-6 * 3.0 * kG);
  EXPECT_NEAR(reading.force.head<2>().norm(), 0.0, 1e-6);
  // The corners carry the weight symmetrically about the bottom's middle.
  EXPECT_NEAR(reading.torque.norm(), 0.0, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Solvers, ContactSensorWithSolver,
                         ::testing::Values(ContactSolverKind::SoftStep, ContactSolverKind::SequentialImpulses));

TEST(ContactSensor, ReadsNothingInTheAir) {
  World world(settingsWith(1e-3, Vec3(0, 0, -kG)));
  addGround(world);
  BodyDef ball;
  ball.name = "ball";
  ball.shape = SphereShape{0.1};
  ball.position = Vec3(0, 0, 1);
  addBody(world, ball);
  SensorSuite suite({sensorOn("ball", SensorType::Contact, 1000.0)}, 1e-3);
  const ContactReading reading = stepAndReadOne<ContactReading>(world, suite);
  EXPECT_EQ(reading.contacts, 0);
  EXPECT_EQ(reading.force.norm(), 0.0);
}

TEST(ForceTorqueSensor, ReadsTheHangingWeightAtAPendulumsHingeInItsFrame) {
  World world(settingsWith(1e-3, Vec3(0, 0, -kG)));
  BodyDef bob;
  bob.name = "bob";
  bob.mass = 2.0;
  bob.shape = SphereShape{0.1};
  bob.position = Vec3(0, 0, 1.0);
  const BodyId id = addBody(world, bob);
  JointDef hinge;
  hinge.name = "hinge";
  hinge.type = JointType::Revolute;
  hinge.bodyB = id;
  hinge.anchor = Vec3(0, 0, 1.5);
  hinge.axis = Vec3::UnitX();
  ASSERT_TRUE(world.createJoint(hinge).ok());
  SensorDef ft = sensorOn("bob", SensorType::ForceTorque, 1000.0);
  ft.joint = "hinge";
  ft.position = Vec3(0, 0, 0.5);  // at the hinge
  ft.orientation = Quaternion::fromRollPitchYaw(std::numbers::pi / 2, 0, 0);  // its y is the world's z
  SensorSuite suite({ft}, 1e-3);
  ForceTorqueReading reading;
  for (int i = 0; i < 500; ++i) reading = stepAndReadOne<ForceTorqueReading>(world, suite);
  // The hinge holds the bob up: +m g along the world's z, the sensor's y.
  EXPECT_NEAR(reading.force.y(), 2.0 * kG, 1e-6);
  EXPECT_NEAR(reading.force.x(), 0.0, 1e-6);
  EXPECT_NEAR(reading.force.z(), 0.0, 1e-6);
  EXPECT_NEAR(reading.torque.norm(), 0.0, 1e-6);

  // The same sensor at the bob's centre: the weight acts along the line
  // through both, so still no couple; moved 0.1 m sideways, a couple of
  // m g 0.1 about the world's x.
  SensorDef offset = ft;
  offset.position = Vec3(0, 0.1, 0.5);
  offset.orientation = Quaternion::identity();
  SensorSuite moved({offset}, 1e-3);
  const ForceTorqueReading side = stepAndReadOne<ForceTorqueReading>(world, moved);
  EXPECT_NEAR(side.force.z(), 2.0 * kG, 1e-6);
  // τ_o = τ_anchor + (anchor − o) × F = (0, −0.1, 0) × (0, 0, m g) = (−0.1 m g, 0, 0)
  EXPECT_NEAR(side.torque.x(), -0.1 * 2.0 * kG, 1e-6);
}

}  // namespace
}  // namespace rbsim
