// Range sensors and lidars in a box room of known size: every beam reads
// the distance to the wall, floor or nothing that a closed form gives, and
// the range limits read as ROS REP 117 says (+inf: no return, -inf: too close).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "unit/sensors/sensor_test_support.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addGround;
using testing::sensorOn;
using testing::settingsWith;
using testing::stepAndReadOne;

// Inner faces at x = ±kHalfX, y = ±kHalfY; walls kWallHeight high on the ground.
constexpr double kHalfX = 3.0, kHalfY = 2.0, kWallHeight = 1.0;
const Vec3 kMount(0.5, 0.25, 0.5);  // the sensor's origin (a static mount's centre)

void addWall(World& world, const std::string& name, const Vec3& centre, const Vec3& halfExtents) {
  BodyDef wall;
  wall.name = name;
  wall.isStatic = true;
  wall.position = centre;
  wall.shape = BoxShape{halfExtents};
  addBody(world, wall);
}

World boxRoom() {
  World world(settingsWith(1e-3, Vec3(0, 0, -9.81)));
  addGround(world);
  const double h = kWallHeight / 2;
  addWall(world, "east", Vec3(kHalfX + 0.1, 0, h), Vec3(0.1, kHalfY + 0.2, h));
  addWall(world, "west", Vec3(-kHalfX - 0.1, 0, h), Vec3(0.1, kHalfY + 0.2, h));
  addWall(world, "north", Vec3(0, kHalfY + 0.1, h), Vec3(kHalfX + 0.2, 0.1, h));
  addWall(world, "south", Vec3(0, -kHalfY - 0.1, h), Vec3(kHalfX + 0.2, 0.1, h));
  BodyDef mount;  // the sensor's own body, which its beams never hit
  mount.name = "mount";
  mount.isStatic = true;
  mount.position = kMount;
  mount.shape = BoxShape{Vec3::Constant(0.05)};
  addBody(world, mount);
  return world;
}

// The closed form: the distance from kMount along (azimuth, elevation) to
// the first of the walls and the ground, +inf past the top of the walls.
double expectedRange(double azimuth, double elevation) {
  const double c = std::cos(azimuth), s = std::sin(azimuth);
  const double inf = std::numeric_limits<double>::infinity();
  const double toX = c > 1e-12 ? (kHalfX - kMount.x()) / c : c < -1e-12 ? (-kHalfX - kMount.x()) / c : inf;
  const double toY = s > 1e-12 ? (kHalfY - kMount.y()) / s : s < -1e-12 ? (-kHalfY - kMount.y()) / s : inf;
  const double horizontal = std::min(toX, toY);
  const double toWall = horizontal / std::cos(elevation);
  const double wallHitHeight = kMount.z() + toWall * std::sin(elevation);
  const double toGround = elevation < 0 ? kMount.z() / -std::sin(elevation) : inf;
  if (toGround < toWall) return toGround;
  return wallHitHeight <= kWallHeight ? toWall : inf;
}

SensorDef lidarOnTheMount(int samples, int beams) {
  SensorDef lidar = sensorOn("mount", SensorType::Lidar, 1000.0);
  ScanPattern& pattern = lidar.pattern;
  pattern.horizontalSamples = samples;
  pattern.horizontalMin = -std::numbers::pi;
  pattern.horizontalMax = std::numbers::pi * (1.0 - 2.0 / samples);
  pattern.beams = beams;
  pattern.verticalMin = beams > 1 ? -0.3 : 0.0;
  pattern.verticalMax = beams > 1 ? 0.3 : 0.0;
  pattern.maxRange = 20.0;
  return lidar;
}

TEST(Lidar, ReadsTheWallsOfABoxRoomInAPlanarFan) {
  World world = boxRoom();
  SensorDef lidar = lidarOnTheMount(360, 1);
  lidar.pattern.reportBodies = true;
  SensorSuite suite({lidar}, 1e-3);
  const RangeReading scan = stepAndReadOne<RangeReading>(world, suite);
  ASSERT_EQ(scan.ranges.size(), 360u);
  ASSERT_EQ(scan.hitBodies.size(), 360u);
  for (int s = 0; s < 360; ++s) {
    const double azimuth = lidar.pattern.horizontalMin + s * lidar.pattern.horizontalIncrement();
    const double expected = expectedRange(azimuth, 0.0);
    // float on the wire: 2^-24 relative
    EXPECT_NEAR(scan.ranges[static_cast<std::size_t>(s)], expected, 1e-6 * expected) << "azimuth " << azimuth;
    EXPECT_FALSE(scan.hitBodies[static_cast<std::size_t>(s)].empty());
  }
  EXPECT_EQ(scan.hitBodies[180], "east");  // azimuth 0: +x
  EXPECT_EQ(scan.hitBodies[270], "north");  // +π/2: +y
  EXPECT_EQ((scan.position - kMount).norm(), 0.0);
}

