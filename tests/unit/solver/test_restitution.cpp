// Colliding contact: the impulse with restitution of Baraff, "Rigid Body
// Simulation" (SIGGRAPH course notes), against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBox;
using testing::addGround;
using testing::addSphere;
using testing::contactSettings;

constexpr double kG = 9.81;

struct Apex {
  double time;    // s
  double height;  // m, of the sphere's bottom above the ground
};

// Drops a sphere from `height` and records the apexes of its bounces.
std::vector<Apex> bounceApexes(WorldSettings settings, double height, int count) {
  World world(settings);
  addGround(world);
  const double radius = 0.1;
  const BodyId ball = addSphere(world, "ball", radius, Vec3(0, 0, radius + height));
  std::vector<Apex> apexes;
  double previous = 0.0;
  for (int i = 0; i < 20000 && static_cast<int>(apexes.size()) < count; ++i) {
    world.step();
    const double v = world.body(ball).linearVelocity().z();
    if (previous > 0.0 && v <= 0.0)
      apexes.push_back({world.time(), world.body(ball).position().z() - radius});
    previous = v;
  }
  return apexes;
}

TEST(Restitution, ApexHeightsFallByESquaredAndBounceTimesByE) {
  for (double e : {0.8, 0.5}) {
    const double h0 = 1.0;
    const auto apexes = bounceApexes(contactSettings(e, 0.5), h0, 4);
    ASSERT_EQ(apexes.size(), 4u) << "e = " << e;
    // Tolerance: the bounce happens when the gap closes within the step, up
    // to v·dt (≤ 4.5 mm at 1 m) above the ground, and the apex is sampled
    // once per step: about 0.5% of the height at these heights.
    std::vector<double> heights{h0};
    for (const Apex& a : apexes) heights.push_back(a.height);
    for (std::size_t k = 1; k < heights.size(); ++k) {
      if (heights[k] < 0.05) break;  // below that, v·dt is no longer small against the height
      EXPECT_NEAR(heights[k] / heights[k - 1], e * e, 0.01) << "e = " << e << " bounce " << k;
    }
    // Time between bounces: 2 v_k / g with v_k = e^k v_0, so consecutive
    // apex-to-apex intervals shrink by e.
    for (std::size_t k = 1; k + 1 < apexes.size(); ++k) {
      const double first = apexes[k].time - apexes[k - 1].time;
      const double second = apexes[k + 1].time - apexes[k].time;
      if (heights[k + 1] < 0.05) break;
      EXPECT_NEAR(second / first, e, 0.02) << "e = " << e;
    }
    // First flight: free fall from h0 then a bounce to e² h0; apex time is
    // sqrt(2 h0 / g) + e sqrt(2 h0 / g).
    EXPECT_NEAR(apexes[0].time, (1.0 + e) * std::sqrt(2.0 * h0 / kG), 0.01);
  }
}

TEST(Restitution, ZeroRestitutionStaysDown) {
  World world(contactSettings(0.0, 0.5));
  addGround(world);
  const BodyId ball = addSphere(world, "ball", 0.1, Vec3(0, 0, 1.1));
  double highestAfterImpact = 0.0;
  bool landed = false;
  for (int i = 0; i < 3000; ++i) {
    world.step();
    const double bottom = world.body(ball).position().z() - 0.1;
    if (bottom < 0.001) landed = true;
    if (landed) highestAfterImpact = std::max(highestAfterImpact, bottom);
  }
  EXPECT_TRUE(landed);
  EXPECT_LT(highestAfterImpact, 0.001);
  EXPECT_LT(world.body(ball).linearVelocity().norm(), 1e-3);
}

// Two free spheres in zero gravity, frictionless.
struct TwoSpheres {
  Vec3 v1, v2;
};
TwoSpheres collide(double e, double m1, double m2, const Vec3& u1, const Vec3& u2,
                   const Vec3& offset) {
  WorldSettings settings = contactSettings(e, 0.0);
  settings.gravity = Vec3::Zero();
  settings.contact.sleeping = false;
  World world(settings);
  BodyDef a;
  a.name = "a";
  a.shape = SphereShape{0.1};
  a.mass = m1;
  a.position = Vec3::Zero();
  a.linearVelocity = u1;
  BodyDef b = a;
  b.name = "b";
  b.mass = m2;
  b.position = offset;
  b.linearVelocity = u2;
  const BodyId ia = *world.createBody(a), ib = *world.createBody(b);
  for (int i = 0; i < 400; ++i) world.step();
  return {world.body(ia).linearVelocity(), world.body(ib).linearVelocity()};
}

