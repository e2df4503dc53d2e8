// Stacking benchmark scenes (issue 16), shared by the engine adapters in
// bench/stacks (rbsim, Bullet, ODE): the large pyramid and the anchors'
// tower of cubes, the two scenes whose point is that the solver holds a
// stack still.
//
// As bench/joints/joint_scenes.h, this header includes no engine header: a
// scene is plain data (cubes with their mass, inertia and pose, a static
// ground plane), built deterministically here, so every engine starts from
// bit-identical bodies. An adapter implements Engine and calls runMain();
// the runner owns the timing loop, the drift measurement, the disturbance
// checks and the output, which follow the anchors harness (its scene.hpp,
// kept outside this repository): the same option names, and REP and ROW
// lines with the same fields in the same order, so that rows of both
// harnesses can stand in one table (bench/compare_anchors.sh).
//
// Conventions: SI units, z up, quaternions (w, x, y, z), world frame.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

namespace rbsim::bench::stacks {

using Vec3 = std::array<double, 3>;
using Quat = std::array<double, 4>;  // (w, x, y, z)

// The anchors' cube and contact (make_box() in their scene.hpp): half
// extent 0.1 m, density 1000 kg/m³, so 8 kg and I = m (2 side²) / 12 about
// every axis; Coulomb friction 0.5 for every pair, no restitution.
constexpr double kBoxHalf = 0.1;           // m
constexpr double kDensity = 1000.0;        // kg/m³
constexpr double kFriction = 0.5;          // effective coefficient per pair
constexpr double kRestitution = 0.0;
constexpr double kStandingDrift = 1e-3;    // m: the "top box drifts less than 1 mm"

struct BodySpec {
  double half = kBoxHalf;  // cube half extent, m
  double mass = 0;         // kg
  double inertia = 0;      // kg m², the same about every axis (a cube)
  Vec3 position{0, 0, 0};
  Quat orientation{1, 0, 0, 0};
};

struct Scene {
  std::string name;
  int n = 0;            // the scene's size parameter (pyramid: base count; stack: cubes)
  double dt = 1e-3;     // s
  int steps = 10000;    // 10 s
  double gravity = -9.81;  // m/s², along z
  bool sleep = false;   // the scene's default for --sleep
  std::vector<BodySpec> bodies;  // all dynamic; the ground is the plane z = 0, normal +z
  int track = -1;       // the body whose drift is reported: the top box
};

inline BodySpec makeCube(const Vec3& position) {
  BodySpec b;
  const double side = 2 * kBoxHalf;
  b.mass = kDensity * side * side * side;        // 8 kg
  b.inertia = b.mass * (2 * side * side) / 12.0;  // 0.0533 kg m²
  b.position = position;
  return b;
}

// pyramid: the layout of the "large pyramid" of Box2D's benchmark suite
// (Box2D v3; issue 16 names Box3D's too), made of the anchors' cubes: row i
// (0 at the bottom) has base − i cubes side by side, each row shifted by half
// a cube against the one below, so that every cube rests on two. As in
// Box2D's benchmark the cubes exactly touch, without spacing: row i's centres
// are at z = (2 i + 1) h and x = h (2 k + 1 + i − base), k = 0 … base − i − 1
// (the pyramid is centred on x = 0). (Box2D's benchmark builds 100 at the
// base; issue 16 asks for 90. The older Box2D testbed pyramid spaced the
// boxes by 1/8 of their size instead; the benchmark's layout starts at rest,
// so what it measures is the solver holding the pyramid, not the settling.)
// All cubes lie in the vertical plane y = 0 (a 2-D scene in 3-D: nothing
// holds it in that plane but the symmetry). Base 90: 4095 cubes, 18 m wide
// and tall. Sleeping off by default: the point is that the solver itself
// holds the pyramid still. The top cube is tracked.
inline void buildPyramid(Scene& s) {
  const int base = s.n;
  for (int row = 0; row < base; ++row) {
    const double z = (2 * row + 1) * kBoxHalf;
    for (int k = 0; k < base - row; ++k) {
      s.bodies.push_back(makeCube({kBoxHalf * (2 * k + 1 + row - base), 0, z}));
    }
  }
  s.track = static_cast<int>(s.bodies.size()) - 1;
  s.sleep = false;
}

// stack: the anchors' tower of n cubes, exactly touching (z_i = 0.1 + 0.2 i),
// unrotated; the top cube is tracked. Sleeping on by default, as in the
// anchors harness, so that its rows and these compare.
inline void buildStack(Scene& s) {
  for (int i = 0; i < s.n; ++i) s.bodies.push_back(makeCube({0, 0, kBoxHalf + 2 * kBoxHalf * i}));
  s.track = s.n - 1;
  s.sleep = true;
}

inline bool makeScene(const std::string& name, int n, Scene& s) {
  s = Scene();
  s.name = name;
  if (name == "pyramid") {
    s.n = n > 0 ? n : 90;
    buildPyramid(s);
  } else if (name == "stack") {
    s.n = n > 0 ? n : 20;
    buildStack(s);
  } else {
    return false;
  }
  return true;
}

// ---------------------------------------------------------------- engine
// What an adapter is told beyond the scene: resolved from the options and
// the scene's defaults by the runner.
struct EngineSettings {
  bool sleep = false;   // the engine may put bodies at rest to sleep
  int iterations = -1;  // solver iterations; < 0: the engine's default
  int threads = 1;      // threads of an engine that has them (rbsim's world.threads; 0: one per core)
  std::string solver;   // rbsim's contact solver (sequential_impulses, soft_step); empty: its default
  int substeps = -1;    // rbsim's soft-step sub-steps; < 0: its default
  double contactHertz = -1;  // rbsim's soft-step contact stiffness; <= 0: its default
};

struct BodyState {
  Vec3 position{0, 0, 0};         // m, centre of mass, world
  Vec3 velocity{0, 0, 0};         // m/s, world
  Vec3 angularVelocity{0, 0, 0};  // rad/s, any frame (only its norm is used: cubes are isotropic)
};

class Engine {
 public:
  virtual ~Engine() = default;
  // World, gravity, the ground plane z = 0, the scene's bodies in order
  // (body i of the scene is state(i)). Timed apart from the steps.
  virtual void build(const Scene& s, const EngineSettings& settings) = 0;
  virtual void step() = 0;  // exactly one fixed step of s.dt, collision detection included. Timed.
  virtual BodyState state(int body) const = 0;
  virtual long contacts() const = 0;                // contact points held now, -1 if not exposed
  virtual std::string settings() const = 0;         // solver settings, for the CFG line
  virtual std::string notes() const { return ""; }  // sleeping bodies, warnings
};

// -------------------------------------------------------------- options
struct Options {
  std::string scene = "pyramid";
  int n = 0;            // 0: the scene's default
  int reps = 3;
  int steps = -1;       // < 0: the scene's default
  double dt = -1;       // <= 0: the scene's default
  int iters = -1;       // < 0: the engine's default
  int sleep = -1;       // < 0: the scene's default
  double maxWall = 0;   // s of stepping per rep; 0: no cap
  std::string label;    // engine label in the output
  int threads = 1;      // engines with threads (rbsim); the peers' adapters run on one
  std::string solver;   // rbsim only: its contact solver
  int substeps = -1;    // rbsim only: the soft-step solver's sub-steps
  double contactHertz = -1;  // rbsim only: the soft-step solver's contact stiffness (Hz)
};

inline void usage(const char* program) {
  std::fprintf(stderr,
               "usage: %s --scene pyramid|stack [--n N] [--reps 3] [--steps S] [--dt DT] [--iters K]\n"
               "          [--sleep 0|1] [--max-wall SEC] [--label NAME] [--threads N]\n"
               "          [--solver sequential_impulses|soft_step] [--substeps N] [--contact-hertz F]  (rbsim only)\n"
               "  pyramid: --n = base count (90: 4095 cubes), sleeping off by default\n"
               "  stack:   --n = cubes in the tower (20), sleeping on by default (as the anchors)\n",
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
    else if (arg == "--dt") o.dt = std::atof(value);
    else if (arg == "--iters") o.iters = std::atoi(value);
    else if (arg == "--sleep") o.sleep = std::atoi(value);
    else if (arg == "--max-wall") o.maxWall = std::atof(value);
    else if (arg == "--label") o.label = value;
    else if (arg == "--threads") o.threads = std::atoi(value);
    else if (arg == "--solver") o.solver = value;
    else if (arg == "--substeps") o.substeps = std::atoi(value);
    else if (arg == "--contact-hertz") o.contactHertz = std::atof(value);
    else {
      usage(argv[0]);
      return false;
    }
  }
  return o.reps > 0;
}

// ---------------------------------------------------------- disturbance
// A timing is only as good as the machine was quiet: per-CPU jiffies from
// /proc/stat before and after the steps give the busiest other core's load
// and this core's steal time, getrusage the involuntary context switches.
// The row shows the worst rep, so a disturbed row can be seen and re-run.
struct CpuTimes {
  std::vector<unsigned long long> busy, total, steal;
};

inline CpuTimes readCpuTimes() {
  CpuTimes t;
  FILE* file = std::fopen("/proc/stat", "r");
  if (!file) return t;
  char line[512];
  while (std::fgets(line, sizeof line, file)) {
    if (std::strncmp(line, "cpu", 3) != 0) break;  // the cpu lines come first
    if (line[3] == ' ') continue;                   // the all-CPU sum
    int cpu = -1;
    // user nice system idle iowait irq softirq steal
    unsigned long long f[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    const int read = std::sscanf(line, "cpu%d %llu %llu %llu %llu %llu %llu %llu %llu", &cpu, &f[0], &f[1], &f[2],
                                 &f[3], &f[4], &f[5], &f[6], &f[7]);
    if (read < 5 || cpu < 0) continue;
    const auto index = static_cast<size_t>(cpu);
    if (index >= t.total.size()) {
      t.busy.resize(index + 1, 0);
      t.total.resize(index + 1, 0);
      t.steal.resize(index + 1, 0);
    }
    unsigned long long total = 0;
    for (unsigned long long x : f) total += x;
    t.total[index] = total;
    t.busy[index] = total - f[3] - f[4];  // all but idle and iowait
    t.steal[index] = f[7];
  }
  std::fclose(file);
  return t;
}

struct Disturbance {
  double otherBusyPct = -1;  // the busiest other core, %
  double ownStealPct = -1;   // steal time of our core, %
  long involuntarySwitches = -1;
};

inline Disturbance disturbance(const CpuTimes& before, const CpuTimes& after, const rusage& usageBefore,
                               const rusage& usageAfter) {
  Disturbance d;
  d.involuntarySwitches = usageAfter.ru_nivcsw - usageBefore.ru_nivcsw;
  const int own = sched_getcpu();
  const size_t cpus = std::min(before.total.size(), after.total.size());
  for (size_t c = 0; c < cpus; ++c) {
    const double total = static_cast<double>(after.total[c] - before.total[c]);
    if (total <= 0) continue;
    if (static_cast<int>(c) == own) {
      d.ownStealPct = 100.0 * static_cast<double>(after.steal[c] - before.steal[c]) / total;
    } else {
      d.otherBusyPct = std::max(d.otherBusyPct, 100.0 * static_cast<double>(after.busy[c] - before.busy[c]) / total);
    }
  }
  return d;
}

// ---------------------------------------------------------------- runner
struct RepResult {
  int stepsDone = 0;
  bool timedOut = false;
  double setupSeconds = 0;
  double meanMs = 0, p99Ms = 0, maxMs = 0;
  double lastMeanMs = 0, lastP99Ms = 0;  // the last simulated second
  long contacts = -1;
  double ke0 = 0, ke = 0, vmax = 0;      // J, J, m/s
  double driftXy = 0, driftZ = 0;        // m: the top box at the end against its start
  double driftXyMax = 0;                 // m: the top box's largest horizontal excursion over the run
  bool finite = true;
  std::string notes;
  Disturbance noise;
};

inline double percentile(std::vector<double> v, double pct) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t k = std::max<size_t>(1, static_cast<size_t>(std::ceil(pct / 100 * static_cast<double>(v.size()))));
  return v[k - 1];  // nearest rank
}

inline double mean(const std::vector<double>& v, size_t from, size_t to) {
  double sum = 0;
  for (size_t i = from; i < to; ++i) sum += v[i];
  return to > from ? sum / static_cast<double>(to - from) : 0;
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Total kinetic energy Σ ½ m v² + ½ I |ω|² (cubes: isotropic inertia), the
// fastest body's speed, and whether every state number is finite (an
// exploded simulation must not read as a still one).
inline double kineticEnergy(const Engine& engine, const Scene& s, double* vmax, bool* finite) {
  double ke = 0;
  *vmax = 0;
  *finite = true;
  for (size_t i = 0; i < s.bodies.size(); ++i) {
    const BodyState b = engine.state(static_cast<int>(i));
    const double v2 = dot(b.velocity, b.velocity), w2 = dot(b.angularVelocity, b.angularVelocity);
    if (!std::isfinite(v2) || !std::isfinite(w2) || !std::isfinite(dot(b.position, b.position))) *finite = false;
    ke += 0.5 * s.bodies[i].mass * v2 + 0.5 * s.bodies[i].inertia * w2;
    *vmax = std::max(*vmax, std::sqrt(v2));
  }
  return ke;
}

using Clock = std::chrono::steady_clock;

inline RepResult runRep(Engine& engine, const Scene& s, const EngineSettings& settings, double maxWall) {
  RepResult r;
  const auto t0 = Clock::now();
  engine.build(s, settings);
  r.setupSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  bool finite = true;
  r.ke0 = kineticEnergy(engine, s, &r.vmax, &finite);
  const Vec3 start = engine.state(s.track).position;

  std::vector<double> ms(static_cast<size_t>(s.steps), 0.0);
  rusage usage0, usage1;
  getrusage(RUSAGE_SELF, &usage0);
  const CpuTimes cpu0 = readCpuTimes();
  const auto begin = Clock::now();
  for (int i = 0; i < s.steps; ++i) {
    const auto a = Clock::now();
    engine.step();
    const auto b = Clock::now();
    ms[static_cast<size_t>(i)] = std::chrono::duration<double, std::milli>(b - a).count();
    r.stepsDone = i + 1;
    // Outside the timed region: the top box's sway, which could come back
    // by the end and so not show in the final drift.
    const Vec3 p = engine.state(s.track).position;
    const double sway = std::hypot(p[0] - start[0], p[1] - start[1]);
    r.driftXyMax = std::isfinite(sway) && std::isfinite(r.driftXyMax) ? std::max(r.driftXyMax, sway) : NAN;
    if (maxWall > 0 && std::chrono::duration<double>(b - begin).count() > maxWall && i + 1 < s.steps) {
      r.timedOut = true;
      break;
    }
  }
  const CpuTimes cpu1 = readCpuTimes();
  getrusage(RUSAGE_SELF, &usage1);
  r.noise = disturbance(cpu0, cpu1, usage0, usage1);
  ms.resize(static_cast<size_t>(r.stepsDone));
  r.meanMs = mean(ms, 0, ms.size());
  r.p99Ms = percentile(ms, 99);
  r.maxMs = ms.empty() ? 0 : *std::max_element(ms.begin(), ms.end());
  const size_t window = std::min(ms.size(), static_cast<size_t>(std::llround(1.0 / s.dt)));
  const std::vector<double> last(ms.end() - static_cast<long>(window), ms.end());
  r.lastMeanMs = mean(last, 0, last.size());
  r.lastP99Ms = percentile(last, 99);
  r.contacts = engine.contacts();
  r.ke = kineticEnergy(engine, s, &r.vmax, &r.finite);
  const Vec3 end = engine.state(s.track).position;
  r.driftXy = std::hypot(end[0] - start[0], end[1] - start[1]);
  r.driftZ = end[2] - start[2];
  r.notes = engine.notes();
  return r;
}

inline std::string format(const char* f, double v) {
  char text[64];
  std::snprintf(text, sizeof text, f, v);
  return text;
}

inline void watchdog(int) {
  const char message[] = "WATCHDOG: a single step or the setup ran past --max-wall + 120 s; aborting\n";
  const ssize_t written = write(2, message, sizeof message - 1);
  (void)written;
  _exit(124);
}

// Runs o.reps fresh builds of the scene: a CFG line, one REP line each and
// one markdown ROW with the medians over the reps of the timings (the
// physics figures are the first rep's; the row says if another rep ended
// elsewhere). The REP and ROW fields are the anchors harness's, in its
// order; REP adds drift_xy_max at the end. An engine that can sleep
// (sleepingEngine) is labelled NAME-nosleep when it runs without, as
// bench/compare_anchors.sh names such rows.
inline int runMain(int argc, char** argv, const std::string& engineName, bool sleepingEngine,
                   const std::string& version, const std::function<std::unique_ptr<Engine>()>& makeEngine) {
  Options o;
  if (!parseOptions(argc, argv, o)) return 2;
  Scene s;
  if (!makeScene(o.scene, o.n, s)) {
    usage(argv[0]);
    return 2;
  }
  if (o.steps > 0) s.steps = o.steps;
  if (o.dt > 0) s.dt = o.dt;
  EngineSettings settings;
  settings.sleep = o.sleep < 0 ? s.sleep : o.sleep != 0;
  settings.iterations = o.iters;
  settings.threads = o.threads;
  settings.solver = o.solver;
  settings.substeps = o.substeps;
  settings.contactHertz = o.contactHertz;
  const std::string label =
      !o.label.empty() ? o.label : engineName + (o.solver == "soft_step" ? "-soft" : "") +
                               (sleepingEngine && !settings.sleep ? "-nosleep" : "");

  if (o.maxWall > 0) std::signal(SIGALRM, watchdog);
  std::vector<RepResult> reps;
  for (int rep = 0; rep < o.reps; ++rep) {
    if (o.maxWall > 0) alarm(static_cast<unsigned>(o.maxWall + 120));
    RepResult r;
    {
      const std::unique_ptr<Engine> engine = makeEngine();
      r = runRep(*engine, s, settings, o.maxWall);
      if (rep == 0) {
        std::printf("CFG engine=%s version=%s scene=%s n=%d bodies=%zu dt=%g steps=%d settings=\"%s\"\n",
                    label.c_str(), version.c_str(), s.name.c_str(), s.n, s.bodies.size(), s.dt, s.steps,
                    engine->settings().c_str());
      }
    }
    alarm(0);
    std::printf("REP engine=%s scene=%s n=%d rep=%d dt=%g steps=%d/%d timeout=%d setup_s=%.3f mean_ms=%.4f "
                "p99_ms=%.4f max_ms=%.3f last_mean_ms=%.4f last_p99_ms=%.4f contacts=%ld ke0=%.6g ke=%.6g "
                "vmax=%.4g drift_xy=%.6f drift_z=%.6f finite=%d other_cpu_busy_pct=%.1f own_steal_pct=%.1f "
                "nivcsw=%ld notes=\"%s\" drift_xy_max=%.6f\n",
                label.c_str(), s.name.c_str(), s.n, rep, s.dt, r.stepsDone, s.steps, r.timedOut ? 1 : 0,
                r.setupSeconds, r.meanMs, r.p99Ms, r.maxMs, r.lastMeanMs, r.lastP99Ms, r.contacts, r.ke0, r.ke,
                r.vmax, r.driftXy, r.driftZ, r.finite ? 1 : 0, r.noise.otherBusyPct, r.noise.ownStealPct,
                r.noise.involuntarySwitches, r.notes.c_str(), r.driftXyMax);
    std::fflush(stdout);
    reps.push_back(r);
    if (r.timedOut) break;  // a rep that hit the cap would hit it again
  }

  auto medianOf = [&reps](double RepResult::*field) {
    std::vector<double> v;
    for (const RepResult& r : reps) v.push_back(r.*field);
    return median(v);
  };
  const RepResult& first = reps.front();
  bool samePhysics = true;
  for (const RepResult& r : reps) samePhysics = samePhysics && r.ke == first.ke && r.driftXy == first.driftXy;
  std::string physics = "top dxy " + format("%.6f", first.driftXy) + " m, dz " + format("%+.6f", first.driftZ) +
                        " m, KE " + format("%.3g", first.ke) + " J";
  // Stands: the criterion, on the top box's horizontal drift (its
  // sinking, dz, is mostly the contacts' compression and shows on its own).
  // A top box off by half a cube or more has left its place: collapsed.
  const bool collapsed = !first.finite || first.driftXy >= kBoxHalf || first.driftZ <= -kBoxHalf;
  if (collapsed) physics += ", COLLAPSED (top moved >= half a cube)";
  else if (first.driftXy < kStandingDrift) physics += ", stands (top dxy < 1 mm)";
  else physics += ", top dxy >= 1 mm";
  if (!first.finite) physics += ", NON-FINITE STATE";
  if (!samePhysics) physics += ", reps differ";
  std::string status = first.timedOut
                           ? "TIMEOUT after " + std::to_string(first.stepsDone) + "/" + std::to_string(s.steps) + " steps"
                           : std::to_string(reps.size()) + " reps";
  double busy = 0;
  long switches = 0;
  for (const RepResult& r : reps) {
    busy = std::max(busy, r.noise.otherBusyPct);
    switches = std::max(switches, r.noise.involuntarySwitches);
  }
  status += "; other core busy <=" + format("%.0f", busy) + "%, preempted <=" + std::to_string(switches) + "x";
  if (!first.notes.empty()) status += "; " + first.notes;
  const double meanMs = medianOf(&RepResult::meanMs);
  std::printf("ROW | %s | %s | %d | %.4f | %.4f | %.0f | %.4f | %.4f | %s | %s | %s |\n", label.c_str(),
              s.name.c_str(), s.n, meanMs, medianOf(&RepResult::p99Ms), meanMs > 0 ? 1000.0 / meanMs : 0.0,
              medianOf(&RepResult::lastMeanMs), medianOf(&RepResult::lastP99Ms),
              first.contacts >= 0 ? std::to_string(first.contacts).c_str() : "n/a", physics.c_str(), status.c_str());
  return 0;
}

}  // namespace rbsim::bench::stacks
