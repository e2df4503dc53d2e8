#pragma once
// What a URDF file says around the model urdfdom builds from it: where each
// link and joint is written (urdfdom keeps no line numbers), the order the
// links are written in, and every element rbsim does not use, so that a
// load report can name each one by line instead of dropping it in silence
// (transmissions, gazebo and sensor tags, a joint's
// safety controller and calibration, anything unknown).
//
// Read with tinyxml2, which records each element's line; the model itself is
// urdfdom's (robot/urdf_robot.h).

#include <map>
#include <string>
#include <vector>

#include "rbsim/physics/types.h"

namespace rbsim {

// An element of the file that changes nothing in the simulation.
struct UnusedUrdfElement {
  std::string element;  // its path: "link 'base'/visual", "transmission 'tr1'", "gazebo"
  int line = 0;         // 1-based
  std::string reason;   // why it is not used
};

struct UrdfDocument {
  std::map<std::string, int, std::less<>> linkLine;   // link name -> line of its <link>
  std::map<std::string, int, std::less<>> jointLine;  // joint name -> line of its <joint>
  std::vector<std::string> linkOrder;                 // the links as written
  std::vector<UnusedUrdfElement> unused;              // in the file's order
};

// Reads `xml`; errors (not XML, no <robot> root, joints that do not make a
// tree) name `sourceName` and the line, as "arm.urdf:12: ...".
// The tree is checked here, before urdfdom sees the file: urdfdom links a
// joint's parent to its child by shared pointers, so a joint to itself or
// a loop of joints would never be freed (and is no URDF: a URDF's joints
// form a tree, each link the child of at most one joint).
Expected<UrdfDocument> readUrdfDocument(const std::string& xml, const std::string& sourceName);

}  // namespace rbsim