TEST(Restitution, HeadOnSpheresMatchTheClosedForm) {
  // Along the line of centres: v1' = ((m1 − e m2) u1 + (1 + e) m2 u2) / (m1 + m2), and symmetrically.
  for (const auto& [e, m1, m2] : {std::tuple{1.0, 1.0, 1.0}, std::tuple{0.5, 1.0, 3.0},
                                  std::tuple{0.0, 2.0, 1.0}, std::tuple{0.9, 5.0, 0.5}}) {
    const double u1 = 1.5, u2 = -0.5;
    const TwoSpheres r = collide(e, m1, m2, Vec3(u1, 0, 0), Vec3(u2, 0, 0), Vec3(0.3, 0, 0));
    const double v1 = ((m1 - e * m2) * u1 + (1 + e) * m2 * u2) / (m1 + m2);
    const double v2 = ((m2 - e * m1) * u2 + (1 + e) * m1 * u1) / (m1 + m2);
    EXPECT_NEAR(r.v1.x(), v1, 1e-9) << "e " << e << " m1 " << m1 << " m2 " << m2;
    EXPECT_NEAR(r.v2.x(), v2, 1e-9);
    EXPECT_NEAR(r.v1.y(), 0.0, 1e-12);
    // Momentum is conserved exactly.
    EXPECT_NEAR(m1 * r.v1.x() + m2 * r.v2.x(), m1 * u1 + m2 * u2, 1e-12);
  }
}

// A row of touching balls hit end-on (a cradle without strings, no
// gravity): the impact passes from ball to ball, each collision between
// equal masses passing on (1 + e)/2 of the speed, so the far ball leaves
// with ((1 + e)/2)⁴ of the striker's. The four left behind move at
// (1 − e)/2 of what reached them, slower than the restitution threshold
// apart: they meet without bouncing and go on together, with the rest of
// the momentum. A simultaneous solve of the row would send all four off
// together at 2/5 of the striker's speed (e = 1).
TEST(Restitution, ARowOfTouchingBallsPassesAnImpactAlong) {
  for (const double e : {1.0, 0.9}) {
    for (const double dt : {1e-3, 5e-4}) {
      SCOPED_TRACE("e " + std::to_string(e) + ", dt " + std::to_string(dt));
      WorldSettings settings = contactSettings(e, 0.0);
      settings.dt = dt;
      settings.gravity = Vec3::Zero();
      World world(settings);
      const double radius = 0.05, speed = 2.0;
      std::vector<BodyId> balls;
      balls.push_back(addSphere(world, "striker", radius, Vec3(-0.05, 0, 0), Vec3(speed, 0, 0)));
      for (int i = 1; i < 5; ++i)
        balls.push_back(addSphere(world, "ball" + std::to_string(i), radius, Vec3(0.1 * i, 0, 0)));
      for (int s = 0; s < static_cast<int>(0.05 / dt); ++s) world.step();
      const double far = speed * std::pow(0.5 * (1.0 + e), 4);
      EXPECT_NEAR(world.body(balls[4]).linearVelocity().x(), far, 1e-12 * speed);
      // Momentum to rounding; the four behind share theirs to what ten
      // sweeps over a row of plastic contacts settle (1e-5 of the speed).
      double momentum = 0.0;
      for (const BodyId b : balls) momentum += world.body(b).linearVelocity().x();
      EXPECT_NEAR(momentum, speed, 1e-12 * speed);
      for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(world.body(balls[static_cast<std::size_t>(i)]).linearVelocity().x(), 0.25 * (speed - far),
                    e == 1.0 ? 1e-12 * speed : 1e-5 * speed)
            << "ball " << i;
    }
  }
}

// Oblique impacts and a box landing on a corner, against closed forms for
// every integrator: test_impacts.cpp.

}  // namespace
}  // namespace rbsim
