#pragma once
// A robot from its URDF description (parsed by urdfdom, the parser ROS
// uses) as bodies and joints of a world, with everything that changes the
// physics honoured and everything else reported, by element and line.
//
// The mapping:
//  - a link is a body named "<robot>/<link>", placed where the link's frame
//    is with the joints at their initial positions; its <inertial> gives
//    the mass properties (mass, centre of mass and inertia in the link's
//    frame), its <collision> elements its shape (one: that shape; several:
//    a compound; box, sphere, cylinder, and meshes (OBJ, STL, COLLADA), which collide
//    as their convex hull and may be open, since the mass is given). A link
//    without collisions collides with nothing.
//  - revolute, continuous, prismatic and fixed joints are joints with their
//    axis, limits and <dynamics> (damping, friction); a floating joint
//    leaves its child free; a planar joint is refused.
//  - the root link is static when the robot has a fixed base, or when it
//    has no mass (PyBullet's convention for a static base).
//  - a link without mass (no <inertial>, or mass 0: a sensor's frame) is
//    merged into its parent when a fixed joint holds it there (its
//    collisions join the parent's shape); anywhere else it is an error.
//    Links held by fixed joints are merged into one body with their masses
//    combined exactly when the robot asks for it (merge_fixed_links).
//  - a link's <visual> elements (box, sphere, cylinder, and meshes: STL,
//    OBJ, COLLADA) are how its body is drawn, with the colour of their
//    <material> (inline or by the name of a robot's <material>); they
//    change nothing in the simulation and go beside the bodies
//    (RobotModel::visuals), not into them. A visual that cannot be drawn
//    (a mesh not found, a size that is not one) is left out and reported,
//    never an error.
// Errors name the file and the line of the element at fault.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rbsim/physics/body_definition.h"
#include "rbsim/physics/joint_definition.h"
#include "rbsim/physics/types.h"
#include "robot/visual.h"

namespace rbsim {

// Where a robot goes and how it starts.
struct RobotPlacement {
  std::string name;  // the prefix of its bodies' and joints' names
  Vec3 position = Vec3::Zero();                     // m: where the root link's frame goes
  Quaternion orientation = Quaternion::identity();  // root link frame -> world
  bool fixedBase = false;                           // the root link static (welded to the world)
  bool mergeFixedLinks = false;                     // links held by fixed joints merged into one body
  // Initial joint positions by the URDF's joint names (rad or m); the
  // others start at 0. The joints read them as their positions there.
  std::map<std::string, double, std::less<>> jointPositions;
  // Collision meshes collide as their convex hulls, simplified as engines
  // cook hulls (simplifiedConvexHullMesh): to at most hullMaxVertices
  // vertices while the full hull stays within hullTolerance of the
  // simplified hull's face planes (tolerance 0 and a budget of at least
  // the hull's vertices keep every vertex).
  double hullTolerance = 0.001;  // m
  std::size_t hullMaxVertices = 256;
};

// Where a URDF's files are: its own directory (for relative mesh paths) and
// the directories package://NAME/... is looked up in (each holds packages,
// DIR/NAME/..., or is the package itself, .../NAME), then those of
// ROS_PACKAGE_PATH.
//
// A robot spawned over LCM comes from a sender who is not trusted with the
// server's file system: `confinedTo` is then the spawn directory, and every
// file the description names is opened only inside it, by the rules of
// meshio/contained_path.h (relative, no '..', no link leading out, a
// regular file). `directory` and `packagePaths` are then relative to it,
// ROS_PACKAGE_PATH is not consulted, and messages name a file as the
// description does, never by the host's path.
struct RobotFiles {
  std::string sourceName;  // the URDF as messages name it
  std::string directory;
  std::vector<std::string> packagePaths;
  std::optional<std::string> confinedTo;
  // The viewer bridge's mesh route that visual meshes are published under
  // (kWorldMeshRoute, kSpawnMeshRoute) and the directory it serves there
  // (the world file's directory, the spawn directory): a visual mesh inside
  // it is published as ROUTE/RELATIVE/PATH (Visual::meshUrl), one outside
  // it without a URL. Empty: no URLs.
  std::string meshRoute;
  std::string meshRouteDirectory;
};

// What a robot adds to a world, and the report of what was made of its
// description and what was not used.
struct RobotModel {
  std::vector<BodyDef> bodies;
  std::vector<NamedJointDef> joints;
  std::vector<std::string> report;  // one line each
  // Every link of the URDF, in document order, with the body it is part of
  // (its own, "<robot>/<link>", or the body it was merged into): what the
  // world file's per-link settings (collision filters, excluded pairs)
  // apply to.
  std::vector<std::pair<std::string, std::string>> linkBodies;
  // How the bodies look (their links' <visual> elements, placed in the
  // body's shape frame), for the bodies that have any, by body name.
  BodyVisuals visuals;
};

// Builds the robot of the URDF text `xml`. Errors: XML that is not a URDF
// (urdfdom's message), a planar joint, a mimic joint, a moving link without
// mass, mass properties no rigid body has, a shape of non-positive size, a
// mesh that cannot be read (loadMesh's message: OBJ, STL and COLLADA are
// read, any other format is refused by its extension), a joint position
// for a joint the robot does not have or that does not move, or outside its
// limits.
Expected<RobotModel> buildRobot(const std::string& xml, const RobotPlacement& placement, const RobotFiles& files);

// The same from the file at `path` (sourceName: how messages name it;
// confined, `path` must have been resolved inside files.confinedTo).
Expected<RobotModel> loadRobot(const std::string& path, const RobotPlacement& placement, RobotFiles files);

}  // namespace rbsim
