// Joint benchmark scenes (issue 12), shared by every engine adapter in
// bench/joints (Bullet, ODE, and later rbsim itself).
//
// This header deliberately includes no engine header: a scene is plain data
// (bodies, joints, static ground), built deterministically here, so every
// engine starts from bit-identical initial states. An adapter implements
// Engine and calls runMain(); the runner owns the timing loop, the joint
// error measurement and the output format, so the figures of different
// engines are comparable line by line.
//
// Conventions: SI units, z up, quaternions (w, x, y, z), world frame unless
// a name says "local".
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace rbsim::bench::joints {

using Vec3 = std::array<double, 3>;
using Quat = std::array<double, 4>;  // (w, x, y, z)

constexpr double kPi = 3.14159265358979323846;
constexpr double kFriction = 0.5;  // effective Coulomb coefficient per pair

// ------------------------------------------------------------------- math
inline Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double norm(const Vec3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

inline Quat conjugate(const Quat& q) { return {q[0], -q[1], -q[2], -q[3]}; }

inline Quat axisAngle(const Vec3& axis, double angle) {
  const double s = std::sin(angle / 2) / norm(axis);
  return {std::cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s};
}

inline Quat multiply(const Quat& a, const Quat& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

// v' = q v q*, written out (q need not be exactly unit: engines return
// quaternions rounded to their precision).
inline Vec3 rotate(const Quat& q, const Vec3& v) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  // t = 2 (q.xyz × v); v' = v + w t + q.xyz × t
  const Vec3 t = {2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])};
  return {v[0] + w * t[0] + (y * t[2] - z * t[1]), v[1] + w * t[1] + (z * t[0] - x * t[2]),
          v[2] + w * t[2] + (x * t[1] - y * t[0])};
}

struct Pose {
  Vec3 position{0, 0, 0};
  Quat orientation{1, 0, 0, 0};
};

// Local coordinates of a world point in the frame of a pose.
inline Vec3 toLocal(const Pose& pose, const Vec3& world) {
  return rotate(conjugate(pose.orientation), sub(world, pose.position));
}

inline Vec3 toWorld(const Pose& pose, const Vec3& local) {
  return add(pose.position, rotate(pose.orientation, local));
}

// ----------------------------------------------------------------- scenes
enum class ShapeKind { kSphere, kBox };

struct BodySpec {
  ShapeKind shape = ShapeKind::kBox;
  Vec3 halfExtents{0.1, 0.1, 0.1};  // box
  double radius = 0.1;              // sphere
  double mass = 1;                  // kg
  Vec3 inertia{0, 0, 0};            // principal moments in the body frame, kg m²
  Pose pose;                        // initial pose of the centre of mass
  bool collides = true;             // false: no contacts with anything
};

enum class JointKind { kBall, kHinge };

constexpr int kWorld = -1;

struct JointSpec {
  JointKind kind = JointKind::kBall;
  int bodyA = 0;
  int bodyB = kWorld;  // kWorld: bodyA is attached to a fixed world point
  Vec3 anchor{0, 0, 0};  // world anchor at build time
  // Hinge: the hinge axis. Limited ball joint: the cone (twist) axis, along
  // the child bone. Unit length, world frame at build time.
  Vec3 axis{1, 0, 0};
  bool limited = false;
  // Hinge limits: rotation of body B relative to body A about `axis`
  // (right-handed), zero at the build pose. Adapters convert to their
  // engine's sign convention.
  double lower = 0, upper = 0;
  // Limited ball joint: half-angle of the swing cone about `axis` and
  // the symmetric twist range about it, both zero at the build pose.
  double swing = 0, twist = 0;
};

struct Scene {
  std::string name;
  int n = 0;
  double dt = 1e-3;
  int steps = 0;
  int velocityIterations = 10;
  Vec3 gravity{0, 0, -9.81};
  bool ground = false;  // static plane z = 0, normal +z (contacts on)
  bool contacts = false;
  std::vector<BodySpec> bodies;
  std::vector<JointSpec> joints;
};

inline Vec3 boxInertia(double mass, const Vec3& h) {
  // Solid box of half extents h: I_x = m (h_y² + h_z²) / 3.
  return {mass * (h[1] * h[1] + h[2] * h[2]) / 3, mass * (h[0] * h[0] + h[2] * h[2]) / 3,
          mass * (h[0] * h[0] + h[1] * h[1]) / 3};
}

