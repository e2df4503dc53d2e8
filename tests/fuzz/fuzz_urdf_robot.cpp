// A URDF robot description (robot/urdf_robot.h), as a world file's robots:
// or a SPAWN would hand it over: XML, urdfdom's model, the mapping to bodies
// and joints (meshes resolved through the test package). A robot that
// loads is built into a world (World::fromDef: mass properties, hulls,
// joints) and stepped a few times.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_paths.h"
#include "rbsim/physics/world.h"
#include "robot/urdf_robot.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rbsim;
  const std::string xml(reinterpret_cast<const char*>(data), size);
  RobotPlacement placement;
  placement.name = "fuzz";
  RobotFiles files;
  files.sourceName = "fuzz.urdf";
  files.directory = rbsim::fuzz::kUrdfDir;
  files.packagePaths = {std::string(rbsim::fuzz::kUrdfDir) + "/packages"};
  Expected<RobotModel> robot = buildRobot(xml, placement, files);
  if (!robot) return 0;
  WorldDef def;
  def.bodies = std::move(robot->bodies);
  def.joints = std::move(robot->joints);
  auto world = World::fromDef(def);
  if (!world) return 0;
  for (int i = 0; i < 3; ++i) world->step();
  return 0;
}
