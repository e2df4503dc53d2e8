// Colliding contacts answered at the time of impact (world/impacts.h),
// against closed forms, for every integrator, two step sizes, and both ways
// of finding the time of impact (regula falsi by default, bisection
// in the backtracking mode).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "physics/body/integrator.h"
#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

using testing::addGround;
using testing::contactSettings;

struct Case {
  IntegratorKind integrator;
  double dt;  // s
  bool backtracking;
};

std::string nameOf(const ::testing::TestParamInfo<Case>& info) {
  const Case& c = info.param;
  return std::string(integratorName(c.integrator)) + "_dt" +
         std::to_string(static_cast<int>(std::lround(c.dt * 1e6))) + "us" +
         (c.backtracking ? "_bisection" : "");
}

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (bool backtracking : {false, true})
    for (IntegratorKind kind :
         {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4})
      for (double dt : {1e-3, 2.5e-4}) cases.push_back({kind, dt, backtracking});
  return cases;
}

class Impacts : public ::testing::TestWithParam<Case> {
 protected:
  WorldSettings settings(double restitution, double friction) const {
    WorldSettings s = contactSettings(restitution, friction);
    s.dt = GetParam().dt;
    s.integrator = GetParam().integrator;
    s.contact.backtracking = GetParam().backtracking;
    return s;
  }
};

// Two frictionless spheres in zero gravity, set up to touch at a chosen time
// with a chosen normal: before it they fly straight, so the closed form is
// the impulse along the line of centres at that moment,
//   J = −(1 + e) v_n / (1/m1 + 1/m2) n,  v1' = u1 − J/m1,  v2' = u2 + J/m2,
// and after it they fly straight again from where they touched.
TEST_P(Impacts, ObliqueSphereImpactsMatchTheClosedForm) {
  const double e = 0.7;
  const double dt = GetParam().dt;
  struct Pair {
    double m1, m2, r1, r2;
  };
  for (const Pair& pair :
       {Pair{1.0, 1.0, 0.1, 0.1}, Pair{2.0, 0.5, 0.05, 0.2}, Pair{0.3, 9.0, 0.15, 0.04}}) {
    for (double speed : {0.3, 3.0, 30.0}) {
      for (double obliquity : {0.0, 0.6, 1.1}) {  // rad between −u_rel and the normal
        WorldSettings s = settings(e, 0.0);
        s.gravity = Vec3::Zero();
        s.contact.sleeping = false;
        s.contact.solver.restitutionThreshold = 0.01;  // so that the slow cases bounce too
        World world(s);
        const Vec3 u1 = speed * Vec3(0.8, 0.3, -0.2);
        const Vec3 u2 = speed * Vec3(-0.5, 0.1, 0.25);
        const Vec3 relative = u2 - u1;
        // The normal at contact: −u_rel turned by `obliquity` about an axis across it.
        const Vec3 across = relative.cross(Vec3::UnitZ()).normalized();
        const Vec3 normal =
            Quaternion::fromAxisAngle(across, obliquity).rotate(-relative.normalized());
        const double radii = pair.r1 + pair.r2;
        const double contactTime = 7.37 * dt;  // s: between two steps
        const Vec3 x1 = Vec3(0.3, -0.2, 1.0);
        const Vec3 x2 = x1 + radii * normal - relative * contactTime;
        BodyDef a;
        a.name = "a";
        a.shape = SphereShape{pair.r1};
        a.mass = pair.m1;
        a.position = x1;
        a.linearVelocity = u1;
        BodyDef b = a;
        b.name = "b";
        b.shape = SphereShape{pair.r2};
        b.mass = pair.m2;
        b.position = x2;
        b.linearVelocity = u2;
        const BodyId ia = *world.createBody(a), ib = *world.createBody(b);
        const int steps = 30;
        for (int i = 0; i < steps; ++i) world.step();

        const double vn = relative.dot(normal);
        ASSERT_LT(vn, 0.0);
        const Vec3 impulse = -(1.0 + e) * vn / (1.0 / pair.m1 + 1.0 / pair.m2) * normal;  // on b
        const Vec3 v1 = u1 - impulse / pair.m1, v2 = u2 + impulse / pair.m2;
        const double t = steps * dt;
        const Vec3 end1 = x1 + u1 * contactTime + v1 * (t - contactTime);
        const Vec3 end2 = x2 + u2 * contactTime + v2 * (t - contactTime);
        const std::string where = "m " + std::to_string(pair.m1) + "/" + std::to_string(pair.m2) +
                                  " r " + std::to_string(pair.r1) + "/" + std::to_string(pair.r2) +
                                  " speed " + std::to_string(speed) + " obliquity " +
                                  std::to_string(obliquity);
        EXPECT_LT((world.body(ia).linearVelocity() - v1).norm(), 1e-6) << where;
        EXPECT_LT((world.body(ib).linearVelocity() - v2).norm(), 1e-6) << where;
        // At the right moment and place: the time of impact is found to a gap
        // of 1 nm, so the positions are off by at most |Δv| · 1 nm / |v_n|.
        EXPECT_LT((world.body(ia).position() - end1).norm(), 1e-7) << where;
        EXPECT_LT((world.body(ib).position() - end2).norm(), 1e-7) << where;
        EXPECT_LT(world.body(ia).angularVelocity().norm(), 1e-9)
            << "frictionless: no spin but rounding";
      }
    }
  }
}

