// The soft-step solver's own laws (solver/soft_step_solver.h); the contact
// tests that hold for every solver run with it too (this executable compiles
// them with RBSIM_TEST_SOFT_STEP).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "physics/solver/soft_step_solver.h"
#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBox;
using testing::addGround;
using testing::addSphere;
using testing::contactSettings;

// One sub-step of a soft contact is one implicit-Euler step of the damped
// spring x'' = −ω² x − 2ζω x' it stands for (Catto, "Solver2D"):
// v' = (v − h ω² x) / (1 + 2ζωh + h²ω²). The solver's impulse per unit
// mass is −massScale (v + biasRate x) − impulseScale λ, with λ = 0 for a
// contact that carried nothing before.
TEST(SoftStep, ASubStepOfASoftContactIsImplicitEulerOfItsDampedSpring) {
  for (const double hertz : {30.0, 500.0, 2000.0}) {
    for (const double zeta : {0.0, 1.0, 10.0}) {
      for (const double h : {2.5e-4, 1e-3, 1.0 / 240.0}) {
        const Softness soft = softness(hertz, zeta, h);
        const double omega = 2.0 * std::numbers::pi * hertz;
        for (const double x : {-1e-3, -2e-6}) {
          for (const double v : {-0.3, 0.0, 0.2}) {
            const double implicitEuler =
                (v - h * omega * omega * x) / (1.0 + 2.0 * zeta * omega * h + h * h * omega * omega);
            const double solved = v - soft.massScale * (v + soft.biasRate * x);
            EXPECT_NEAR(solved, implicitEuler, 1e-12 * (std::abs(v) + h * omega * omega * std::abs(x)))
                << hertz << " Hz, ζ " << zeta << ", h " << h;
          }
        }
      }
    }
  }
  const Softness rigid = softness(0.0, 10.0, 1e-3);
  EXPECT_EQ(rigid.biasRate, 0.0);
  EXPECT_EQ(rigid.massScale, 1.0);
  EXPECT_EQ(rigid.impulseScale, 0.0);
}

// A resting sphere is a mass on the contact's spring: it comes to rest sunk
// by g/ω², ω = 2π f, f twice the contact stiffness against the static
// ground, and the stiffness is capped at an eighth of the sub-step rate.
// Its contact carries exactly its weight: m g dt per step.
TEST(SoftStep, ARestingSphereSinksByGOverOmegaSquaredAndCarriesItsWeight) {
  struct Case {
    double dt;
    int substeps;
    double hertz;  // the stiffness the solver must use: min(500, rate / 8)
  };
  for (const Case c : {Case{1e-3, 8, 500.0}, Case{5e-4, 8, 500.0}, Case{4e-3, 4, 125.0}}) {
    WorldSettings settings = contactSettings(0.0, 0.5);
    settings.contact.solver.kind = ContactSolverKind::SoftStep;
    settings.contact.solver.substeps = c.substeps;
    settings.contact.sleeping = false;
    settings.dt = c.dt;
    World world(settings);
    addGround(world);
    const double radius = 0.1;
    const BodyId ball = addSphere(world, "ball", radius, Vec3(0, 0, radius));
    for (int i = 0; i < static_cast<int>(std::lround(2.0 / c.dt)); ++i) world.step();
    const double omega = 2.0 * std::numbers::pi * 2.0 * c.hertz;
    const double g = -settings.gravity.z();
    EXPECT_NEAR(world.body(ball).position().z(), radius - g / (omega * omega), 1e-6 * g / (omega * omega))
        << "dt " << c.dt;
    EXPECT_NEAR(world.body(ball).linearVelocity().norm(), 0.0, 1e-12);
    ASSERT_EQ(world.contacts().size(), 1u);
    const double mass = world.body(ball).mass();
    EXPECT_NEAR(world.contacts()[0].points[0].normalImpulse, mass * g * c.dt, 1e-9 * mass * g * c.dt);
  }
}

// Heavy on light: ten cubes whose masses alternate 1 kg and 100 kg, the
// heavy ones on the light ones, stand 10 s: the top drifts sideways by less
// than 1 mm, and the stack comes to rest. It rests on springs: each soft
// contact gives way like a spring of its frequency ω on its effective mass,
// and at rest a point carrying λ per sub-step h is sunk by λ / (h ω² m_n).
// A face of two aligned cubes carries its load W at four corners, where
// 1/m_n = 4 (1/mA + 1/mB) (the corners' arms add three times the linear
// term), so each face gives way by W (1/mA + 1/mB) / ω², and the top sinks
// by the sum over the faces, ω doubled against the ground (the closed
// form: 2.7 mm here, nearly all of it the light cubes').
TEST(SoftStep, AStackWithAMassRatioOfAHundredStandsTenSecondsOnItsContactsSprings) {
  WorldSettings settings = contactSettings(0.0, 0.5);
  settings.contact.sleeping = false;
  World world(settings);
  addGround(world);
  std::vector<double> masses;
  std::vector<BodyId> ids;
  for (int k = 0; k < 10; ++k) {
    BodyDef def;
    def.name = "box" + std::to_string(k);
    def.shape = BoxShape{Vec3::Constant(0.1)};
    def.mass = k % 2 == 0 ? 1.0 : 100.0;
    def.position = Vec3(0, 0, 0.1 + 0.2 * k);
    masses.push_back(k % 2 == 0 ? 1.0 : 100.0);
    ids.push_back(*world.createBody(def));
  }
  const Vec3 start = world.body(ids.back()).position();
  double drift = 0.0;
  for (int i = 0; i < 10000; ++i) {
    world.step();
    const Vec3 d = world.body(ids.back()).position() - start;
    drift = std::max(drift, std::hypot(d.x(), d.y()));
  }
  EXPECT_LT(drift, 1e-3);
  // At rest: no cube moves visibly (1 mm/s, as the pyramid's test asks).
  for (const BodyId id : ids) EXPECT_LT(world.body(id).linearVelocity().norm(), 1e-3) << "at rest";

  const double g = -settings.gravity.z();
  const double omega = 2.0 * std::numbers::pi * settings.contact.solver.contactHertz;
  double sink = 0.0;
  for (std::size_t k = 0; k < masses.size(); ++k) {
    double load = 0.0;  // N: the weight on the face under cube k
    for (std::size_t j = k; j < masses.size(); ++j) load += masses[j] * g;
    const bool onGround = k == 0;
    const double compliance = (1.0 / masses[k] + (onGround ? 0.0 : 1.0 / masses[k - 1])) /
                              std::pow(onGround ? 2.0 * omega : omega, 2);
    sink += load * compliance;
  }
  const double sunk = start.z() - world.body(ids.back()).position().z();
  EXPECT_NEAR(sunk, sink, 1e-4 * sink);
}

}  // namespace
}  // namespace rbsim
