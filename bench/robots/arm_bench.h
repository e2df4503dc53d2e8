// The arm benchmark of bench/robots, shared by every engine's adapter: the
// arm as plain data, the engine interface, the PD controller, the timing
// loop, the error measurements and the output.
//
// The arm is config/robots/arm7.urdf as rbsim loads it (arm_model.h makes
// this data from rbsim's RobotModel, so every engine gets the same masses,
// principal inertias, centre-of-mass poses and joint frames). Each engine
// is given the same PD law on every joint, with the same gains, and the
// same targets: hold the start pose, then follow a slow sinusoid per joint.
//
// This header includes no engine header (as bench/joints/joint_scenes.h),
// so it serves Bullet's adapters as well as rbsim's.
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

namespace rbsim::bench::robots {

using Vec3 = std::array<double, 3>;
using Quat = std::array<double, 4>;  // (w, x, y, z)

constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------------- math
inline Vec3 add(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 scale(const Vec3& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

inline Quat conjugate(const Quat& q) {
  return {q[0], -q[1], -q[2], -q[3]};
}

inline Quat multiply(const Quat& a, const Quat& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

// v' = q v q* (q need not be exactly unit: engines round it to their
// precision).
inline Vec3 rotate(const Quat& q, const Vec3& v) {
  const Vec3 u = {q[1], q[2], q[3]};
  const Vec3 t = scale(cross(u, v), 2);
  return add(add(v, scale(t, q[0])), cross(u, t));
}

struct Pose {
  Vec3 position{0, 0, 0};        // m
  Quat orientation{1, 0, 0, 0};  // local -> world
};

inline Vec3 toLocal(const Pose& pose, const Vec3& world) {
  return rotate(conjugate(pose.orientation), sub(world, pose.position));
}

inline Vec3 toWorld(const Pose& pose, const Vec3& local) {
  return add(pose.position, rotate(pose.orientation, local));
}

// ------------------------------------------------------------------ scene
// A moving link: its centre-of-mass frame along its principal axes.
struct LinkSpec {
  std::string name;
  double mass = 0;        // kg
  Vec3 inertia{0, 0, 0};  // principal moments, kg m²
  Pose pose;              // of the centre of mass and the principal axes, at the start
};

constexpr int kBase = -1;  // the static base link

// A revolute joint between a parent (a link, or the base) and a child link.
struct JointSpec {
  std::string name;
  int parent = kBase;
  int child = 0;
  Vec3 anchor{0, 0, 0};  // world, at the start
  Vec3 axis{0, 0, 1};    // world, at the start, unit
  double position = 0;   // rad: the joint coordinate at the start (the URDF's zero is 0)
  double stiffness = 0;  // N·m/rad: the PD law's gains
  double damping = 0;    // N·m·s/rad
};

struct ArmScene {
  std::string robot;
  double dt = 1e-3;
  int steps = 5000;
  int holdSteps = 1000;  // the first second holds the start pose, then the sinusoids
  Vec3 gravity{0, 0, -9.81};
  Pose base;                      // the static base's frame
  std::vector<LinkSpec> links;    // parents before children
  std::vector<JointSpec> joints;  // joints[k].child == k
  // The sinusoid each joint follows after the hold: q0 + A sin(2π f (t − hold)).
  double amplitude = 0.3;           // rad
  std::vector<double> frequencies;  // Hz, per joint
};

// The PD law's gains: a natural frequency and damping ratio on the inertia
// each joint moves in the start pose with the other joints free (arm_model
// works it out). The same for every engine; 10 Hz at dt = 1 ms keeps an
// explicit PD torque stable (arm_model.cpp says why).
constexpr double kNaturalFrequency = 10.0;  // Hz
constexpr double kDampingRatio = 1.0;

// The target of joint k at step i (before the step is taken).
inline double target(const ArmScene& s, int joint, int step) {
  const double q0 = s.joints[static_cast<size_t>(joint)].position;
  if (step < s.holdSteps) return q0;
  const double t = (step - s.holdSteps) * s.dt;
  return q0 + s.amplitude * std::sin(2 * kPi * s.frequencies[static_cast<size_t>(joint)] * t);
}

// The joint coordinate and its rate as an engine reports them (or as
// hingeReading() works them out from the two bodies).
struct JointReading {
  double position = 0;  // rad, counted as JointSpec::position
  double rate = 0;      // rad/s
};

// For engines without joint coordinates of their own (rigid bodies joined
// by constraints): the child's turn about the axis relative to the parent
// since the start, from the parent's and the child's orientations, and the
// relative angular velocity along the axis. `start` is the child's
// orientation relative to the parent's at the start, `axisInParent` the
// axis in the parent's frame.
inline JointReading hingeReading(double startPosition, const Quat& parent, const Quat& child,
                                 const Quat& start, const Vec3& axisInParent,
                                 const Vec3& parentOmega, const Vec3& childOmega) {
  // r = parent⁻¹ child start⁻¹: the turn since the start, in the parent's frame.
  Quat r = multiply(multiply(conjugate(parent), child), conjugate(start));
  if (r[0] < 0) r = {-r[0], -r[1], -r[2], -r[3]};
  const double twist = 2 * std::atan2(dot({r[1], r[2], r[3]}, axisInParent), r[0]);
  const Vec3 axis = rotate(parent, axisInParent);
  return {startPosition + twist, dot(sub(childOmega, parentOmega), axis)};
}

// ----------------------------------------------------------------- engine
class ArmEngine {
 public:
  virtual ~ArmEngine() = default;
  virtual void build(const ArmScene& s) = 0;
  virtual void readJoints(std::vector<JointReading>& out) = 0;
  // One control cycle's command: each engine applies it as its PD mode
  // says (a native drive on `targets`, or the `torques` the harness's PD
  // law worked out from the readings).
  virtual void actuate(const std::vector<double>& targets, const std::vector<double>& torques) = 0;
  virtual void step() = 0;              // exactly one step of dt
  virtual Pose linkPose(int link) = 0;  // the centre-of-mass frame
  virtual std::string settings() const = 0;
};

struct Options {
  int reps = 3;
  int steps = -1;
  std::string label;
  std::string mode;  // engine-specific (rbsim: drive|effort)
};

inline void usage(const char* program, const char* modes) {
  std::fprintf(stderr, "usage: %s [--reps 3] [--steps 5000] [--label NAME]%s%s\n", program,
               modes[0] ? " " : "", modes);
}

inline bool parseOptions(int argc, char** argv, Options& o, const char* modes) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) {
      usage(argv[0], modes);
      return false;
    }
    const char* value = argv[++i];
    if (arg == "--reps")
      o.reps = std::atoi(value);
    else if (arg == "--steps")
      o.steps = std::atoi(value);
    else if (arg == "--label")
      o.label = value;
    else if (arg == "--pd" && modes[0])
      o.mode = value;
    else {
      usage(argv[0], modes);
      return false;
    }
  }
  return o.reps > 0;
}

// Each joint's anchor in the frames of its two sides, from the start poses.
struct AnchorPair {
  int parent, child;
  Vec3 inParent, inChild;
};

inline std::vector<AnchorPair> localAnchors(const ArmScene& s) {
  std::vector<AnchorPair> anchors;
  for (const JointSpec& j : s.joints) {
    const Pose& parent = j.parent == kBase ? s.base : s.links[static_cast<size_t>(j.parent)].pose;
    anchors.push_back({j.parent, j.child, toLocal(parent, j.anchor),
                       toLocal(s.links[static_cast<size_t>(j.child)].pose, j.anchor)});
  }
  return anchors;
}

// The largest distance between a joint's anchor as its parent carries it
// and as its child does; NaN when a pose is not finite.
inline double maxAnchorError(ArmEngine& engine, const ArmScene& s,
                             const std::vector<AnchorPair>& anchors) {
  double worst = 0;
  for (const AnchorPair& a : anchors) {
    const Vec3 p = toWorld(a.parent == kBase ? s.base : engine.linkPose(a.parent), a.inParent);
    const Vec3 c = toWorld(engine.linkPose(a.child), a.inChild);
    const double e = norm(sub(p, c));
    if (!std::isfinite(e)) return NAN;
    worst = std::max(worst, e);
  }
  return worst;
}

inline double percentile(std::vector<double> v, double pct) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t k = std::max<size_t>(
      1, static_cast<size_t>(std::ceil(pct / 100 * static_cast<double>(v.size()))));
  return v[k - 1];
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

inline double worse(double a, double b) {
  return std::isnan(a) || std::isnan(b) ? NAN : std::max(a, b);
}

struct RepResult {
  double setupMs = 0;
  // Per control cycle. On a shared machine a cycle that is preempted
  // counts whole, and a longer cycle is preempted more often: the median
  // is the cost of an undisturbed cycle.
  double meanMs = 0, medianMs = 0, p99Ms = 0, maxMs = 0;
  double anchorErrorMax = 0;  // m, over the run
  double holdErrorMax = 0;    // rad: largest |q − target| while holding
  double trackErrorMax = 0;   // rad: largest |q − target| while following the sinusoids
};

using Clock = std::chrono::steady_clock;

// One run: every step is one control cycle, timed whole: read the joints,
// work out the PD torques, command, step. The errors are measured outside
// the timed region.
inline RepResult runRep(ArmEngine& engine, const ArmScene& s,
                        const std::vector<AnchorPair>& anchors) {
  RepResult r;
  const auto t0 = Clock::now();
  engine.build(s);
  r.setupMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  const size_t n = s.joints.size();
  std::vector<JointReading> readings(n);
  std::vector<double> targets(n), torques(n);
  std::vector<double> ms(static_cast<size_t>(s.steps));
  for (int i = 0; i < s.steps; ++i) {
    for (size_t k = 0; k < n; ++k) targets[k] = target(s, static_cast<int>(k), i);
    const auto a = Clock::now();
    engine.readJoints(readings);
    for (size_t k = 0; k < n; ++k) {
      const JointSpec& j = s.joints[k];
      torques[k] =
          -j.stiffness * (readings[k].position - targets[k]) - j.damping * readings[k].rate;
    }
    engine.actuate(targets, torques);
    engine.step();
    const auto b = Clock::now();
    ms[static_cast<size_t>(i)] = std::chrono::duration<double, std::milli>(b - a).count();
    double tracking = 0;
    for (size_t k = 0; k < n; ++k)
      tracking = worse(tracking, std::abs(readings[k].position - targets[k]));
    if (i < s.holdSteps)
      r.holdErrorMax = worse(r.holdErrorMax, tracking);
    else
      r.trackErrorMax = worse(r.trackErrorMax, tracking);
    r.anchorErrorMax = worse(r.anchorErrorMax, maxAnchorError(engine, s, anchors));
  }
  double total = 0;
  for (double m : ms) total += m;
  r.meanMs = ms.empty() ? 0 : total / static_cast<double>(ms.size());
  r.medianMs = median(ms);
  r.p99Ms = percentile(ms, 99);
  r.maxMs = ms.empty() ? 0 : *std::max_element(ms.begin(), ms.end());
  return r;
}

// o.reps fresh builds: a CFG line, a REP line each, then a ROW with the
// medians of the times (the errors are the first rep's; a deterministic
// engine repeats them exactly).
inline int runMain(const Options& o, ArmScene s, const std::string& engineName,
                   const std::string& version,
                   const std::function<std::unique_ptr<ArmEngine>()>& makeEngine) {
  if (o.steps > 0) s.steps = o.steps;
  const std::string label = o.label.empty() ? engineName : o.label;
  const std::vector<AnchorPair> anchors = localAnchors(s);
  std::vector<double> means, medians, p99s;
  RepResult first;
  for (int rep = 0; rep < o.reps; ++rep) {
    std::unique_ptr<ArmEngine> engine = makeEngine();
    const RepResult r = runRep(*engine, s, anchors);
    if (rep == 0) {
      std::printf(
          "CFG engine=%s version=%s robot=%s links=%zu joints=%zu dt=%g steps=%d hold_steps=%d "
          "pd=\"%.0f Hz, damping ratio %.1f\" settings=\"%s\"\n",
          label.c_str(), version.c_str(), s.robot.c_str(), s.links.size(), s.joints.size(), s.dt,
          s.steps, s.holdSteps, kNaturalFrequency, kDampingRatio, engine->settings().c_str());
      first = r;
    }
    std::printf(
        "REP engine=%s rep=%d setup_ms=%.3f mean_ms=%.5f median_ms=%.5f p99_ms=%.5f max_ms=%.4f "
        "anchor_err_max_m=%.3g "
        "hold_err_max_rad=%.4g track_err_max_rad=%.4g\n",
        label.c_str(), rep, r.setupMs, r.meanMs, r.medianMs, r.p99Ms, r.maxMs, r.anchorErrorMax,
        r.holdErrorMax, r.trackErrorMax);
    std::fflush(stdout);
    means.push_back(r.meanMs);
    medians.push_back(r.medianMs);
    p99s.push_back(r.p99Ms);
  }
  std::printf("ROW | %s | %s | %zu | %.5f | %.5f | %.5f | %.3g | %.4g | %.4g |\n", label.c_str(),
              s.robot.c_str(), s.joints.size(), median(means), median(medians), median(p99s),
              first.anchorErrorMax, first.holdErrorMax, first.trackErrorMax);
  return 0;
}

}  // namespace rbsim::bench::robots
