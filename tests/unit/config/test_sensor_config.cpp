// The `sensors:` list of a world file: each type read as written, the
// example world loads, and every mistake reported at its file:line:column
// with the sensor's name.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "config/config_loader.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

// Lines 1 to 7; the sensors list starts on line 8, its first entry on line 9.
const std::string kWorld =
    "world: {dt: 0.001}\n"
    "bodies:\n"
    "  - {name: ground, static: true, shape: {type: plane}}\n"
    "  - {name: cart, position: [0, 0, 0.1], shape: {type: box, half_extents: [0.3, 0.2, 0.1]}}\n"
    "  - {name: bob, position: [0, 0, 1], shape: {type: sphere, radius: 0.1}}\n"
    "joints:\n"
    "  - {name: hinge, type: revolute, body_a: world, body_b: bob, anchor: [0, 0, 1.5], axis: [1, 0, 0]}\n";

Expected<Config> load(const std::string& sensors) {
  return parseConfig(kWorld + "sensors:\n" + sensors, "s.yaml", "");
}

std::string errorOf(const std::string& sensors) {
  const Expected<Config> config = load(sensors);
  if (config.ok()) {
    ADD_FAILURE() << "accepted:\n" << sensors;
    return "";
  }
  return config.error().message;
}

TEST(SensorConfig, EveryTypeIsReadAsWritten) {
  const Expected<Config> config = load(
      "  - name: imu\n"
      "    type: imu\n"
      "    body: cart\n"
      "    position: [0.1, 0, 0.1]\n"
      "    rpy: [0, 0, 1.5707963267948966]\n"
      "    rate: 1000\n"
      "    noise: {linear_acceleration: 0.02, angular_velocity: 0.001, seed: 0xFFFFFFFFFFFFFFFF}\n"
      "  - {name: touch, type: contact, body: cart, rate: 100, noise: {force: 0.5, torque: 0.1}}\n"
      "  - {name: ft, type: force_torque, joint: hinge, rate: 500, orientation: [0, 1, 0, 0]}\n"
      "  - {name: sonar, type: range, body: cart, rate: 20, min_range: 0.05, max_range: 4, report_bodies: true}\n"
      "  - name: scanner\n"
      "    type: lidar\n"
      "    body: cart\n"
      "    rate: 10\n"
      "    horizontal: {samples: 1800, min: -3.14159, max: 3.14}\n"
      "    vertical: {beams: 16, min: -0.26, max: 0.26}\n"
      "    max_range: 30\n"
      "    noise: {range: 0.01, seed: 3}\n");
  ASSERT_TRUE(config.ok()) << config.error().message;
  ASSERT_EQ(config->sensors.size(), 5u);
  const SensorDef& imu = config->sensors[0];
  EXPECT_EQ(imu.type, SensorType::Imu);
  EXPECT_EQ(imu.body, "cart");
  EXPECT_EQ(imu.position, Vec3(0.1, 0, 0.1));
  EXPECT_NEAR(imu.orientation.w, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(imu.orientation.z, std::sqrt(0.5), 1e-15);
  EXPECT_EQ(imu.rate, 1000.0);
  EXPECT_EQ(imu.noise.linearAcceleration, 0.02);
  EXPECT_EQ(imu.noise.angularVelocity, 0.001);
  EXPECT_EQ(imu.noise.seed, 0xFFFFFFFFFFFFFFFFULL);
  EXPECT_NE(imu.source.find("s.yaml:9:5: sensors[0]"), std::string::npos) << imu.source;
  EXPECT_EQ(config->sensors[1].type, SensorType::Contact);
  EXPECT_EQ(config->sensors[1].noise.force, 0.5);
  const SensorDef& ft = config->sensors[2];
  EXPECT_EQ(ft.type, SensorType::ForceTorque);
  EXPECT_EQ(ft.joint, "hinge");
  EXPECT_EQ(ft.body, "bob");  // the joint's child
  EXPECT_EQ(ft.orientation.x, 1.0);
  const SensorDef& sonar = config->sensors[3];
  EXPECT_EQ(sonar.pattern.rayCount(), 1);
  EXPECT_EQ(sonar.pattern.minRange, 0.05);
  EXPECT_EQ(sonar.pattern.maxRange, 4.0);
  EXPECT_TRUE(sonar.pattern.reportBodies);
  const SensorDef& scanner = config->sensors[4];
  EXPECT_EQ(scanner.type, SensorType::Lidar);
  EXPECT_EQ(scanner.pattern.horizontalSamples, 1800);
  EXPECT_EQ(scanner.pattern.beams, 16);
  EXPECT_EQ(scanner.pattern.verticalMin, -0.26);
  EXPECT_EQ(scanner.pattern.maxRange, 30.0);
  EXPECT_EQ(scanner.noise.range, 0.01);
  EXPECT_EQ(scanner.noise.seed, 3u);
}

TEST(SensorConfig, TheExampleWorldLoads) {
  const Expected<Config> config = loadConfig(std::string(test_support::kTestDataDir) + "/../../config/worlds/sensors.yaml");
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_EQ(config->sensors.size(), 5u);
}

TEST(SensorConfig, ARobotLinkIsItsBody) {
  // A robot's links are bodies named robot/link; robot and link name one.
  const std::string message = errorOf("  - {name: a, type: imu, robot: arm, link: link1, rate: 100}\n");
  EXPECT_NE(message.find("s.yaml:9:44: sensors[0].link: sensor \"a\": no robot link named \"arm/link1\""),
            std::string::npos)
      << message;
}

struct BadSensor {
  const char* yaml;
  const char* expected;  // part of the message, with the file:line:column
};

class SensorConfigError : public ::testing::TestWithParam<BadSensor> {};

TEST_P(SensorConfigError, NamesWhatAndWhere) {
  const std::string message = errorOf(GetParam().yaml);
  EXPECT_NE(message.find(GetParam().expected), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Mistakes, SensorConfigError,
    ::testing::Values(
        BadSensor{"  - {name: a, type: sonar, body: cart, rate: 10}\n",
                  "s.yaml:9:21: sensors[0].type: sensor \"a\": unknown sensor type \"sonar\" (expected imu"},
        BadSensor{"  - {name: a, type: imu, body: crat, rate: 10}\n",
                  "s.yaml:9:32: sensors[0].body: sensor \"a\": no body named \"crat\" (did you mean 'cart'?)"},
        BadSensor{"  - {name: a, type: force_torque, joint: hing, rate: 10}\n",
                  "sensors[0].joint: sensor \"a\": no joint named \"hing\" (did you mean 'hinge'?)"},
        BadSensor{"  - {name: a, type: imu, body: cart, rate: 0}\n", "s.yaml:9:44: sensors[0].rate: expected a positive"},
        BadSensor{"  - {name: a, type: imu, body: cart, rate: -5}\n", "sensors[0].rate: expected a positive"},
        BadSensor{"  - {name: a, type: imu, body: cart, rate: 2000}\n",
                  "s.yaml:9:44: sensors[0].rate: sensor \"a\": rate 2000 Hz is above the world's step rate (1000 Hz, 1/dt)"},
        BadSensor{"  - {name: a, type: imu, body: cart}\n", "s.yaml:9:5: sensors[0].rate: missing required key (sensor \"a\")"},
        BadSensor{"  - {name: a, type: imu, body: cart, rate: 10, position: [0, 1]}\n",
                  "sensors[0].position: expected a list of 3 numbers"},
        BadSensor{"  - {name: a, type: imu, body: cart, rate: 10, orientation: [0, 0, 0, 0]}\n",
                  "sensors[0].orientation"},
        BadSensor{"  - {name: a, type: imu, body: cart, rate: 10, orientation: [1, 0, 0, 0], rpy: [0, 0, 0]}\n",
                  "sensors[0].rpy"},
        BadSensor{"  - {name: a, type: imu, body: cart, rate: 10}\n  - {name: a, type: contact, body: cart, rate: 10}\n",
                  "s.yaml:10:12: sensors[1].name: sensor \"a\": a second sensor of that name (the first is at s.yaml:9:5: sensors[0])"},
        BadSensor{"  - {name: my-imu, type: imu, body: cart, rate: 10}\n",
                  "s.yaml:9:12: sensors[0].name: a sensor's name is 1 to 64 letters, digits or '_'"},
        BadSensor{"  - {name: a, type: imu, body: cart, rate: 10, max_range: 3}\n",
                  "sensors[0].max_range: unknown key; an imu sensor has: name, type, body, robot, link, position, orientation, rpy, rate, noise (sensor \"a\")"},
        BadSensor{"  - {name: a, type: contact, body: cart, rate: 10, noise: {range: 1}}\n", "(sensor \"a\")"},
        BadSensor{"  - {name: a, type: imu, body: cart, rate: 10, noise: {linear_acceleration: -1}}\n",
                  "sensors[0].noise.linear_acceleration"},
        BadSensor{"  - {name: a, type: range, body: cart, rate: 10}\n", "sensor \"a\": missing key \"max_range\""},
        BadSensor{"  - {name: a, type: range, body: cart, rate: 10, min_range: 2, max_range: 1}\n",
                  "sensors[0].max_range: sensor \"a\": max_range must be above min_range (2 m)"},
        BadSensor{"  - {name: a, type: lidar, body: cart, rate: 10, max_range: 5, horizontal: {samples: 0}}\n",
                  "sensors[0].horizontal.samples: sensor \"a\": samples must be at least 1"},
        BadSensor{"  - {name: a, type: lidar, body: cart, rate: 10, max_range: 5, vertical: {min: 0.5, max: 0.1}}\n",
                  "sensors[0].vertical.max: sensor \"a\": max (0.1 rad) is below min (0.5 rad)"},
        BadSensor{"  - {name: a, type: lidar, body: cart, rate: 10, max_range: 5, vertical: {min: -2}}\n",
                  "sensors[0].vertical.min"},
        BadSensor{"  - {name: a, type: force_torque, body: cart, joint: hinge, rate: 10}\n",
                  "sensors[0].body: sensor \"a\": a force_torque sensor is on its joint's child body"},
        BadSensor{"  - {name: a, type: imu, body: cart, robot: r, link: l, rate: 10}\n",
                  "sensor \"a\": give either body, or robot and link, not both"},
        BadSensor{"  - {name: a, type: imu, rate: 10}\n", "sensor \"a\": missing key \"body\""},
        BadSensor{"  - just a string\n", "s.yaml:9:5: sensors[0]: expected a mapping"},
        BadSensor{"  {name: a}\n", "sensors: expected a list"}));

}  // namespace
}  // namespace rbsim
