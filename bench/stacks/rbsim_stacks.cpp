// rbsim on the stacking scenes of stack_scenes.h, beside Bullet and ODE:
//   taskset -c 1 build/bench/stacks/bench_stacks_rbsim --scene pyramid --n 90 --reps 3
// One timed step = World::step(): collision detection, contact response
// (sequential impulses with the solver's defaults unless --iters), and
// integration (semi-implicit Euler, as bench/anchors/ours.cpp). Friction 0.5
// and restitution 0 as the world's default material, so every pair, the
// ground's included, has the scene's coefficients.
#include <cstdio>
#include <optional>

#include "rbsim/physics/world.h"
#include "stack_scenes.h"

namespace {

namespace sb = rbsim::bench::stacks;

rbsim::Vec3 vec(const sb::Vec3& v) { return {v[0], v[1], v[2]}; }

class RbsimEngine final : public sb::Engine {
 public:
  void build(const sb::Scene& s, const sb::EngineSettings& engineSettings) override {
    rbsim::WorldSettings settings;
    settings.dt = s.dt;
    settings.gravity = rbsim::Vec3(0, 0, s.gravity);
    settings.integrator = rbsim::IntegratorKind::SemiImplicitEuler;
    settings.contact.sleeping = engineSettings.sleep;
    if (engineSettings.iterations > 0) settings.contact.solver.velocityIterations = engineSettings.iterations;
    settings.threads = engineSettings.threads;
    if (engineSettings.solver == "soft_step") {
      settings.contact.solver.kind = rbsim::ContactSolverKind::SoftStep;
    } else if (engineSettings.solver == "sequential_impulses") {
      settings.contact.solver.kind = rbsim::ContactSolverKind::SequentialImpulses;
    } else if (!engineSettings.solver.empty() && engineSettings.solver != "sequential_impulses") {
      std::fprintf(stderr, "rbsim: unknown --solver %s\n", engineSettings.solver.c_str());
      std::exit(2);
    }
    if (engineSettings.substeps > 0) settings.contact.solver.substeps = engineSettings.substeps;
    if (engineSettings.contactHertz > 0) settings.contact.solver.contactHertz = engineSettings.contactHertz;
    settings.contact.defaultMaterial.friction = sb::kFriction;
    settings.contact.defaultMaterial.staticFriction = sb::kFriction;
    settings.contact.defaultMaterial.restitution = sb::kRestitution;
    m_world.emplace(settings);
    m_bodies.clear();
    m_bodies.reserve(s.bodies.size());
    for (const sb::BodySpec& b : s.bodies) {
      rbsim::BodyDef def;
      def.name = "box" + std::to_string(m_bodies.size());
      def.shape = rbsim::BoxShape{rbsim::Vec3::Constant(b.half)};
      def.mass = b.mass;  // the inertia follows from the shape: the scene's m (2 side²) / 12
      def.position = vec(b.position);
      def.orientation = {b.orientation[0], b.orientation[1], b.orientation[2], b.orientation[3]};
      m_bodies.push_back(created(m_world->createBody(def)));
    }
    rbsim::BodyDef ground;
    ground.name = "ground";
    ground.shape = rbsim::PlaneShape{};  // z = 0, normal +z
    ground.isStatic = true;
    created(m_world->createBody(ground));
  }

  void step() override { m_world->step(); }

  sb::BodyState state(int body) const override {
    const rbsim::BodyView b = m_world->body(m_bodies[static_cast<size_t>(body)]);
    sb::BodyState result;
    for (int k = 0; k < 3; ++k) {
      result.position[static_cast<size_t>(k)] = b.position()[k];
      result.velocity[static_cast<size_t>(k)] = b.linearVelocity()[k];
      result.angularVelocity[static_cast<size_t>(k)] = b.angularVelocity()[k];
    }
    return result;
  }

  long contacts() const override { return m_world->contactPointCount(); }

  std::string settings() const override {
    const rbsim::ContactSolverSettings& solver = m_world->settings().contact.solver;
    char text[512];
    if (solver.kind == rbsim::ContactSolverKind::SoftStep) {
      std::snprintf(text, sizeof text,
                    "rbsim World::step: semi-implicit Euler, double; soft step, %d sub-steps, contact %.0f Hz, "
                    "damping ratio %.1f, slop %.4f m, warm starting %s; friction 0.5, restitution 0; sleeping %s; "
                    "threads %d",
                    solver.substeps, solver.contactHertz, solver.contactDampingRatio, solver.linearSlop,
                    solver.warmStarting ? "on" : "off", m_world->settings().contact.sleeping ? "on" : "off",
                    rbsim::resolveThreadCount(m_world->settings().threads));
      return text;
    }
    std::snprintf(text, sizeof text,
                  "rbsim World::step: semi-implicit Euler, double; sequential impulses, %d velocity iterations, "
                  "%d split-impulse iterations, slop %.4f m, baumgarte %.2f, warm starting %s, shock propagation "
                  "%s; friction 0.5, restitution 0; sleeping %s; threads %d",
                  solver.velocityIterations, solver.positionIterations, solver.linearSlop, solver.baumgarte,
                  solver.warmStarting ? "on" : "off", solver.shockPropagation ? "on" : "off",
                  m_world->settings().contact.sleeping ? "on" : "off",
                  rbsim::resolveThreadCount(m_world->settings().threads));
    return text;
  }

  std::string notes() const override {
    if (!m_world->settings().contact.sleeping) return "";
    return "sleeping bodies at end: " + std::to_string(m_world->sleepingBodyCount());
  }

 private:
  static rbsim::BodyId created(const rbsim::Expected<rbsim::BodyId>& id) {
    if (!id.ok()) {
      std::fprintf(stderr, "rbsim: %s\n", id.error().message.c_str());
      std::exit(1);
    }
    return id.value();
  }

  std::optional<rbsim::World> m_world;
  std::vector<rbsim::BodyId> m_bodies;
};

}  // namespace

int main(int argc, char** argv) {
  return sb::runMain(argc, argv, "rbsim", true, "this tree",
                     [] { return std::unique_ptr<sb::Engine>(new RbsimEngine()); });
}