inline BodySpec makeBox(const Vec3& half, double mass, const Vec3& position) {
  BodySpec b;
  b.shape = ShapeKind::kBox;
  b.halfExtents = half;
  b.mass = mass;
  b.inertia = boxInertia(mass, half);
  b.pose.position = position;
  return b;
}

inline BodySpec makeSphere(double radius, double mass, const Vec3& position) {
  BodySpec b;
  b.shape = ShapeKind::kSphere;
  b.radius = radius;
  b.mass = mass;
  const double moment = 0.4 * mass * radius * radius;
  b.inertia = {moment, moment, moment};
  b.pose.position = position;
  return b;
}

inline JointSpec ballJoint(int a, int b, const Vec3& anchor) {
  JointSpec j;
  j.kind = JointKind::kBall;
  j.bodyA = a;
  j.bodyB = b;
  j.anchor = anchor;
  return j;
}

// chain: N links, boxes of half extents 0.1 × 0.02 × 0.02 m (a 0.2 m long
// capsule-like rod; boxes rather than spheres so that the rotational
// inertia is that of a rod and the anchor sits 0.1 m from the centre of
// mass, which is what loads the joints), 1 kg each, initially horizontal
// along +x, joined end to end by ball joints at their ends; the first end
// is pinned to the world at (0, 0, 0). The chain swings down under gravity.
// Body–body collisions are off (the chain folds through itself, which keeps
// the scene about joints only); no ground.
inline void buildChain(Scene& s) {
  constexpr double kHalfLength = 0.1;
  const Vec3 half = {kHalfLength, 0.02, 0.02};
  for (int i = 0; i < s.n; ++i) {
    BodySpec link = makeBox(half, 1.0, {(2 * i + 1) * kHalfLength, 0, 0});
    link.collides = false;
    s.bodies.push_back(link);
    s.joints.push_back(ballJoint(i, i == 0 ? kWorld : i - 1, {2 * i * kHalfLength, 0, 0}));
  }
}

// grid: n × n spheres (radius 0.1 m, 1 kg) at 0.4 m spacing in the
// vertical x–z plane, each joined to its right and lower neighbour by a
// ball joint at the midpoint, the top row pinned to the world at the
// sphere centres: as Box2D's "joint grid" benchmark, the grid hangs in the
// plane of gravity and stretches under its own weight (the top joints carry
// the whole column, n kg). 2 n (n - 1) + n joints (4950 for n = 50). No
// collisions (neighbours are 0.2 m apart, and the benchmark is about the
// joint solver), no ground.
inline void buildGrid(Scene& s) {
  constexpr double kSpacing = 0.4;
  const int side = s.n;
  auto index = [side](int row, int column) { return row * side + column; };
  for (int row = 0; row < side; ++row) {
    for (int column = 0; column < side; ++column) {
      BodySpec sphere = makeSphere(0.1, 1.0, {column * kSpacing, 0, -row * kSpacing});
      sphere.collides = false;
      s.bodies.push_back(sphere);
    }
  }
  for (int row = 0; row < side; ++row) {
    for (int column = 0; column < side; ++column) {
      const int self = index(row, column);
      const Vec3 p = s.bodies[self].pose.position;
      if (row == 0) s.joints.push_back(ballJoint(self, kWorld, p));
      if (column + 1 < side) {
        s.joints.push_back(ballJoint(self, index(row, column + 1), {p[0] + kSpacing / 2, 0, p[2]}));
      }
      if (row + 1 < side) {
        s.joints.push_back(ballJoint(self, index(row + 1, column), {p[0], 0, p[2] - kSpacing / 2}));
      }
    }
  }
}

// ---------------------------------------------------------------- ragdoll
// One 15-body humanoid standing with its feet at z = 0, facing +y, arms
// hanging (≈ 70.6 kg, 1.7 m). Kept here so rbsim builds the same skeleton.
struct RagdollPart {
  const char* name;
  ShapeKind shape;
  Vec3 halfExtents;  // box; x of it is the radius for a sphere
  double mass;
  Vec3 centre;  // standing pose
};

