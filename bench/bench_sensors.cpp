// What sensors cost a stepping world (issue 40): the anchors' pile of 1000
// boxes (tests/scenes/pile_scene.h, as dropped, on the ground plane) on a
// 1 kHz world, with a 16-beam x 1800-sample lidar at 10 Hz (28 800 rays every
// 100th step) on a static mast beside the pile, seeing it over a quarter of
// its turn and the ground elsewhere, and an IMU at 1 kHz on a box of the
// pile — as rbserver reads them (SensorSuite: before each step the IMU's
// velocities, after it the readings due, with noise).
//
// Each run steps a copy of the same world for the same steps; the sensors'
// time (beforeStep + readAfterStep) is clocked apart from World::step, so
// the share does not drown in the step time's own noise. A run without
// sensors checks that the world's final state hash is the same (sensors
// observe) and gives the step time alone.
//
//   taskset -c 1 build/bench/bench_sensors [--steps N] [--warmup N] [--threads N]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "rbsim/physics/world.h"
#include "scenes/pile_scene.h"
#include "sensors/sensor_suite.h"

namespace rbsim {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<SensorDef> benchSensors() {
  SensorDef lidar;
  lidar.name = "lidar";
  lidar.type = SensorType::Lidar;
  lidar.body = "mast";
  lidar.position = Vec3(0, 0, 0.6);  // 1.1 m above the ground
  lidar.rate = 10.0;
  lidar.pattern.horizontalSamples = 1800;
  lidar.pattern.horizontalMin = -std::numbers::pi;
  lidar.pattern.horizontalMax = std::numbers::pi * (1.0 - 2.0 / 1800);
  lidar.pattern.beams = 16;
  lidar.pattern.verticalMin = -0.2618;  // ±15°, a VLP-16's field of view
  lidar.pattern.verticalMax = 0.2618;
  lidar.pattern.minRange = 0.1;
  lidar.pattern.maxRange = 30.0;
  lidar.noise.range = 0.01;
  lidar.noise.seed = 1;
  SensorDef imu;
  imu.name = "imu";
  imu.type = SensorType::Imu;
  imu.body = "box950";  // in the top layer
  imu.position = Vec3(0.05, 0.0, 0.1);
  imu.rate = 1000.0;
  imu.noise = {0.02, 0.001, 0.0, 0.0, 0.0, 2};
  return {lidar, imu};
}

World benchWorld(int threads) {
  WorldDef def = scenes::makePileScene(1000, scenes::PileVariant::Dropped);
  BodyDef mast;  // beside the pile: its beams cross the pile over about 90°
  mast.name = "mast";
  mast.isStatic = true;
  mast.position = Vec3(2.5, 0.0, 0.5);
  mast.shape = BoxShape{Vec3(0.05, 0.05, 0.5)};
  def.bodies.push_back(mast);
  def.settings.threads = threads;
  auto world = World::fromDef(def);
  if (!world) {
    std::fprintf(stderr, "%s\n", world.error().message.c_str());
    std::exit(1);
  }
  return std::move(world).value();
}

struct Timing {
  double step = 0.0;     // s in World::step
  double sensors = 0.0;  // s in the suite
  int64_t readings = 0;
  int64_t rays = 0;
  uint64_t hash = 0;
};

Timing run(World world, int steps, bool withSensors) {
  SensorSuite suite(withSensors ? benchSensors() : std::vector<SensorDef>{}, world.settings().dt);
  std::vector<SensorReading> readings;
  Timing timing;
  for (int i = 0; i < steps; ++i) {
    Clock::time_point start = Clock::now();
    suite.beforeStep(world);
    timing.sensors += secondsSince(start);
    start = Clock::now();
    world.step();
    timing.step += secondsSince(start);
    start = Clock::now();
    suite.readAfterStep(world, readings);
    timing.sensors += secondsSince(start);
    timing.readings += static_cast<int64_t>(readings.size());
    for (const SensorReading& reading : readings)
      if (const auto* scan = std::get_if<RangeReading>(&reading.value))
        timing.rays += static_cast<int64_t>(scan->ranges.size());
  }
  timing.hash = world.stateHash();
  return timing;
}

}  // namespace
}  // namespace rbsim

int main(int argc, char** argv) {
  int steps = 2000, warmup = 1000, threads = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--steps") == 0) steps = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--warmup") == 0) warmup = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--threads") == 0) threads = std::atoi(argv[i + 1]);
  }
  rbsim::World world = rbsim::benchWorld(threads);
  for (int i = 0; i < warmup; ++i) world.step();  // into the pile's fall and first impacts
  const rbsim::Timing alone = rbsim::run(world, steps, false);
  const rbsim::Timing with = rbsim::run(world, steps, true);
  const double perStep = with.step / steps;
  std::printf("pile of 1000 boxes, dt 1 ms, %d threads, steps %d..%d\n", threads, warmup + 1, warmup + steps);
  std::printf("step without sensors  %.1f us/step\n", 1e6 * alone.step / steps);
  std::printf("step with sensors     %.1f us/step (World::step only)\n", 1e6 * perStep);
  std::printf("sensors               %.1f us/step: %lld readings, %lld rays (%.2f M rays/s)\n",
              1e6 * with.sensors / steps, static_cast<long long>(with.readings), static_cast<long long>(with.rays),
              with.rays / with.sensors * 1e-6);
  std::printf("sensors' share        %.1f %% of the step time\n", 100.0 * with.sensors / with.step);
  std::printf("same final state      %s\n", alone.hash == with.hash ? "yes" : "NO: sensors changed the world");
  return alone.hash == with.hash ? 0 : 1;
}