TEST(Lidar, ReadsWallsFloorAndNothingInAThreeDimensionalPattern) {
  World world = boxRoom();
  SensorDef lidar = lidarOnTheMount(72, 5);  // elevations -0.3, -0.15, 0, 0.15, 0.3 rad
  lidar.orientation = Quaternion::identity();
  SensorSuite suite({lidar}, 1e-3);
  const RangeReading scan = stepAndReadOne<RangeReading>(world, suite);
  ASSERT_EQ(scan.ranges.size(), 72u * 5u);
  int noReturn = 0;
  for (int b = 0; b < 5; ++b) {
    const double elevation = lidar.pattern.verticalMin + b * lidar.pattern.verticalIncrement();
    for (int s = 0; s < 72; ++s) {
      const double azimuth = lidar.pattern.horizontalMin + s * lidar.pattern.horizontalIncrement();
      const double expected = expectedRange(azimuth, elevation);
      const float range = scan.ranges[static_cast<std::size_t>(b * 72 + s)];
      if (std::isinf(expected)) {
        EXPECT_EQ(range, std::numeric_limits<float>::infinity()) << b << " " << s;
        ++noReturn;
      } else {
        EXPECT_NEAR(range, expected, 1e-6 * expected) << "beam " << b << " azimuth " << azimuth;
      }
    }
  }
  EXPECT_GT(noReturn, 0);  // the upper beams pass over the walls somewhere
}

TEST(Lidar, FollowsItsBodyAndItsPoseInTheBody) {
  World world = boxRoom();
  SensorDef range = sensorOn("mount", SensorType::Range, 1000.0);
  range.pattern.maxRange = 10.0;
  // Mounted 0.2 m above the mount's centre, yawed to look along +y.
  range.position = Vec3(0, 0, 0.2);
  range.orientation = Quaternion::fromRollPitchYaw(0, 0, std::numbers::pi / 2);
  SensorSuite suite({range}, 1e-3);
  const RangeReading scan = stepAndReadOne<RangeReading>(world, suite);
  ASSERT_EQ(scan.ranges.size(), 1u);
  EXPECT_NEAR(scan.ranges[0], kHalfY - kMount.y(), 1e-6);
  EXPECT_NEAR(scan.position.z(), kMount.z() + 0.2, 1e-12);
}

TEST(Lidar, ReadsPlusInfinityBeyondTheMaximumRangeAndMinusInfinityBelowTheMinimum) {
  World world = boxRoom();
  SensorDef lidar = lidarOnTheMount(360, 1);
  lidar.pattern.minRange = 2.55;
  lidar.pattern.maxRange = 2.8;
  SensorSuite suite({lidar}, 1e-3);
  const RangeReading scan = stepAndReadOne<RangeReading>(world, suite);
  int tooClose = 0, tooFar = 0, within = 0;
  for (int s = 0; s < 360; ++s) {
    const double azimuth = lidar.pattern.horizontalMin + s * lidar.pattern.horizontalIncrement();
    const double expected = expectedRange(azimuth, 0.0);
    const float range = scan.ranges[static_cast<std::size_t>(s)];
    if (expected > 2.8) {
      EXPECT_EQ(range, std::numeric_limits<float>::infinity());
      ++tooFar;
    } else if (expected < 2.55) {
      EXPECT_EQ(range, -std::numeric_limits<float>::infinity());
      ++tooClose;
    } else {
      EXPECT_NEAR(range, expected, 1e-6 * expected);
      ++within;
    }
  }
  EXPECT_GT(tooClose, 0);
  EXPECT_GT(tooFar, 0);
  EXPECT_GT(within, 0);
}

}  // namespace
}  // namespace rbsim