struct RagdollJoint {
  const char* name;
  JointKind kind;
  int parent, child;  // indices into kRagdollParts
  Vec3 anchor;        // standing pose
  Vec3 axis;          // hinge axis, or cone axis along the child bone
  double lower, upper;  // hinge: child relative to parent about axis
  double swing, twist;  // limited ball joint
};

enum RagdollPartIndex {
  kPelvis, kTorso, kHead,
  kUpperArmL, kLowerArmL, kHandL, kUpperArmR, kLowerArmR, kHandR,
  kThighL, kShinL, kFootL, kThighR, kShinR, kFootR,
  kRagdollPartCount
};

// Left is -x. The arms hang 0.01 m clear of the torso and the legs 0.06 m
// apart, so the only initial contacts are across joints (filtered out).
inline const std::array<RagdollPart, kRagdollPartCount> kRagdollParts = {{
    {"pelvis", ShapeKind::kBox, {0.15, 0.10, 0.10}, 10.0, {0, 0, 1.00}},
    {"torso", ShapeKind::kBox, {0.17, 0.10, 0.20}, 20.0, {0, 0, 1.30}},
    {"head", ShapeKind::kSphere, {0.10, 0.10, 0.10}, 5.0, {0, 0, 1.60}},
    {"upper_arm_l", ShapeKind::kBox, {0.05, 0.05, 0.15}, 2.5, {-0.23, 0, 1.33}},
    {"lower_arm_l", ShapeKind::kBox, {0.045, 0.045, 0.13}, 1.8, {-0.23, 0, 1.05}},
    {"hand_l", ShapeKind::kBox, {0.04, 0.02, 0.06}, 0.5, {-0.23, 0, 0.86}},
    {"upper_arm_r", ShapeKind::kBox, {0.05, 0.05, 0.15}, 2.5, {0.23, 0, 1.33}},
    {"lower_arm_r", ShapeKind::kBox, {0.045, 0.045, 0.13}, 1.8, {0.23, 0, 1.05}},
    {"hand_r", ShapeKind::kBox, {0.04, 0.02, 0.06}, 0.5, {0.23, 0, 0.86}},
    {"thigh_l", ShapeKind::kBox, {0.07, 0.07, 0.22}, 8.0, {-0.10, 0, 0.68}},
    {"shin_l", ShapeKind::kBox, {0.06, 0.06, 0.20}, 4.0, {-0.10, 0, 0.26}},
    {"foot_l", ShapeKind::kBox, {0.06, 0.12, 0.03}, 1.0, {-0.10, 0.05, 0.03}},
    {"thigh_r", ShapeKind::kBox, {0.07, 0.07, 0.22}, 8.0, {0.10, 0, 0.68}},
    {"shin_r", ShapeKind::kBox, {0.06, 0.06, 0.20}, 4.0, {0.10, 0, 0.26}},
    {"foot_r", ShapeKind::kBox, {0.06, 0.12, 0.03}, 1.0, {0.10, 0.05, 0.03}},
}};

