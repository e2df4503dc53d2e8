#include "public_scenes.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "bench_paths.h"

namespace rbsim::bench::robots {

namespace {

std::string dataDir() {
  return std::string(rbsim::bench::kBenchRobotsDir) + "/data";
}

PublicScene arm(const std::string& name, const std::string& robot, const std::string& urdf,
                std::vector<std::string> joints, std::vector<double> start) {
  PublicScene s;
  s.name = name;
  s.robot = robot;
  s.urdf = dataDir() + "/" + urdf;
  s.joints = std::move(joints);
  s.start = std::move(start);
  return s;
}

PublicScene iiwa(const std::string& name) {
  std::vector<std::string> joints;
  for (int k = 1; k <= 7; ++k) joints.push_back("lbr_iiwa_joint_" + std::to_string(k));
  // Reaching forward, elbow bent, wrist down.
  return arm(name, "iiwa", "kuka_iiwa/model.urdf", joints, {0, 0.6, 0, -1.2, 0, 0.8, 0});
}

PublicScene panda(const std::string& name) {
  // The second finger is independent in this copy of the URDF (no mimic):
  // both are driven to the same opening.
  return arm(name, "panda", "franka_panda/panda.urdf",
             {"panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4", "panda_joint5",
              "panda_joint6", "panda_joint7", "panda_finger_joint1", "panda_finger_joint2"},
             {0, -0.3, 0, -2.2, 0, 2.0, 0.8, 0.02, 0.02});
}

PublicScene ur5e(const std::string& name) {
  return arm(name, "ur5e", "ur5e/ur5e.urdf",
             {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
              "wrist_2_joint", "wrist_3_joint"},
             {0, -1.2, 1.2, -1.57, -1.57, 0});
}

// The Panda reaching over a table with 20 objects on it, in a 5 × 4 grid:
// boxes, cylinders and convex mesh pebbles, resting 1 mm above the top.
PublicScene table() {
  PublicScene s = panda("table-panda");
  s.start = {0, 0.1, 0, -1.9, 0, 2.0, 0.8, 0.04, 0.04};
  s.table = true;
  s.tableHalfExtents = {0.3, 0.4, 0.2};
  s.tableCenter = {0.65, 0, 0.2};
  const double top = 0.4, gap = 0.001;
  const std::string pebble = dataDir() + "/objects/pebble.obj";
  for (int i = 0; i < 20; ++i) {
    const int row = i / 4, column = i % 4;
    ObjectSpec o;
    o.name = "object" + std::to_string(i);
    const double x = 0.43 + 0.11 * row, y = -0.27 + 0.18 * column;
    // A turn about z per object, so that no two sit alike.
    const double yaw = 0.37 * i;
    o.pose.orientation = {std::cos(yaw / 2), 0, 0, std::sin(yaw / 2)};
    switch (i % 3) {
      case 0:
        o.kind = ObjectSpec::Kind::Box;
        o.halfExtents = {0.02 + 0.002 * (i % 4), 0.025, 0.02 + 0.003 * (i % 5)};
        o.mass = 0.15;
        o.pose.position = {x, y, top + gap + o.halfExtents[2]};
        break;
      case 1:
        o.kind = ObjectSpec::Kind::Cylinder;
        o.radius = 0.02 + 0.002 * (i % 4);
        o.halfLength = 0.03;
        o.mass = 0.12;
        o.pose.position = {x, y, top + gap + o.halfLength};
        break;
      default:
        o.kind = ObjectSpec::Kind::Mesh;
        o.mesh = pebble;
        o.mass = 0.05;
        o.pose.position = {x, y, top + gap + 0.016};  // the pebble's half height
        break;
    }
    s.objects.push_back(o);
  }
  return s;
}

}  // namespace

std::vector<PublicScene> publicScenes() {
  std::vector<PublicScene> scenes;
  // (1) Held at a pose, self-collision off.
  scenes.push_back(iiwa("hold-iiwa"));
  scenes.push_back(panda("hold-panda"));
  scenes.push_back(ur5e("hold-ur5e"));
  // (2) Folded and unfolded every 2 s (a raised cosine between the start
  // pose and the folded one), self-collision on: the forearm comes close
  // to the upper arm and the hand to the forearm.
  PublicScene foldIiwa = iiwa("fold-iiwa");
  foldIiwa.fold = {0.5, 1.2, 0, -2.05, 0, 2.05, 0};
  PublicScene foldPanda = panda("fold-panda");
  foldPanda.fold = {0, 0.2, 0, -3.0, 0, 3.6, 0.8, 0.04, 0.04};
  PublicScene foldUr5e = ur5e("fold-ur5e");
  foldUr5e.fold = {0, -0.6, 2.8, -2.5, -1.57, 0};
  for (PublicScene* s : {&foldIiwa, &foldPanda, &foldUr5e}) {
    s->selfCollision = true;
    scenes.push_back(*s);
  }
  // (3) The A1 standing: its zero pose is outside the calf limits
  // [−2.70, −0.92] rad, so it starts at a standing pose (thigh 0.8, calf
  // −1.6 rad: the feet 0.30 m below the hips), dropped from 1 cm.
  PublicScene a1 = arm("stand-a1", "a1", "a1/a1.urdf", {}, {});
  a1.fixedBase = false;
  a1.base.position = {0, 0, 0.31};
  for (const char* leg : {"FR", "FL", "RR", "RL"}) {
    for (const char* joint : {"_hip_joint", "_upper_joint", "_lower_joint"})
      a1.joints.push_back(std::string(leg) + joint);
    a1.start.insert(a1.start.end(), {0.0, 0.8, -1.6});
  }
  // Stiffer than the arms: the legs carry the trunk (12 kg in all).
  a1.naturalFrequency = 20.0;
  scenes.push_back(a1);
  // The Solo-12 standing, the quadruped whose links collide as meshes (STL
  // hulls; the feet are discs): its "standing" pose of example-robot-data's
  // srdf/solo.srdf (hips ±0.1 rad outward, the front knees bent back, the
  // hind ones forward: the feet 0.22 m below the hips, their discs' radius
  // 16 mm), dropped from about 1 cm.
  PublicScene solo = arm("stand-solo12", "solo12", "solo12/solo12.urdf", {}, {});
  solo.fixedBase = false;
  solo.base.position = {0, 0, 0.25};
  for (const char* leg : {"FL", "FR", "HL", "HR"}) {
    const double side = leg[1] == 'L' ? 1 : -1, end = leg[0] == 'F' ? 1 : -1;
    for (const char* joint : {"_HAA", "_HFE", "_KFE"})
      solo.joints.push_back(std::string(leg) + joint);
    solo.start.insert(solo.start.end(), {0.1 * side, 0.8 * end, -1.6 * end});
  }
  // As the A1's: the legs carry the trunk.
  solo.naturalFrequency = 20.0;
  scenes.push_back(solo);
  // (4) The table.
  scenes.push_back(table());
  return scenes;
}

double publicTarget(const PublicScene& s, size_t joint, int step) {
  const double q0 = s.start[joint];
  if (s.fold.empty()) return q0;
  const double t = step * s.dt;
  const double blend = 0.5 * (1 - std::cos(2 * kPi * t / s.foldPeriod));
  return q0 + blend * (s.fold[joint] - q0);
}

namespace {

void publicUsage(const char* program) {
  std::fprintf(stderr,
               "usage: %s [--scene NAME[,NAME...]|all] [--steps N] [--reps R] "
               "[--self-collision on|off] [--label NAME] [--write-worlds DIR]\n"
               "scenes:",
               program);
  for (const PublicScene& s : publicScenes()) std::fprintf(stderr, " %s", s.name.c_str());
  std::fprintf(stderr, "\n");
}

}  // namespace

bool parsePublicOptions(int argc, char** argv, PublicOptions& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) {
      publicUsage(argv[0]);
      return false;
    }
    const std::string value = argv[++i];
    if (arg == "--scene") {
      if (value == "all") continue;
      size_t begin = 0;
      while (begin <= value.size()) {
        const size_t comma = value.find(',', begin);
        const size_t end = comma == std::string::npos ? value.size() : comma;
        if (end > begin) o.scenes.push_back(value.substr(begin, end - begin));
        begin = end + 1;
      }
    } else if (arg == "--steps") {
      o.steps = std::atoi(value.c_str());
    } else if (arg == "--reps") {
      o.reps = std::atoi(value.c_str());
    } else if (arg == "--self-collision" && (value == "on" || value == "off")) {
      o.selfCollision = value == "on" ? 1 : 0;
    } else if (arg == "--label") {
      o.label = value;
    } else if (arg == "--write-worlds") {
      o.writeWorlds = value;
    } else {
      publicUsage(argv[0]);
      return false;
    }
  }
  const std::vector<PublicScene> all = publicScenes();
  for (const std::string& name : o.scenes) {
    bool known = false;
    for (const PublicScene& s : all) known = known || s.name == name;
    if (!known) {
      std::fprintf(stderr, "unknown scene %s\n", name.c_str());
      publicUsage(argv[0]);
      return false;
    }
  }
  return o.reps > 0 && o.steps != 0;
}

