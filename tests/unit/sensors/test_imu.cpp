// The IMU against closed forms: zero specific force in free fall, +g at rest,
// the angular velocity of a spinning body in the sensor frame, and the
// centripetal term of an off-centre sensor on a turntable, at two steps
// and with every integrator.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "unit/sensors/sensor_test_support.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addGround;
using testing::sensorOn;
using testing::settingsWith;
using testing::stepAndReadOne;

constexpr double kG = 9.81;  // m/s²

class ImuAtEveryStep : public ::testing::TestWithParam<std::tuple<double, IntegratorKind>> {
 protected:
  double dt() const { return std::get<0>(GetParam()); }
  IntegratorKind integrator() const { return std::get<1>(GetParam()); }
  SensorDef imuOn(const std::string& body) const { return sensorOn(body, SensorType::Imu, 1.0 / dt()); }
};

TEST_P(ImuAtEveryStep, ReadsNoSpecificForceInFreeFall) {
  World world(settingsWith(dt(), Vec3(0, 0, -kG), integrator()));
  BodyDef box;
  box.name = "box";
  box.shape = BoxShape{Vec3(0.1, 0.2, 0.3)};
  box.orientation = Quaternion::fromRollPitchYaw(0.3, -0.2, 1.1);
  box.linearVelocity = Vec3(1.0, -2.0, 3.0);
  addBody(world, box);
  SensorDef imu = imuOn("box");
  imu.position = Vec3(0.1, -0.05, 0.2);
  imu.orientation = Quaternion::fromRollPitchYaw(0.5, 0.0, -0.7);
  SensorSuite suite({imu}, dt());
  for (int i = 0; i < 20; ++i) {
    const ImuReading reading = stepAndReadOne<ImuReading>(world, suite);
    EXPECT_LT(reading.linearAcceleration.norm(), 1e-9) << "step " << i;
    EXPECT_LT(reading.angularVelocity.norm(), 1e-15);
  }
}

TEST_P(ImuAtEveryStep, ReadsTheAngularVelocityInTheSensorFrame) {
  World world(settingsWith(dt(), Vec3::Zero(), integrator()));
  BodyDef ball;  // a sphere: every axis is principal, ω stays what it was given
  ball.name = "ball";
  ball.shape = SphereShape{0.2};
  ball.orientation = Quaternion::fromRollPitchYaw(0.1, 0.7, -0.4);
  const Vec3 omega(1.0, -2.0, 3.0);
  ball.angularVelocity = omega;
  addBody(world, ball);
  SensorDef imu = imuOn("ball");
  imu.orientation = Quaternion::fromRollPitchYaw(0.0, 0.0, 1.5707963267948966);
  SensorSuite suite({imu}, dt());
  for (int i = 0; i < 10; ++i) {
    const ImuReading reading = stepAndReadOne<ImuReading>(world, suite);
    const Mat3 sensorToWorld = reading.orientation.toRotationMatrix();
    const Vec3 expected = sensorToWorld.transpose() * omega;
    EXPECT_NEAR((reading.angularVelocity - expected).norm(), 0.0, 1e-12) << "step " << i;
    // and the orientation is the body's composed with the sensor's
    const BodyView body = world.body(world.findBody("ball"));
    const Mat3 fromBody = body.rotation() * body.description().shapeRotation.transpose() *
                          imu.orientation.toRotationMatrix();
    EXPECT_LT((sensorToWorld - fromBody).norm(), 1e-12);
  }
}