// Elbows flex forward (+y) and knees backward: with the limb hanging along
// -z, a rotation about +x swings it towards +y.
inline const std::array<RagdollJoint, kRagdollPartCount - 1> kRagdollJoints = {{
    {"waist", JointKind::kBall, kPelvis, kTorso, {0, 0, 1.10}, {0, 0, 1}, 0, 0, 0.5, 0.4},
    {"neck", JointKind::kBall, kTorso, kHead, {0, 0, 1.50}, {0, 0, 1}, 0, 0, 0.6, 0.6},
    {"shoulder_l", JointKind::kBall, kTorso, kUpperArmL, {-0.23, 0, 1.48}, {0, 0, -1}, 0, 0, 1.5, 0.8},
    {"elbow_l", JointKind::kHinge, kUpperArmL, kLowerArmL, {-0.23, 0, 1.18}, {1, 0, 0}, 0.0, 2.5, 0, 0},
    {"wrist_l", JointKind::kHinge, kLowerArmL, kHandL, {-0.23, 0, 0.92}, {1, 0, 0}, -1.0, 1.0, 0, 0},
    {"shoulder_r", JointKind::kBall, kTorso, kUpperArmR, {0.23, 0, 1.48}, {0, 0, -1}, 0, 0, 1.5, 0.8},
    {"elbow_r", JointKind::kHinge, kUpperArmR, kLowerArmR, {0.23, 0, 1.18}, {1, 0, 0}, 0.0, 2.5, 0, 0},
    {"wrist_r", JointKind::kHinge, kLowerArmR, kHandR, {0.23, 0, 0.92}, {1, 0, 0}, -1.0, 1.0, 0, 0},
    {"hip_l", JointKind::kBall, kPelvis, kThighL, {-0.10, 0, 0.90}, {0, 0, -1}, 0, 0, 1.2, 0.5},
    {"knee_l", JointKind::kHinge, kThighL, kShinL, {-0.10, 0, 0.46}, {1, 0, 0}, -2.5, 0.0, 0, 0},
    {"ankle_l", JointKind::kHinge, kShinL, kFootL, {-0.10, 0, 0.06}, {1, 0, 0}, -0.7, 0.7, 0, 0},
    {"hip_r", JointKind::kBall, kPelvis, kThighR, {0.10, 0, 0.90}, {0, 0, -1}, 0, 0, 1.2, 0.5},
    {"knee_r", JointKind::kHinge, kThighR, kShinR, {0.10, 0, 0.46}, {1, 0, 0}, -2.5, 0.0, 0, 0},
    {"ankle_r", JointKind::kHinge, kShinR, kFootR, {0.10, 0, 0.06}, {1, 0, 0}, -0.7, 0.7, 0, 0},
}};

// Adds one ragdoll, rotated by `orientation` about its feet point and moved
// there to `base`.
inline void addRagdoll(Scene& s, const Vec3& base, const Quat& orientation) {
  const int first = static_cast<int>(s.bodies.size());
  auto place = [&](const Vec3& standing) { return add(base, rotate(orientation, standing)); };
  for (const RagdollPart& part : kRagdollParts) {
    BodySpec body = part.shape == ShapeKind::kSphere ? makeSphere(part.halfExtents[0], part.mass, place(part.centre))
                                                     : makeBox(part.halfExtents, part.mass, place(part.centre));
    body.pose.orientation = orientation;
    s.bodies.push_back(body);
  }
  for (const RagdollJoint& rj : kRagdollJoints) {
    JointSpec j;
    j.kind = rj.kind;
    j.bodyA = first + rj.parent;
    j.bodyB = first + rj.child;
    j.anchor = place(rj.anchor);
    j.axis = rotate(orientation, rj.axis);
    j.limited = true;
    j.lower = rj.lower;
    j.upper = rj.upper;
    j.swing = rj.swing;
    j.twist = rj.twist;
    s.joints.push_back(j);
  }
}

// ragdolls: a pile of 2 layers × 8 × 6 dynamic boxes (0.4 m cubes, 20 kg,
// 0.1 m gaps) on the ground, and N ragdolls (default 20) in a 5-wide grid,
// standing upright 1 m above the pile with a deterministic turn about z,
// that fall onto it. Contacts on, friction 0.5, no restitution; bodies
// joined by a joint do not collide with each other.
inline void buildRagdolls(Scene& s) {
  s.ground = true;
  s.contacts = true;
  constexpr double kBoxHalf = 0.2, kPitch = 0.5;
  for (int layer = 0; layer < 2; ++layer) {
    for (int row = 0; row < 6; ++row) {
      for (int column = 0; column < 8; ++column) {
        // odd layers shifted by a quarter pitch so the top is uneven
        const double shift = layer % 2 ? kPitch / 4 : 0;
        s.bodies.push_back(makeBox({kBoxHalf, kBoxHalf, kBoxHalf}, 20.0,
                                   {(column - 3.5) * kPitch + shift, (row - 2.5) * kPitch + shift,
                                    kBoxHalf + layer * (2 * kBoxHalf + 0.01)}));
      }
    }
  }
  const double top = 2 * (2 * kBoxHalf + 0.01);
  for (int i = 0; i < s.n; ++i) {
    const int column = i % 5, row = i / 5;
    const Vec3 base = {(column - 2) * 0.8, (row - 1.5) * 0.7, top + 1.0 + 0.1 * (i % 3)};
    addRagdoll(s, base, axisAngle({0, 0, 1}, 0.37 * i));
  }
}