namespace {

struct PublicRep {
  double setupMs = 0;
  double meanMs = 0, medianMs = 0, p99Ms = 0, maxMs = 0;
  double contactsMean = 0;  // points after a step, over the run
  int contactsLast = 0;
  double errorMax = 0;  // rad or m: largest |q − q*| over the joints and the run
};

PublicRep runPublicRep(PublicEngine& engine, const PublicScene& s,
                       const std::vector<JointGains>& gains) {
  PublicRep r;
  const auto t0 = Clock::now();
  engine.build(s, gains);
  r.setupMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  const size_t n = s.joints.size();
  std::vector<JointReading> readings(n);
  std::vector<double> targets(n), efforts(n, 0.0);
  std::vector<double> ms(static_cast<size_t>(s.steps));
  const bool native = engine.nativeDrives(), damp = engine.explicitDamping();
  double contacts = 0;
  for (int i = 0; i < s.steps; ++i) {
    for (size_t k = 0; k < n; ++k) targets[k] = publicTarget(s, k, i);
    const auto a = Clock::now();
    engine.readJoints(readings);
    if (!native) {
      for (size_t k = 0; k < n; ++k)
        efforts[k] = -gains[k].stiffness * (readings[k].position - targets[k]) -
                     (damp ? gains[k].damping * readings[k].rate : 0.0);
    }
    engine.actuate(targets, efforts);
    engine.step();
    ms[static_cast<size_t>(i)] =
        std::chrono::duration<double, std::milli>(Clock::now() - a).count();
    for (size_t k = 0; k < n; ++k)
      r.errorMax = worse(r.errorMax, std::abs(readings[k].position - targets[k]));
    r.contactsLast = engine.contactPoints();
    contacts += r.contactsLast;
  }
  double total = 0;
  for (double m : ms) total += m;
  r.meanMs = ms.empty() ? 0 : total / static_cast<double>(ms.size());
  r.medianMs = median(ms);
  r.p99Ms = percentile(ms, 99);
  r.maxMs = ms.empty() ? 0 : *std::max_element(ms.begin(), ms.end());
  r.contactsMean = s.steps > 0 ? contacts / s.steps : 0;
  return r;
}

}  // namespace