// A free box spinning about its z axis (a principal axis: ω stays constant)
// with no gravity, the IMU 0.5 m out along the box's x axis: the sensor point
// goes round a circle of radius r = 0.5 m, and its acceleration is ω² r
// towards the axis, which is -x in the sensor frame.
TEST_P(ImuAtEveryStep, ReadsTheCentripetalAccelerationOfAnOffCentreSensorOnATurntable) {
  World world(settingsWith(dt(), Vec3::Zero(), integrator()));
  BodyDef table;
  table.name = "table";
  table.shape = BoxShape{Vec3(0.6, 0.6, 0.05)};
  const double omega = 4.0;  // rad/s
  table.angularVelocity = Vec3(0, 0, omega);
  addBody(world, table);
  SensorDef imu = imuOn("table");
  const double r = 0.5;  // m
  imu.position = Vec3(r, 0, 0);
  SensorSuite suite({imu}, dt());
  for (int i = 0; i < 50; ++i) {
    const ImuReading reading = stepAndReadOne<ImuReading>(world, suite);
    EXPECT_NEAR(reading.linearAcceleration.x(), -omega * omega * r, 1e-9 * omega * omega * r) << "step " << i;
    EXPECT_NEAR(reading.linearAcceleration.y(), 0.0, 1e-9);
    EXPECT_NEAR(reading.linearAcceleration.z(), 0.0, 1e-9);
    EXPECT_NEAR(reading.angularVelocity.z(), omega, 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(StepsAndIntegrators, ImuAtEveryStep,
                         ::testing::Combine(::testing::Values(1e-3, 1e-2),
                                            ::testing::Values(IntegratorKind::ExplicitEuler,
                                                              IntegratorKind::SemiImplicitEuler,
                                                              IntegratorKind::Rk4)));

// The same turntable held by a revolute joint about the world's z axis, in
// gravity: ω² r towards the axis from the velocity change the joint solver
// gives, and +g up.
TEST(Imu, ReadsCentripetalAndGravityOnAJointedTurntable) {
  const double dt = 1e-3;
  World world(settingsWith(dt, Vec3(0, 0, -kG)));
  BodyDef table;
  table.name = "table";
  table.shape = BoxShape{Vec3(0.6, 0.6, 0.05)};
  const double omega = 3.0;
  table.angularVelocity = Vec3(0, 0, omega);
  const BodyId id = addBody(world, table);
  JointDef hinge;
  hinge.name = "spindle";
  hinge.type = JointType::Revolute;
  hinge.bodyB = id;
  hinge.anchor = Vec3::Zero();
  hinge.axis = Vec3::UnitZ();
  ASSERT_TRUE(world.createJoint(hinge).ok());
  SensorDef imu = sensorOn("table", SensorType::Imu, 1000.0);
  const double r = 0.4;
  imu.position = Vec3(0, r, 0);  // along the body's y: the sensor's +y points away from the axis
  SensorSuite suite({imu}, dt);
  for (int i = 0; i < 200; ++i) {
    const ImuReading reading = stepAndReadOne<ImuReading>(world, suite);
    if (i < 5) continue;  // the joint's first steps settle its impulses
    const double w = world.body(id).angularVelocity().z();
    EXPECT_NEAR(reading.linearAcceleration.y(), -w * w * r, 1e-6) << "step " << i;
    EXPECT_NEAR(reading.linearAcceleration.x(), 0.0, 1e-6);
    EXPECT_NEAR(reading.linearAcceleration.z(), kG, 1e-6);
  }
}

TEST(Imu, ReadsPlusGUpAtRestOnAPlaneInTheSensorFrame) {
  for (const bool sleeping : {true, false}) {
    WorldSettings settings = settingsWith(1e-3, Vec3(0, 0, -kG));
    settings.contact.sleeping = sleeping;
    World world(settings);
    addGround(world);
    BodyDef box;
    box.name = "box";
    box.shape = BoxShape{Vec3(0.2, 0.1, 0.05)};
    box.position = Vec3(0, 0, 0.05);
    addBody(world, box);
    SensorDef imu = sensorOn("box", SensorType::Imu, 1000.0);
    imu.position = Vec3(0.15, 0.05, 0.05);
    imu.orientation = Quaternion::fromRollPitchYaw(1.5707963267948966, 0.0, 0.0);  // sensor y up
    SensorSuite suite({imu}, 1e-3);
    ImuReading reading;
    for (int i = 0; i < 2000; ++i) reading = stepAndReadOne<ImuReading>(world, suite);
    // Rolled +90° about x: the sensor's +y is the world's +z, so +g reads along +y.
    const Vec3 expected = reading.orientation.toRotationMatrix().transpose() * Vec3(0, 0, kG);
    EXPECT_NEAR(expected.y(), kG, 1e-9);
    EXPECT_NEAR((reading.linearAcceleration - expected).norm(), 0.0, 1e-6) << "sleeping " << sleeping;
    EXPECT_NEAR(reading.angularVelocity.norm(), 0.0, 1e-6);
  }
}

// Sensors observe: a world steps to the same bits with a suite reading it
// after every step as without.
TEST(Sensors, DoNotChangeTheWorld) {
  const auto run = [](bool withSensors) {
    World world(settingsWith(1e-3, Vec3(0, 0, -kG)));
    addGround(world);
    BodyDef box;
    box.name = "box";
    box.shape = BoxShape{Vec3(0.2, 0.1, 0.05)};
    box.position = Vec3(0, 0, 0.3);
    box.angularVelocity = Vec3(1, 2, 0);
    addBody(world, box);
    SensorDef imu = sensorOn("box", SensorType::Imu, 1000.0);
    SensorDef contact = sensorOn("box", SensorType::Contact, 1000.0);
    SensorDef lidar = sensorOn("box", SensorType::Lidar, 100.0);
    imu.name = "imu";
    contact.name = "contact";
    lidar.name = "lidar";
    lidar.pattern.horizontalSamples = 90;
    lidar.pattern.horizontalMin = -3.0;
    lidar.pattern.horizontalMax = 3.0;
    lidar.pattern.beams = 4;
    lidar.pattern.verticalMin = -0.5;
    lidar.pattern.verticalMax = 0.5;
    SensorSuite suite({imu, contact, lidar}, 1e-3);
    for (int i = 0; i < 500; ++i) {
      if (withSensors) testing::stepAndRead(world, suite);
      else world.step();
    }
    return world.stateHash();
  };
  EXPECT_EQ(run(true), run(false));
}

}  // namespace
}  // namespace rbsim
