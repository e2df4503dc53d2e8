// A torque-free rigid body with distinct principal moments: conservation of
// world-frame angular momentum and energy, and the intermediate-axis theorem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "rbsim/physics/world.h"
#include "support/torque_free_world.h"

namespace rbsim {
namespace {

constexpr double kDt = 1e-3;

// Box with half extents (0.1, 0.2, 0.3) m: principal moments ∝ (b²+c², a²+c², a²+b²)
// = (0.13, 0.10, 0.05): x is the major axis, y the intermediate, z the minor.
World makeTumbler(IntegratorKind kind, const Vec3& angularVelocity) {
  BodyDef def;
  def.name = "tumbler";
  def.shape = BoxShape{Vec3(0.1, 0.2, 0.3)};
  def.mass = 6.0;
  def.angularVelocity = angularVelocity;
  return testing::torqueFreeWorld(def, kind, kDt);
}

// World-frame direction of the body axis whose principal moment is the
// k-th smallest.
Vec3 principalAxisInWorld(BodyView body, int rank) {
  std::array<int, 3> order{0, 1, 2};
  const Vec3& moments = body.dynamics().inertiaBody;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return moments[a] < moments[b]; });
  return body.rotation().col(order[static_cast<size_t>(rank)]);
}

class TorqueFree : public ::testing::TestWithParam<IntegratorKind> {};

TEST_P(TorqueFree, WorldAngularMomentumIsConserved) {
  World world = makeTumbler(GetParam(), Vec3(3.0, -2.0, 5.0));
  const Vec3 initial = world.bodies()[0].angularMomentum();
  ASSERT_GT(initial.norm(), 0.1);
  for (int i = 0; i < 10000; ++i) world.step();
  EXPECT_LT((world.bodies()[0].angularMomentum() - initial).norm(), 1e-12 * initial.norm());
}

TEST_P(TorqueFree, SpinAboutTheIntermediateAxisFlipsAndTheOthersDoNot) {
  const double spin = 5.0;   // rad/s
  const double wobble = 1e-3;  // rad/s about the other axes
  // Body axes coincide with world axes at t = 0 (the box's inertia is diagonal).
  for (int rank = 0; rank < 3; ++rank) {
    Vec3 omega = Vec3::Constant(wobble);
    World probe = makeTumbler(GetParam(), Vec3::Zero());
    const Vec3 axis = principalAxisInWorld(probe.bodies()[0], rank);
    omega += spin * axis;
    World world = makeTumbler(GetParam(), omega);
    double minAlignment = 1.0;
    for (int i = 0; i < 10000; ++i) {
      world.step();
      minAlignment = std::min(minAlignment, principalAxisInWorld(world.bodies()[0], rank).dot(axis));
    }
    if (rank == 1) {
      EXPECT_LT(minAlignment, -0.9) << "the intermediate axis must turn over";
    } else {
      EXPECT_GT(minAlignment, 0.99) << "spin about axis of rank " << rank << " must stay stable";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, TorqueFree,
                         ::testing::Values(IntegratorKind::ExplicitEuler,
                                           IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4),
                         [](const auto& testParam) { return std::string(integratorName(testParam.param)); });

TEST(TorqueFreeRk4, EnergyDriftOverTenSecondsIsBelowOnePartPerMillion) {
  World world = makeTumbler(IntegratorKind::Rk4, Vec3(3.0, -2.0, 5.0));
  const double initial = world.totalKineticEnergy();
  double worst = 0.0;
  for (int i = 0; i < 10000; ++i) {
    world.step();
    worst = std::max(worst, std::abs(world.totalKineticEnergy() - initial) / initial);
  }
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace rbsim
