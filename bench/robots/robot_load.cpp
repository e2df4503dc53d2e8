// How long rbsim takes to make robots of URDF descriptions:
//   build/bench/robots/bench_robots_load [--reps 200]
// For config/robots/arm7.urdf (fixed base, in config/worlds/robot_arm.yaml's
// start pose) and config/robots/humanoid30.urdf (floating), each timed
// alone, as the median over the repetitions (after one untimed load):
//  - urdf:  loadRobot: read the file, parse it (urdfdom and tinyxml2 for
//           the lines), build the bodies and joints;
//  - world: loadWorldConfig of a world file with the robot (the arm in
//           config/worlds/robot_arm.yaml, the humanoid standing on the
//           ground in bench/robots/humanoid30.yaml): the YAML and the URDF;
//  - build: World::fromDef of that world: bodies, mass properties,
//           colliders and joints made in the physics world.
// Prints a ROW per measurement: what, robot, bodies, joints, median, min
// and max µs.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "arm_bench.h"
#include "bench_paths.h"
#include "config/config_loader.h"
#include "rbsim/physics/world.h"
#include "robot/urdf_robot.h"

namespace {

namespace rb = rbsim::bench::robots;
using Clock = std::chrono::steady_clock;

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "bench_robots_load: %s\n", message.c_str());
  std::exit(1);
}

// Times `load` `reps` times after one untimed call; prints its ROW.
void measure(const char* what, const char* robot, int reps,
             const std::function<std::pair<size_t, size_t>()>& load) {
  const std::pair<size_t, size_t> made = load();
  std::vector<double> us;
  for (int i = 0; i < reps; ++i) {
    const auto a = Clock::now();
    load();
    us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - a).count());
  }
  const double median = rb::median(us);
  std::printf("ROW | %s | %s | %zu | %zu | %.1f | %.1f | %.1f |\n", what, robot, made.first,
              made.second, median, *std::min_element(us.begin(), us.end()),
              *std::max_element(us.begin(), us.end()));
  std::fflush(stdout);
}

struct Robot {
  const char* name;
  std::string urdf;
  std::string world;
  bool fixedBase;
  std::map<std::string, double, std::less<>> jointPositions;
};

}  // namespace

int main(int argc, char** argv) {
  int reps = 200;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--reps" && i + 1 < argc) {
      reps = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: %s [--reps 200]\n", argv[0]);
      return 2;
    }
  }
  if (reps <= 0) return 2;
  const std::string robots = rbsim::bench::kRobotsDir;
  const std::vector<Robot> list = {
      {"arm7",
       robots + "/arm7.urdf",
       std::string(rbsim::bench::kWorldsDir) + "/robot_arm.yaml",
       true,
       {{"joint2", 0.6}, {"joint4", 1.2}, {"joint6", 0.8}}},
      {"humanoid30",
       robots + "/humanoid30.urdf",
       std::string(rbsim::bench::kBenchRobotsDir) + "/humanoid30.yaml",
       false,
       {}},
  };
  std::printf("CFG reps=%d (median, min, max over them, after one untimed load)\n", reps);
  std::printf("ROW | what | robot | bodies | joints | median us | min us | max us |\n");
  for (const Robot& robot : list) {
    rbsim::RobotPlacement placement;
    placement.name = robot.name;
    placement.fixedBase = robot.fixedBase;
    placement.jointPositions = robot.jointPositions;
    rbsim::RobotFiles files;
    files.sourceName = std::string(robot.name) + ".urdf";
    measure("urdf", robot.name, reps, [&] {
      const rbsim::Expected<rbsim::RobotModel> model =
          rbsim::loadRobot(robot.urdf, placement, files);
      if (!model.ok()) fail(model.error().message);
      return std::pair{model->bodies.size(), model->joints.size()};
    });
    measure("world", robot.name, reps, [&] {
      const rbsim::Expected<rbsim::WorldDef> def = rbsim::loadWorldConfig(robot.world);
      if (!def.ok()) fail(def.error().message);
      return std::pair{def->bodies.size(), def->joints.size()};
    });
    const rbsim::Expected<rbsim::WorldDef> def = rbsim::loadWorldConfig(robot.world);
    if (!def.ok()) fail(def.error().message);
    measure("build", robot.name, reps, [&] {
      const rbsim::Expected<rbsim::World> world = rbsim::World::fromDef(*def);
      if (!world.ok()) fail(world.error().message);
      return std::pair{static_cast<size_t>(world->bodyCount()),
                       static_cast<size_t>(world->jointCount())};
    });
  }
  return 0;
}