inline bool makeScene(const std::string& name, int n, Scene& s) {
  s = Scene();
  s.name = name;
  if (name == "chain") {
    s.n = n > 0 ? n : 100;
    s.steps = 5000;
    buildChain(s);
  } else if (name == "grid") {
    s.n = n > 0 ? n : 50;
    s.steps = 2000;
    buildGrid(s);
  } else if (name == "ragdolls") {
    s.n = n > 0 ? n : 20;
    s.steps = 3000;
    buildRagdolls(s);
  } else {
    return false;
  }
  return true;
}

// ----------------------------------------------------------------- engine
class Engine {
 public:
  virtual ~Engine() = default;
  // World, gravity, solver iterations and the ground plane (s.ground).
  virtual void configure(const Scene& s) = 0;
  // Bodies are added in scene order; the returned index is the scene index.
  virtual void addBody(const BodySpec& body) = 0;
  // Called after all bodies; joint.bodyB may be kWorld.
  virtual void addJoint(const JointSpec& joint) = 0;
  // Exactly one fixed step (collision detection included). Timed.
  virtual void step(double dt) = 0;
  virtual Pose pose(int body) const = 0;
  virtual std::string settings() const = 0;  // solver settings, for the CFG line
  virtual std::string notes() const { return ""; }  // unsupported features, warnings
  // The engine's own counts over the rep (its solver's work per step), for
  // a STAT line after the REP line; empty: none.
  virtual std::string repStats() const { return ""; }
};

struct Options {
  std::string scene = "chain";
  int n = 0;  // 0: scene default
  int reps = 3;
  int steps = -1;
  int iters = -1;
  std::string label;
};

inline void usage(const char* program) {
  std::fprintf(stderr,
               "usage: %s --scene chain|grid|ragdolls [--n N] [--reps 3] [--steps S] [--iters 10] "
               "[--label NAME]\n",
               program);
}

inline bool parseOptions(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) {
      usage(argv[0]);
      return false;
    }
    const char* value = argv[++i];
    if (arg == "--scene") o.scene = value;
    else if (arg == "--n") o.n = std::atoi(value);
    else if (arg == "--reps") o.reps = std::atoi(value);
    else if (arg == "--steps") o.steps = std::atoi(value);
    else if (arg == "--iters") o.iters = std::atoi(value);
    else if (arg == "--label") o.label = value;
    else {
      usage(argv[0]);
      return false;
    }
  }
  return o.reps > 0;
}

// The anchor of every joint in the local frames of its two bodies, taken
// from the build poses; the world side of a pinned joint is the anchor.
struct AnchorPair {
  int bodyA, bodyB;
  Vec3 localA, localB;
};

inline std::vector<AnchorPair> localAnchors(const Scene& s) {
  std::vector<AnchorPair> anchors;
  anchors.reserve(s.joints.size());
  for (const JointSpec& j : s.joints) {
    AnchorPair a{j.bodyA, j.bodyB, toLocal(s.bodies[j.bodyA].pose, j.anchor), j.anchor};
    if (j.bodyB != kWorld) a.localB = toLocal(s.bodies[j.bodyB].pose, j.anchor);
    anchors.push_back(a);
  }
  return anchors;
}

// Largest distance between a joint's anchor as carried by body A and by
// body B: the positional error every joint type shares. NaN if any pose is
// not finite (an exploded simulation must not read as a small error).
inline double maxJointError(const Engine& engine, const std::vector<AnchorPair>& anchors) {
  double worst = 0;
  for (const AnchorPair& a : anchors) {
    const Vec3 pa = toWorld(engine.pose(a.bodyA), a.localA);
    const Vec3 pb = a.bodyB == kWorld ? a.localB : toWorld(engine.pose(a.bodyB), a.localB);
    const double e = norm(sub(pa, pb));
    if (!std::isfinite(e)) return NAN;
    worst = std::max(worst, e);
  }
  return worst;
}

struct RepResult {
  double setupSeconds = 0;
  double meanMs = 0, p99Ms = 0, maxMs = 0;
  double errorEnd = 0, errorMax = 0;  // m
  double lowestZ = 0;                 // lowest body centre at the end, m
};

inline double percentile(std::vector<double> v, double pct) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t k = std::max<size_t>(1, static_cast<size_t>(std::ceil(pct / 100 * static_cast<double>(v.size()))));
  return v[k - 1];
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

