// The joint-space dynamics of the seven-joint example arm
// (config/robots/arm7.urdf, fixed base, bent): the model read from the
// world, then M(q), h(q, q̇) and one link point's Jacobian, as a
// model-based controller asks for them each cycle. The target:
// all of it within 20 µs.
//
//   build/bench/bench_joint_space_dynamics --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "rbsim/physics/joint_space_dynamics.h"
#include "rbsim/physics/world.h"
#include "robot/urdf_robot.h"

namespace {

rbsim::World bentArm() {
  using namespace rbsim;
  RobotPlacement placement;
  placement.name = "arm";
  placement.fixedBase = true;
  placement.jointPositions = {{"joint2", 0.6}, {"joint3", 0.4}, {"joint4", -1.2}, {"joint6", 0.8}};
  RobotFiles files;
  files.sourceName = "arm7.urdf";
  Expected<RobotModel> robot = loadRobot(std::string(RBSIM_SOURCE_DIR) + "/config/robots/arm7.urdf", placement, files);
  if (!robot) {
    std::fprintf(stderr, "%s\n", robot.error().message.c_str());
    std::exit(1);
  }
  WorldDef def;
  def.settings.gravity = Vec3(0, 0, -9.81);
  def.bodies = robot->bodies;
  def.joints = robot->joints;
  Expected<World> world = World::fromDef(def);
  if (!world) {
    std::fprintf(stderr, "%s\n", world.error().message.c_str());
    std::exit(1);
  }
  for (int k = 0; k < 50; ++k) world->step();  // moving: q̇ ≠ 0
  return std::move(*world);
}

void MassBiasAndJacobian(benchmark::State& state) {
  const rbsim::World world = bentArm();
  const rbsim::Vec3 tool = world.body(world.findBody("arm/link7")).position();
  for (auto _ : state) {
    const auto dynamics = rbsim::JointSpaceDynamics::ofRobot(world, "arm/");
    benchmark::DoNotOptimize(dynamics->massMatrix());
    benchmark::DoNotOptimize(dynamics->biasForces());
    benchmark::DoNotOptimize(dynamics->jacobian("arm/link7", tool));
  }
}
BENCHMARK(MassBiasAndJacobian)->Unit(benchmark::kMicrosecond);

// The three alone, on a model already read.
void MassBiasAndJacobianOnly(benchmark::State& state) {
  const rbsim::World world = bentArm();
  const rbsim::Vec3 tool = world.body(world.findBody("arm/link7")).position();
  const auto dynamics = rbsim::JointSpaceDynamics::ofRobot(world, "arm/");
  for (auto _ : state) {
    benchmark::DoNotOptimize(dynamics->massMatrix());
    benchmark::DoNotOptimize(dynamics->biasForces());
    benchmark::DoNotOptimize(dynamics->jacobian("arm/link7", tool));
  }
}
BENCHMARK(MassBiasAndJacobianOnly)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