// A ball dropped on the ground, e = 0.8. With H the energy per unit mass above
// the touching height (½v² + g (z − r)), each bounce multiplies H by e²
// exactly, and in flight each integrator changes it by a known amount per
// step of length h: explicit Euler by +½g²h², semi-implicit Euler by −½g²h²,
// RK4 not at all (it is exact for constant gravity). So from apex k−1 to
// apex k, with n1 steps down and n2 up,
//   H_k = e² (H_{k−1} + δ1) + δ2,  |δ1| <= n1 c,  |δ2| <= n2 c,  c = ½g²dt²,
// and the ratio H_k / H_{k−1} stays within (e² n1 + n2) c / H_{k−1} of e²:
// no drift beyond the integrator's own in free flight. (Answering the bounce
// at the start of the step instead gave 0.645, 0.646, 0.647 for 0.64.)
TEST_P(Impacts, BouncingBallApexRatiosStayAtESquared) {
  const double e = 0.8, radius = 0.1, h0 = 1.0, g = 9.81, dt = GetParam().dt;
  World world(settings(e, 0.5));
  addGround(world);
  const BodyId ball = testing::addSphere(world, "ball", radius, Vec3(0, 0, radius + h0));
  const auto energy = [&] {
    const BodyView b = world.body(ball);
    return 0.5 * b.linearVelocity().squaredNorm() + g * (b.position().z() - radius);
  };
  double previousEnergy = g * h0;
  int previousApexStep = 0;
  double previousVelocity = 0.0;
  int bounces = 0;
  const double c = 0.5 * g * g * dt * dt;
  const double perStep = GetParam().integrator == IntegratorKind::Rk4 ? 0.0 : c;
  for (int i = 1; i <= static_cast<int>(10.0 / dt) && bounces < 5; ++i) {
    world.step();
    const double v = world.body(ball).linearVelocity().z();
    if (previousVelocity > 0.0 && v <= 0.0) {
      const double apexEnergy = energy();
      const int steps = i - previousApexStep;
      // Down and up take about as long each: n1 = n2 = steps / 2 bounds e² n1 + n2.
      const double bound = (1.0 + e * e) * 0.5 * steps * perStep / previousEnergy + 1e-8;
      EXPECT_NEAR(apexEnergy / previousEnergy, e * e, bound) << "bounce " << bounces + 1;
      previousEnergy = apexEnergy;
      previousApexStep = i;
      ++bounces;
    }
    previousVelocity = v;
  }
  EXPECT_EQ(bounces, 5);
}

