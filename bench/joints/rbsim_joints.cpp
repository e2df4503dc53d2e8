// rbsim on the joint scenes of joint_scenes.h, beside Bullet and ODE:
//   build/bench/joints/bench_joints_rbsim --scene chain --reps 3
// The world is built as rbsim_scene_world.h says (joints at the position
// level, no sleeping). Twist ranges of ball joints are not supported yet
// (the ragdoll's shoulders, hips, waist and neck twist freely; the notes
// say so).
#include <cstdio>
#include <optional>

#include "joint_scenes.h"
#include "rbsim_scene_world.h"
#include "physics/joint/row_system.h"
#include "rbsim/physics/world.h"
#include "support/allocation_counter.h"

namespace {

namespace jb = rbsim::bench::joints;

class RbsimEngine final : public jb::Engine {
 public:
  void configure(const jb::Scene& s) override {
    m_world.emplace(jb::sceneWorldSettings(s));
    m_start = rbsim::RowSystem::counts();
    m_steps = 0;
    m_sceneSteps = s.steps;
    m_allocations = m_steadyAllocations = {};
    m_steadySteps = 0;
    if (s.ground) m_world->createBody(jb::sceneGround()).value();
  }

  void addBody(const jb::BodySpec& b) override {
    const rbsim::Expected<rbsim::BodyId> id = m_world->createBody(jb::sceneBody(b, m_bodies.size()));
    if (!id.ok()) {
      std::fprintf(stderr, "rbsim: %s\n", id.error().message.c_str());
      std::exit(1);
    }
    m_bodies.push_back(id.value());
  }

  void addJoint(const jb::JointSpec& j) override {
    if (j.kind == jb::JointKind::kBall && j.limited && j.twist > 0) ++m_untwistedBalls;
    const rbsim::Expected<rbsim::JointId> id = m_world->createJoint(jb::sceneJoint(j, m_bodies, m_joints++));
    if (!id.ok()) {
      std::fprintf(stderr, "rbsim: %s\n", id.error().message.c_str());
      std::exit(1);
    }
  }

  // Each step's heap allocations are counted (allocation_counter.h: a
  // thread-local add per allocation, none when there are none), those of
  // the second half of the run apart: the steady state.
  void step(double) override {
    const rbsim::testing::AllocationScope scope;
    m_world->step();
    const rbsim::testing::AllocationCounts c = scope.counts();
    m_allocations.total += c.total;
    m_allocations.joints += c.joints;
    m_allocations.jointNewton += c.jointNewton;
    if (2 * m_steps >= m_sceneSteps) {
      m_steadyAllocations.total += c.total;
      m_steadyAllocations.joints += c.joints;
      m_steadyAllocations.jointNewton += c.jointNewton;
      ++m_steadySteps;
    }
    ++m_steps;
  }

  jb::Pose pose(int body) const override {
    const rbsim::BodyView b = m_world->body(m_bodies[static_cast<size_t>(body)]);
    jb::Pose result;
    result.position = {b.position().x(), b.position().y(), b.position().z()};
    result.orientation = {b.orientation().w, b.orientation().x, b.orientation().y, b.orientation().z};
    return result;
  }

  std::string settings() const override {
    char text[256];
    std::snprintf(text, sizeof text,
                  "joints at the position level (exact block-sparse solve, tolerance 1e-12); contact velocity "
                  "iterations=%d; friction 0.5, restitution 0; no sleeping",
                  m_world->settings().contact.solver.velocityIterations);
    return text;
  }

  // The joint systems' work per step (row_system.h): numeric
  // factorisations, factors found already made, solves; and the heap
  // allocations per step, in all and in joint code, over the run and over
  // its second half.
  std::string repStats() const override {
    const rbsim::RowSystemCounts now = rbsim::RowSystem::counts();
    const double steps = m_steps > 0 ? static_cast<double>(m_steps) : 1.0;
    const double steady = m_steadySteps > 0 ? static_cast<double>(m_steadySteps) : 1.0;
    char text[400];
    std::snprintf(text, sizeof text,
                  "factorisations_per_step=%.3f kept_per_step=%.3f solves_per_step=%.2f allocs_per_step=%.1f "
                  "joint_allocs_per_step=%.1f newton_allocs_per_step=%.1f steady_allocs_per_step=%.2f "
                  "steady_joint_allocs_per_step=%.2f steady_newton_allocs_per_step=%.2f",
                  static_cast<double>(now.factorisations - m_start.factorisations) / steps,
                  static_cast<double>(now.kept - m_start.kept) / steps,
                  static_cast<double>(now.solves - m_start.solves) / steps,
                  static_cast<double>(m_allocations.total) / steps, static_cast<double>(m_allocations.joints) / steps,
                  static_cast<double>(m_allocations.jointNewton) / steps,
                  static_cast<double>(m_steadyAllocations.total) / steady,
                  static_cast<double>(m_steadyAllocations.joints) / steady,
                  static_cast<double>(m_steadyAllocations.jointNewton) / steady);
    return text;
  }

  std::string notes() const override {
    if (m_untwistedBalls == 0) return "";
    return std::to_string(m_untwistedBalls) + " ball joints with a cone but without their twist range "
           "(rbsim has no twist limit yet)";
  }

 private:
  std::optional<rbsim::World> m_world;
  std::vector<rbsim::BodyId> m_bodies;
  int m_joints = 0;
  int m_untwistedBalls = 0;
  rbsim::RowSystemCounts m_start;
  long m_steps = 0;
  long m_sceneSteps = 0;
  rbsim::testing::AllocationCounts m_allocations, m_steadyAllocations;
  long m_steadySteps = 0;
};

}  // namespace

int main(int argc, char** argv) {
  return jb::runMain(argc, argv, "rbsim", "this tree", [] { return std::unique_ptr<jb::Engine>(new RbsimEngine()); });
}