using Clock = std::chrono::steady_clock;

inline RepResult runRep(Engine& engine, const Scene& s, const std::vector<AnchorPair>& anchors) {
  RepResult r;
  const auto t0 = Clock::now();
  engine.configure(s);
  for (const BodySpec& b : s.bodies) engine.addBody(b);
  for (const JointSpec& j : s.joints) engine.addJoint(j);
  r.setupSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  std::vector<double> ms(static_cast<size_t>(s.steps));
  for (int i = 0; i < s.steps; ++i) {
    const auto a = Clock::now();
    engine.step(s.dt);
    const auto b = Clock::now();
    ms[static_cast<size_t>(i)] = std::chrono::duration<double, std::milli>(b - a).count();
    // Outside the timed region: the error is the runner's, not the engine's.
    const double e = maxJointError(engine, anchors);
    r.errorMax = std::isnan(e) || std::isnan(r.errorMax) ? NAN : std::max(r.errorMax, e);
  }
  double total = 0;
  for (double m : ms) total += m;
  r.meanMs = ms.empty() ? 0 : total / static_cast<double>(ms.size());
  r.p99Ms = percentile(ms, 99);
  r.maxMs = ms.empty() ? 0 : *std::max_element(ms.begin(), ms.end());
  r.errorEnd = maxJointError(engine, anchors);
  r.lowestZ = INFINITY;
  for (size_t i = 0; i < s.bodies.size(); ++i) {
    r.lowestZ = std::min(r.lowestZ, engine.pose(static_cast<int>(i)).position[2]);
  }
  return r;
}

// Runs o.reps fresh builds of the scene: one REP line each, then one ROW
// with the medians over the reps (the joint error is that of the first rep;
// reps of a deterministic engine are identical).
inline int runMain(int argc, char** argv, const std::string& engineName, const std::string& version,
                   const std::function<std::unique_ptr<Engine>()>& makeEngine) {
  Options o;
  if (!parseOptions(argc, argv, o)) return 2;
  Scene s;
  if (!makeScene(o.scene, o.n, s)) {
    usage(argv[0]);
    return 2;
  }
  if (o.steps > 0) s.steps = o.steps;
  if (o.iters > 0) s.velocityIterations = o.iters;
  const std::string label = o.label.empty() ? engineName : o.label;
  const std::vector<AnchorPair> anchors = localAnchors(s);

  std::vector<double> means, p99s;
  double firstError = 0;
  for (int rep = 0; rep < o.reps; ++rep) {
    std::unique_ptr<Engine> engine = makeEngine();
    const RepResult r = runRep(*engine, s, anchors);
    if (rep == 0) {
      std::printf("CFG engine=%s version=%s scene=%s bodies=%zu joints=%zu dt=%g steps=%d iterations=%d "
                  "settings=\"%s\" notes=\"%s\"\n",
                  label.c_str(), version.c_str(), s.name.c_str(), s.bodies.size(), s.joints.size(), s.dt, s.steps,
                  s.velocityIterations, engine->settings().c_str(), engine->notes().c_str());
    }
    std::printf("REP engine=%s scene=%s n=%d rep=%d setup_s=%.3f mean_ms=%.4f p99_ms=%.4f max_ms=%.3f "
                "joint_err_end_m=%.6g joint_err_max_m=%.6g lowest_z_m=%.4f\n",
                label.c_str(), s.name.c_str(), s.n, rep, r.setupSeconds, r.meanMs, r.p99Ms, r.maxMs, r.errorEnd,
                r.errorMax, r.lowestZ);
    const std::string stats = engine->repStats();
    if (!stats.empty()) std::printf("STAT engine=%s scene=%s n=%d rep=%d %s\n", label.c_str(), s.name.c_str(), s.n, rep, stats.c_str());
    std::fflush(stdout);
    means.push_back(r.meanMs);
    p99s.push_back(r.p99Ms);
    if (rep == 0) firstError = r.errorEnd;
  }
  std::printf("ROW | %s | %s | %d | %.4f | %.4f | %.3g |\n", label.c_str(), s.name.c_str(), s.n, median(means),
              median(p99s), firstError);
  return 0;
}

}  // namespace rbsim::bench::joints
