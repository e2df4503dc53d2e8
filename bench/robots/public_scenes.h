// The benchmark of public robots (bench/robots/README.md, "Public robots"),
// shared by every engine's adapter: the scenes as plain data, the engine
// interface, the joint targets, the timing loop and the output. Like
// arm_bench.h it includes no engine header.
//
// Scenes (publicScenes() in public_scenes.cpp has the numbers):
//   hold-<arm>   the arm on a fixed base held at a pose by joint drives;
//                self-collision off
//   fold-<arm>   the arm driven through a joint-space trajectory that folds
//                it (links come close); self-collision on
//   stand-a1     the Unitree A1 standing on the ground, its 12 joints held
//   stand-solo12 the Solo-12 (mesh collision geometry) standing likewise
//   table-panda  the Panda beside a table with 20 objects on it (boxes,
//                cylinders, convex mesh pebbles), held at a pose above them
// dt = 1 ms, gravity (0, 0, −9.81) m/s², a ground plane at z = 0.
//
// Conventions: SI units, z up, quaternions (w, x, y, z), world frame.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "arm_bench.h"

namespace rbsim::bench::robots {

struct ObjectSpec {
  enum class Kind { Box, Cylinder, Mesh };
  std::string name;
  Kind kind = Kind::Box;
  Vec3 halfExtents{0, 0, 0};  // box
  double radius = 0;          // cylinder (along z)
  double halfLength = 0;      // cylinder
  std::string mesh;           // mesh: absolute path of an OBJ file (a closed convex mesh)
  double mass = 0.1;          // kg; inertia from the shape (uniform density)
  Pose pose;                  // of the shape's frame
};

struct PublicScene {
  std::string name;       // e.g. hold-iiwa
  std::string robot;      // the robot's name, the prefix of its bodies and joints
  std::string urdf;       // absolute path
  Pose base;              // the URDF root link's frame
  bool fixedBase = true;
  // The driven joints (URDF names), their start positions (rad or m) and,
  // for the fold scenes, the folded pose the trajectory reaches.
  std::vector<std::string> joints;
  std::vector<double> start;
  std::vector<double> fold;  // empty: hold the start pose
  double foldPeriod = 2.0;   // s: start → fold → start
  bool selfCollision = false;
  double naturalFrequency = 10.0;  // Hz: the drives' gains (public_model.cpp)
  double dampingRatio = 1.0;
  // A static table (a box) and the objects on it.
  bool table = false;
  Vec3 tableHalfExtents{0, 0, 0};
  Vec3 tableCenter{0, 0, 0};
  std::vector<ObjectSpec> objects;
  double friction = 0.8;
  double dt = 1e-3;
  int steps = 3000;
};

// Every scene, with the data's paths from the build (bench_paths.h).
std::vector<PublicScene> publicScenes();

// The drive's target of joint k at step i.
double publicTarget(const PublicScene& s, size_t joint, int step);

// The gains every engine uses, per driven joint (public_model.cpp works
// them out from the robot as rbsim loads it).
struct JointGains {
  double stiffness = 0;  // N·m/rad or N/m
  double damping = 0;    // N·m·s/rad or N·s/m
};

class PublicEngine {
 public:
  virtual ~PublicEngine() = default;
  virtual void build(const PublicScene& s, const std::vector<JointGains>& gains) = 0;
  virtual void readJoints(std::vector<JointReading>& out) = 0;
  // One control cycle's command: rbsim sets its drives' targets; the
  // others apply the PD law's efforts worked out from the readings.
  virtual void actuate(const std::vector<double>& targets, const std::vector<double>& efforts) = 0;
  virtual void step() = 0;
  virtual int contactPoints() = 0;  // after the last step
  virtual int bodyCount() const = 0;
  virtual std::string settings() const = 0;
  // True when the engine applies the PD law itself (rbsim's implicit
  // drives); the harness then passes targets only.
  virtual bool nativeDrives() const { return false; }
  // False: the harness does not add the damping term to the efforts
  // (MuJoCo: the damping is the joints' own, implicit in its integrator).
  virtual bool explicitDamping() const { return true; }
};

struct PublicOptions {
  std::vector<std::string> scenes;  // empty: all
  int reps = 1;
  int steps = -1;
  int selfCollision = -1;  // -1: the scene's default; 0 off; 1 on
  std::string label;
  std::string writeWorlds;  // rbsim: also write the world files here
};

bool parsePublicOptions(int argc, char** argv, PublicOptions& o);

// Runs the chosen scenes, o.reps fresh builds each: a CFG line per scene,
// a REP line per repetition and a ROW with the medians of the times.
// `gainsOf` gives the gains of a scene (the same for every engine).
int runPublic(const PublicOptions& o, const std::string& engineName, const std::string& version,
              const std::function<std::unique_ptr<PublicEngine>()>& makeEngine,
              const std::function<std::vector<JointGains>(const PublicScene&)>& gainsOf);

}  // namespace rbsim::bench::robots