// A frictionless box tilted so that one corner is lowest, falling on the
// ground: it must take Baraff's impulse j = −(1+e) v_rel / (1/M +
// n·(I⁻¹(r×n))×r) at the corner, with the state of the moment the corner
// touches. The test finds that moment itself, by bisection on the corner's
// height along the integrator's free flight.
TEST_P(Impacts, BoxLandingOnACornerGetsTheImpulseWhereItTouches) {
  const double e = 0.6;
  const WorldSettings s = settings(e, 0.0);
  World world(s);
  addGround(world);
  const Vec3 halfExtents(0.1, 0.15, 0.2);
  const Quaternion tilt = Quaternion::fromRollPitchYaw(0.3, 0.4, 0.0);
  const BodyId box =
      testing::addBox(world, "box", halfExtents, Vec3(0, 0, 0.5), tilt, Vec3(0.2, 0, 0));
  world.setBodyVelocities(box, Vec3(0.2, 0.0, 0.0), Vec3(0.5, -0.3, 0.2));
  const double dt = s.dt;
  // The lowest corner of a box at a state (its frame is the body frame).
  const auto lowestCorner = [&](const RigidState& state) {
    Vec3 lowest = Vec3::Constant(1e9);
    for (int k = 0; k < 8; ++k) {
      const Vec3 local((k & 1 ? 1 : -1) * halfExtents.x(), (k & 2 ? 1 : -1) * halfExtents.y(),
                       (k & 4 ? 1 : -1) * halfExtents.z());
      const Vec3 corner = state.position + state.orientation.rotate(local);
      if (corner.z() < lowest.z()) lowest = corner;
    }
    return lowest;
  };
  for (int i = 0; i < static_cast<int>(2.0 / dt); ++i) {
    // The box before the step (a view would follow it through the step).
    const RigidState startState = world.body(box).state();
    const Mat3 startRotation = world.body(box).rotation();
    const BodyDynamics dynamics = world.body(box).dynamics();
    world.step();
    if (world.contacts().empty() || world.contacts()[0].points[0].normalImpulse == 0.0) continue;
    ASSERT_EQ(world.contacts().size(), 1u);
    const SolvedManifold& m = world.contacts()[0];
    ASSERT_EQ(m.pointCount, 1) << "one corner touches";

    ForceInputs gravity;
    gravity.gravity = s.gravity;
    const auto flight = [&](double t) {
      return t == 0.0 ? startState
                      : integrateStep(s.integrator, startState, startRotation,
                                      dynamics, gravity, t);
    };
    double low = 0.0, high = dt;
    ASSERT_GT(lowestCorner(flight(low)).z(), 0.0);
    ASSERT_LT(lowestCorner(flight(high)).z(), 0.0)
        << "the corner reaches the ground within the step";
    for (int k = 0; k < 100; ++k) {
      const double mid = 0.5 * (low + high);
      (lowestCorner(flight(mid)).z() > 0.0 ? low : high) = mid;
    }
    const RigidState atImpact = flight(low);
    const Mat3 rotation = atImpact.orientation.toRotationMatrix();
    const Mat3 inverseInertia =
        rotation * dynamics.inverseInertiaBody.asDiagonal() * rotation.transpose();
    const Vec3 v = atImpact.linearMomentum * dynamics.inverseMass;
    const Vec3 omega = inverseInertia * atImpact.angularMomentum;
    const Vec3 n = Vec3::UnitZ();
    const Vec3 r = lowestCorner(atImpact) - atImpact.position;
    const double vRel = (v + omega.cross(r)).dot(n);
    ASSERT_LT(vRel, -0.5);  // colliding
    const double k = dynamics.inverseMass + n.dot((inverseInertia * r.cross(n)).cross(r));
    const double j = -(1.0 + e) * vRel / k;
    EXPECT_NEAR(m.points[0].normalImpulse, j, 1e-7 * j);
    EXPECT_LT((m.points[0].point - lowestCorner(atImpact)).norm(), 1e-7)
        << "reported where it touched";
    EXPECT_NEAR(m.points[0].relativeNormalVelocity, vRel, 1e-7)
        << "reported colliding at its impact speed";
    // After the impulse, free flight over the rest of the step.
    RigidState after = atImpact;
    after.linearMomentum += j * n;
    after.angularMomentum += r.cross(j * n);
    after = integrateStep(s.integrator, after, rotation, dynamics, gravity, dt - low);
    const BodyView stepped = world.body(box);
    EXPECT_LT((stepped.linearMomentum() - after.linearMomentum).norm(), 1e-7 * j);
    EXPECT_LT((stepped.angularMomentum() - after.angularMomentum).norm(), 1e-7 * j);
    // The world's time of impact is found to a gap of 1 nm, the test's to
    // rounding: the positions differ by up to |Δv| · 1 nm / |v_rel| = (1 + e) nm.
    EXPECT_LT((stepped.position() - after.position).norm(), (1.0 + e) * 1e-9);
    // It leaves the corner with exactly −e v_rel.
    const Vec3 vAfter = (atImpact.linearMomentum + j * n) * dynamics.inverseMass;
    const Vec3 omegaAfter = inverseInertia * (atImpact.angularMomentum + r.cross(j * n));
    EXPECT_NEAR((vAfter + omegaAfter.cross(r)).dot(n), -e * vRel, 1e-9);
    return;
  }
  FAIL() << "the box never landed";
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, Impacts, ::testing::ValuesIn(allCases()), nameOf);

}  // namespace
}  // namespace rbsim
