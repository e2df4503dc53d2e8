// rbsim as an engine of the anchors benchmark harness (kept outside this
// repository; RBSIM_ANCHORS_DIR in bench/CMakeLists.txt says where), so
// that it runs the very same scenes, timing loop and statistics as Bullet,
// ODE and MuJoCo, in the same session:
//   taskset -c 1 build/bench/bench_anchors_ours --scene free --n 1000 --reps 3
// --threads N (ours alone; taken out before the harness reads the options)
// sets world.threads: 1 (the default here, one core as the peers) steps on
// the caller alone, 0 on every core the process may run on (pin it to
// both: taskset -c 0,1). --solver soft_step|sequential_impulses (ours
// alone, too) picks the contact solver; without it, the world's default
// (soft_step).
// One timed step = World::step(): collision detection, contact response, integration.
#include "scene.hpp"

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "rbsim/physics/world.h"

namespace {

rbsim::Vec3 vec(const double v[3]) { return {v[0], v[1], v[2]}; }

int g_threads = 1;  // --threads
std::optional<rbsim::ContactSolverKind> g_solver;  // --solver; unset: the world's default

struct RbsimEngine : anchors::Engine {
  std::optional<rbsim::World> world;
  bool sleeping = true;

  void build(const anchors::Scene& scene, const anchors::Options& options) override {
    rbsim::WorldSettings settings;
    settings.contact.sleeping = options.sleep != 0;
    if (options.iters > 0) settings.contact.solver.velocityIterations = options.iters;
    sleeping = settings.contact.sleeping;
    settings.dt = scene.dt;
    settings.gravity = rbsim::Vec3(0, 0, scene.gravity);
    settings.integrator = rbsim::IntegratorKind::SemiImplicitEuler;
    settings.threads = g_threads;
    if (g_solver) settings.contact.solver.kind = *g_solver;
    world.emplace(settings);
    int index = 0;
    for (const anchors::BodyDef& b : scene.bodies) {
      rbsim::BodyDef def;
      def.name = "b" + std::to_string(index++);
      if (b.shape == anchors::Shape::Box) {
        def.shape = rbsim::BoxShape{rbsim::Vec3::Constant(b.size)};
      } else {
        def.shape = rbsim::SphereShape{b.size};
      }
      def.mass = b.mass;
      def.position = vec(b.p);
      def.orientation = rbsim::Quaternion{b.q[0], b.q[1], b.q[2], b.q[3]};
      def.linearVelocity = vec(b.v);
      def.angularVelocity = vec(b.w);
      if (!world->createBody(def).ok()) std::abort();
    }
    if (scene.ground) {
      rbsim::BodyDef ground;
      ground.name = "ground";
      ground.shape = rbsim::PlaneShape{};
      ground.isStatic = true;
      if (!world->createBody(ground).ok()) std::abort();
    }
    int wall = 0;
    for (const anchors::StaticBox& box : scene.statics) {
      rbsim::BodyDef def;
      def.name = "wall" + std::to_string(wall++);
      def.shape = rbsim::BoxShape{vec(box.he)};
      def.position = vec(box.p);
      def.isStatic = true;
      if (!world->createBody(def).ok()) std::abort();
    }
  }

  void step() override { world->step(); }

  void state(int i, double p[3], double v[3], double w[3]) const override {
    const rbsim::BodyView body = world->bodyAt(i);
    for (int k = 0; k < 3; ++k) {
      p[k] = body.position()[k];
      v[k] = body.linearVelocity()[k];
      w[k] = body.angularVelocity()[k];
    }
  }

  long contacts() const override { return world->contactPointCount(); }
  std::string notes() const override {
    return sleeping ? "sleeping bodies at end: " + std::to_string(world->sleepingBodyCount()) : "";
  }
  std::string settings() const override {
    const rbsim::ContactSolverSettings& solver = world->settings().contact.solver;
    if (solver.kind == rbsim::ContactSolverKind::SoftStep)
      return std::string("rbsim World::step: semi-implicit Euler, double; soft step, ") +
             std::to_string(solver.substeps) + " sub-steps, contact " +
             std::to_string(static_cast<int>(solver.contactHertz)) + " Hz, patch friction 0.5; sleeping " +
             (sleeping ? "on" : "off") + "; threads " + std::to_string(rbsim::resolveThreadCount(g_threads));
    return std::string("rbsim World::step: semi-implicit Euler, double; sequential impulses, ") +
           std::to_string(world->settings().contact.solver.velocityIterations) +
           " iterations, patch friction 0.5, split impulses, shock propagation; sleeping " +
           (sleeping ? "on" : "off") + "; threads " + std::to_string(rbsim::resolveThreadCount(g_threads));
  }
};

}  // namespace

int main(int argc, char** argv) {
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::string(argv[i]) == "--threads" && i + 1 < argc) {
      g_threads = std::atoi(argv[++i]);
      continue;
    }
    if (std::string(argv[i]) == "--solver" && i + 1 < argc) {
      const std::string name = argv[++i];
      if (name != "soft_step" && name != "sequential_impulses") {
        std::fprintf(stderr, "rbsim: unknown --solver %s\n", name.c_str());
        return 2;
      }
      g_solver = name == "soft_step" ? rbsim::ContactSolverKind::SoftStep
                                     : rbsim::ContactSolverKind::SequentialImpulses;
      continue;
    }
    args.push_back(argv[i]);
  }
  return anchors::run_main(static_cast<int>(args.size()), args.data(), "rbsim", "0.1.0",
                           [] { return std::make_unique<RbsimEngine>(); });
}
