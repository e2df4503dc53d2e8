// Noise that replays bit for bit and has the asked-for spread, and sensors
// that read at their rates on the simulated clock.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sensors/gaussian_noise.h"
#include "unit/sensors/sensor_test_support.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addGround;
using testing::sensorOn;
using testing::settingsWith;

TEST(GaussianNoise, IsAPureFunctionOfSeedStepAndComponentWithUnitSpread) {
  EXPECT_EQ(standardNormal(7, 100, 3), standardNormal(7, 100, 3));
  EXPECT_NE(standardNormal(7, 100, 3), standardNormal(8, 100, 3));
  EXPECT_NE(standardNormal(7, 100, 3), standardNormal(7, 101, 3));
  EXPECT_NE(standardNormal(7, 100, 3), standardNormal(7, 100, 4));
  const int n = 200000;
  double sum = 0.0, squares = 0.0;
  for (int i = 0; i < n; ++i) {
    const double z = standardNormal(42, i / 6, static_cast<uint64_t>(i % 6));
    sum += z;
    squares += z * z;
  }
  const double mean = sum / n;
  const double variance = squares / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(n));           // 5 standard errors
  EXPECT_NEAR(variance, 1.0, 5.0 * std::sqrt(2.0 / n));  // the variance's standard error
}

// Two runs of the same world and sensors give the same noisy readings, bit
// for bit; another seed gives others.
std::vector<double> noisyRun(uint64_t seed) {
  World world(settingsWith(1e-3, Vec3(0, 0, -9.81)));
  addGround(world);
  BodyDef box;
  box.name = "box";
  box.shape = BoxShape{Vec3(0.1, 0.1, 0.1)};
  box.position = Vec3(0, 0, 0.5);
  addBody(world, box);
  SensorDef imu = sensorOn("box", SensorType::Imu, 1000.0);
  imu.name = "imu";
  imu.noise = {0.05, 0.01, 0.0, 0.0, 0.0, seed};
  SensorDef range = sensorOn("box", SensorType::Range, 100.0);
  range.name = "range";
  range.orientation = Quaternion::fromRollPitchYaw(0, std::numbers::pi / 2, 0);  // x down
  range.pattern.maxRange = 5.0;
  range.noise.range = 0.01;
  range.noise.seed = seed;
  SensorSuite suite({imu, range}, 1e-3);
  std::vector<double> values;
  for (int i = 0; i < 600; ++i) {
    for (const SensorReading& reading : testing::stepAndRead(world, suite)) {
      if (const auto* imuReading = std::get_if<ImuReading>(&reading.value)) {
        for (int k = 0; k < 3; ++k) values.push_back(imuReading->linearAcceleration[k]);
        for (int k = 0; k < 3; ++k) values.push_back(imuReading->angularVelocity[k]);
      } else if (const auto* scan = std::get_if<RangeReading>(&reading.value)) {
        values.push_back(scan->ranges[0]);
      }
    }
  }
  return values;
}

TEST(SensorNoise, ReplaysBitForBitWithTheSameSeed) {
  const std::vector<double> first = noisyRun(11);
  const std::vector<double> second = noisyRun(11);
  ASSERT_EQ(first.size(), 600u * 6u + 60u);  // the IMU every step, the range every 10th
  ASSERT_EQ(first.size(), second.size());
  EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0);
  const std::vector<double> other = noisyRun(12);
  EXPECT_NE(std::memcmp(first.data(), other.data(), first.size() * sizeof(double)), 0);
}

TEST(SensorNoise, HasTheDeclaredSpread) {
  // A box in free fall reads 0: what it reads is the noise alone.
  World world(settingsWith(1e-3, Vec3(0, 0, -9.81)));
  BodyDef box;
  box.name = "box";
  box.shape = BoxShape{Vec3(0.1, 0.1, 0.1)};
  addBody(world, box);
  SensorDef imu = sensorOn("box", SensorType::Imu, 1000.0);
  imu.noise.linearAcceleration = 0.2;
  imu.noise.seed = 5;
  SensorSuite suite({imu}, 1e-3);
  double squares = 0.0;
  const int n = 3000;
  for (int i = 0; i < n; ++i) {
    const ImuReading reading = testing::stepAndReadOne<ImuReading>(world, suite);
    squares += reading.linearAcceleration.squaredNorm();
    EXPECT_EQ(reading.angularVelocity.norm(), 0.0);
  }
  const double stddev = std::sqrt(squares / (3 * n));
  EXPECT_NEAR(stddev, 0.2, 0.2 * 5.0 / std::sqrt(2.0 * 3 * n));
}

TEST(SensorRates, ReadEveryStepAtTheStepRateAndEveryHundredthAtATenth) {
  World world(settingsWith(1e-3, Vec3(0, 0, -9.81)));
  BodyDef box;
  box.name = "box";
  addBody(world, box);
  SensorDef fast = sensorOn("box", SensorType::Imu, 1000.0);
  fast.name = "fast";
  SensorDef slow = sensorOn("box", SensorType::Lidar, 10.0);
  slow.name = "slow";
  SensorSuite suite({fast, slow}, 1e-3);
  EXPECT_EQ(suite.periodSteps(0), 1);
  EXPECT_EQ(suite.periodSteps(1), 100);
  int fastReads = 0, slowReads = 0;
  for (int i = 1; i <= 1000; ++i) {
    for (const SensorReading& reading : testing::stepAndRead(world, suite)) {
      EXPECT_EQ(reading.step, i);
      if (reading.sensor->name == "fast") ++fastReads;
      if (reading.sensor->name == "slow") {
        ++slowReads;
        EXPECT_EQ(i % 100, 0);
      }
    }
  }
  EXPECT_EQ(fastReads, 1000);
  EXPECT_EQ(slowReads, 10);
  EXPECT_EQ(sensorPeriodSteps(333.0, 1e-3), 3);  // rounded to whole steps
}

TEST(Sensors, AreSilentWhileTheirBodyIsNotInTheWorld) {
  World world(settingsWith(1e-3, Vec3::Zero()));
  SensorSuite suite({sensorOn("absent", SensorType::Imu, 1000.0)}, 1e-3);
  EXPECT_TRUE(testing::stepAndRead(world, suite).empty());
}

}  // namespace
}  // namespace rbsim