int runPublic(const PublicOptions& o, const std::string& engineName, const std::string& version,
              const std::function<std::unique_ptr<PublicEngine>()>& makeEngine,
              const std::function<std::vector<JointGains>(const PublicScene&)>& gainsOf) {
  const std::string label = o.label.empty() ? engineName : o.label;
  std::printf(
      "ROW | engine | scene | self-collision | bodies | joints | mean ms | median ms | p99 ms | "
      "real-time factor | contact points (mean) | max joint error |\n");
  for (PublicScene s : publicScenes()) {
    bool chosen = o.scenes.empty();
    for (const std::string& name : o.scenes) chosen = chosen || name == s.name;
    if (!chosen) continue;
    if (o.steps > 0) s.steps = o.steps;
    if (o.selfCollision >= 0) s.selfCollision = o.selfCollision == 1;
    const std::vector<JointGains> gains = gainsOf(s);
    std::vector<double> means, medians, p99s;
    PublicRep first;
    int bodies = 0;
    for (int rep = 0; rep < o.reps; ++rep) {
      std::unique_ptr<PublicEngine> engine = makeEngine();
      const PublicRep r = runPublicRep(*engine, s, gains);
      if (rep == 0) {
        bodies = engine->bodyCount();
        std::printf(
            "CFG engine=%s version=%s scene=%s robot=%s joints=%zu objects=%zu dt=%g steps=%d "
            "self_collision=%s pd=\"%.0f Hz, damping ratio %.1f\" settings=\"%s\"\n",
            label.c_str(), version.c_str(), s.name.c_str(), s.robot.c_str(), s.joints.size(),
            s.objects.size(), s.dt, s.steps, s.selfCollision ? "on" : "off", s.naturalFrequency,
            s.dampingRatio, engine->settings().c_str());
        first = r;
      }
      std::printf(
          "REP engine=%s scene=%s rep=%d setup_ms=%.2f mean_ms=%.4f median_ms=%.4f p99_ms=%.4f "
          "max_ms=%.3f contacts_mean=%.1f contacts_last=%d max_joint_err=%.4g\n",
          label.c_str(), s.name.c_str(), rep, r.setupMs, r.meanMs, r.medianMs, r.p99Ms, r.maxMs,
          r.contactsMean, r.contactsLast, r.errorMax);
      std::fflush(stdout);
      means.push_back(r.meanMs);
      medians.push_back(r.medianMs);
      p99s.push_back(r.p99Ms);
    }
    const double mean = median(means);
    std::printf("ROW | %s | %s | %s | %d | %zu | %.4f | %.4f | %.4f | %.3g | %.1f | %.4g |\n",
                label.c_str(), s.name.c_str(), s.selfCollision ? "on" : "off", bodies,
                s.joints.size(), mean, median(medians), median(p99s),
                mean > 0 ? s.dt * 1e3 / mean : 0.0, first.contactsMean, first.errorMax);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace rbsim::bench::robots
