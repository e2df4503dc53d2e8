// The penalty model against the closed-form solution of the linear
// spring–damper: a ball dropped on the ground (with gravity), two balls
// colliding in free space (a coupled pair), and the static depth m g / k.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

constexpr double kG = 9.81;
constexpr double kRadius = 0.1;
const IntegratorKind kIntegrators[] = {IntegratorKind::ExplicitEuler,
                                       IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4};

// m d̈ = −k d − c ḋ + m g during contact, d the penetration, from touch-down
// (d = 0, ḋ = vIn > 0) at t = 0. With y = d − d_s, d_s = m g / k, this is the
// damped oscillator m ÿ + c ẏ + k y = 0, y(0) = −d_s, ẏ(0) = vIn:
//   y = e^(−ζωt) (A cos ω_d t + B sin ω_d t),  A = −d_s,  B = (vIn + ζω A) / ω_d,
// ω = √(k/m), ζ = c / (2√(k m)), ω_d = ω √(1 − ζ²) (underdamped).
// Contact ends at the first root of d (unclamped law: the spring lets go at
// zero penetration) or of k d + c ḋ (clamped law: the force reaches zero
// while the ball is still in the ground, and earlier; it then flies freely,
// since in free flight k d + c ḋ is a parabola in t that stays negative until
// d = 0). Both roots are transcendental with gravity (e^(−ζωt) R cos(ω_d t −
// φ) = −m g for the clamped one); they are found by bisection on these
// expressions. Without gravity the clamped one is tan ω_d t =
// −2ζ√(1−ζ²)/(1 − 2ζ²) (Schwager and Pöschel 2007), checked below.
struct SpringDamperContact {
  double mass, stiffness, damping, gravity, impactSpeed;

  double omega() const { return std::sqrt(stiffness / mass); }
  double zeta() const { return damping / (2.0 * std::sqrt(stiffness * mass)); }
  double omegaDamped() const { return omega() * std::sqrt(1.0 - zeta() * zeta()); }
  double staticDepth() const { return mass * gravity / stiffness; }

  double depth(double t) const {
    const double a = -staticDepth(), b = (impactSpeed + zeta() * omega() * a) / omegaDamped();
    return staticDepth() + std::exp(-zeta() * omega() * t) *
                               (a * std::cos(omegaDamped() * t) + b * std::sin(omegaDamped() * t));
  }
  double depthRate(double t) const {
    const double a = -staticDepth(), b = (impactSpeed + zeta() * omega() * a) / omegaDamped();
    const double zw = zeta() * omega(), wd = omegaDamped();
    return std::exp(-zw * t) *
           ((b * wd - zw * a) * std::cos(wd * t) - (a * wd + zw * b) * std::sin(wd * t));
  }
  double switching(PenaltyLaw law, double t) const {
    return law == PenaltyLaw::Unclamped ? depth(t) : stiffness * depth(t) + damping * depthRate(t);
  }
  // The contact's duration: the first root after touch-down.
  double duration(PenaltyLaw law) const {
    const double period = 2.0 * std::numbers::pi / omegaDamped();
    const double scan = period * 1e-4;
    double low = scan;
    while (switching(law, low + scan) > 0.0) low += scan;
    double high = low + scan;
    for (int i = 0; i < 200 && high - low > 1e-15; ++i) {
      const double mid = 0.5 * (low + high);
      (switching(law, mid) > 0.0 ? low : high) = mid;
    }
    return 0.5 * (low + high);
  }
  double exitSpeed(PenaltyLaw law) const { return -depthRate(duration(law)); }
  double exitDepth(PenaltyLaw law) const { return depth(duration(law)); }
};

// What a simulated bounce measured. Touch-down and lift-off are located
// between steps on the free-flight trajectories next to the contact (exact
// for RK4, which integrates constant gravity exactly), so that the figures do
// not depend on where the step boundaries fall.
struct Bounce {
  double duration = 0.0;     // s
  double impactSpeed = 0.0;  // m/s
  double exitSpeed = 0.0;    // m/s, where the force ends
  double apex = 0.0;         // m, of the ball's bottom above the ground after the bounce
  bool oneContact = false;   // the force acted over one run of consecutive steps
};

double stepImpulse(const World& world) {
  double total = 0.0;
  for (const SolvedManifold& m : world.contacts())
    for (int p = 0; p < m.pointCount; ++p) total += m.points[p].normalImpulse;
  return total;
}

// The root in [−dt, 0] of a τ² + b τ + c (τ: time back from a state).
double rootBack(double a, double b, double c, double dt) {
  if (a == 0.0) return -c / b;
  const double s = std::sqrt(b * b - 4.0 * a * c);
  for (const double r : {(-b + s) / (2.0 * a), (-b - s) / (2.0 * a)})
    if (r <= 1e-12 && r >= -dt * (1.0 + 1e-9)) return r;
  return std::nan("");
}

WorldSettings penaltySettings(IntegratorKind integrator, double dt, double k, double c,
                              PenaltyLaw law) {
  WorldSettings settings = testing::contactSettings(0.0, 0.0);
  settings.dt = dt;
  settings.integrator = integrator;
  settings.contact.model = ContactModel::Penalty;
  settings.contact.penaltyStiffness = k;
  settings.contact.penaltyDamping = c;
  settings.contact.penaltyLaw = law;
  return settings;
}

BodyId addBall(World& world, const std::string& name, const Vec3& position, const Vec3& velocity,
               double mass) {
  BodyDef def;
  def.name = name;
  def.shape = SphereShape{kRadius};
  def.mass = mass;
  def.position = position;
  def.linearVelocity = velocity;
  return *world.createBody(def);
}

// A 1 kg ball whose bottom starts `drop` above the ground, at rest.
Bounce dropBall(IntegratorKind integrator, double dt, double k, double c, PenaltyLaw law,
                double drop) {
  World world(penaltySettings(integrator, dt, k, c, law));
  testing::addGround(world);
  const BodyId ball = addBall(world, "ball", Vec3(0, 0, kRadius + drop), Vec3::Zero(), 1.0);
  Bounce bounce;
  int runs = 0;
  bool touching = false, touched = false;
  double z = world.body(ball).position().z(), v = world.body(ball).linearVelocity().z();
  for (int i = 0; i < static_cast<int>(std::lround(0.5 / dt)); ++i) {
    const double zBefore = z, vBefore = v, t = world.time();
    world.step();
    z = world.body(ball).position().z();
    v = world.body(ball).linearVelocity().z();
    const bool pushed = stepImpulse(world) != 0.0;  // (the unclamped law pulls at the end)
    if (pushed && !touching) {
      ++runs;
      // Touch-down: the bottom reaches the ground on the parabola from the
      // state before this step, τ after it.
      const double tau = -rootBack(-0.5 * kG, -vBefore, zBefore - kRadius, dt);
      bounce.duration -= t + tau;
      bounce.impactSpeed = -(vBefore - kG * tau);
    }
    if (!pushed && touching) {
      // Lift-off, on the parabola back from the state after the last pushing
      // step (z, v at t): where d = 0 (unclamped) or k d + c ḋ = 0 (clamped),
      // d = r − z(τ), ḋ = −v(τ), z(τ) = z + v τ − g τ²/2.
      const double tau = law == PenaltyLaw::Unclamped
                             ? rootBack(0.5 * kG, -vBefore, kRadius - zBefore, dt)
                             : rootBack(0.5 * k * kG, -k * vBefore + c * kG,
                                        k * (kRadius - zBefore) - c * vBefore, dt);
      bounce.duration += t + tau;
      bounce.exitSpeed = vBefore - kG * tau;
      bounce.apex = zBefore + vBefore * vBefore / (2.0 * kG) - kRadius;
      touched = true;
      break;
    }
    touching = pushed;
  }
  bounce.oneContact = touched && runs == 1;
  return bounce;
}

struct BounceErrors {
  double duration, restitution, apex;  // relative to the closed form
};

BounceErrors bounceErrors(IntegratorKind integrator, double dt, PenaltyLaw law,
                          bool print = false) {
  // ω = 100 rad/s, ζ = 0.2: about 32 ms of contact; impact at 0.99 m/s.
  const double k = 1e4, c = 40.0, drop = 0.05;
  const Bounce b = dropBall(integrator, dt, k, c, law, drop);
  EXPECT_TRUE(b.oneContact) << integratorName(integrator) << " dt " << dt;
  const SpringDamperContact exact{1.0, k, c, kG, std::sqrt(2.0 * kG * drop)};
  const double duration = exact.duration(law);
  const double restitution = exact.exitSpeed(law) / exact.impactSpeed;
  const double apex =
      -exact.exitDepth(law) + exact.exitSpeed(law) * exact.exitSpeed(law) / (2.0 * kG);
  const BounceErrors errors{std::abs(b.duration / duration - 1.0),
                            std::abs(b.exitSpeed / b.impactSpeed / restitution - 1.0),
                            std::abs(b.apex / apex - 1.0)};
  if (print)
    std::printf(
        "%-20s %-9s dt %.4f s: duration %.6f s (exact %.6f), e %.6f (exact %.6f), apex %.6f m "
        "(exact %.6f)\n",
        std::string(integratorName(integrator)).c_str(), std::string(penaltyLawName(law)).c_str(),
        dt, b.duration, duration, b.exitSpeed / b.impactSpeed, restitution, b.apex, apex);
  return errors;
}

TEST(PenaltyBounce, ClosedFormCheckWithoutGravity) {
  // The bisection above against the closed form of the clamped law's end.
  const SpringDamperContact free{1.0, 1e4, 40.0, 0.0, 1.0};
  const double z = free.zeta(), s = std::sqrt(1.0 - z * z);
  const double expected =
      (std::numbers::pi - std::atan(2.0 * z * s / (1.0 - 2.0 * z * z))) / free.omegaDamped();
  EXPECT_NEAR(free.duration(PenaltyLaw::Clamped), expected, 1e-12);
  EXPECT_NEAR(free.duration(PenaltyLaw::Unclamped), std::numbers::pi / free.omegaDamped(), 1e-12);
  EXPECT_NEAR(free.exitSpeed(PenaltyLaw::Unclamped), std::exp(-z * std::numbers::pi / s), 1e-12);
}

TEST(PenaltyBounce, Rk4MatchesTheClosedFormWithinOnePercentAtOneMillisecond) {
  for (const PenaltyLaw law : {PenaltyLaw::Clamped, PenaltyLaw::Unclamped}) {
    const BounceErrors e = bounceErrors(IntegratorKind::Rk4, 1e-3, law, true);
    EXPECT_LT(e.duration, 0.01) << penaltyLawName(law);
    EXPECT_LT(e.restitution, 0.01) << penaltyLawName(law);
    EXPECT_LT(e.apex, 0.01) << penaltyLawName(law);
  }
  // For comparison, not asserted: the Euler methods at the same dt. Only the
  // apex is meaningful for them (their free flight is not the exact parabola
  // the touch-down and lift-off are located on).
  for (const IntegratorKind integrator :
       {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler})
    for (const PenaltyLaw law : {PenaltyLaw::Clamped, PenaltyLaw::Unclamped})
      bounceErrors(integrator, 1e-3, law, true);
}

TEST(PenaltyBounce, Rk4ErrorFallsAtFourthOrderWithTheStep) {
  // The contact forces are evaluated at every stage and the step is cut where
  // the force switches, so RK4 keeps its order: halving dt divides the error
  // by about 16. Forces held over the step (or a stage across the jump at
  // touch-down) would make it first order: a factor of 2.
  for (const PenaltyLaw law : {PenaltyLaw::Clamped, PenaltyLaw::Unclamped}) {
    const BounceErrors coarse = bounceErrors(IntegratorKind::Rk4, 2e-3, law, true);
    const BounceErrors fine = bounceErrors(IntegratorKind::Rk4, 1e-3, law, true);
    const BounceErrors finer = bounceErrors(IntegratorKind::Rk4, 5e-4, law, true);
    std::printf(
        "rk4 %s relative errors at dt = 2, 1, 0.5 ms: restitution %.3e %.3e %.3e, "
        "duration %.3e %.3e %.3e, apex %.3e %.3e %.3e\n",
        std::string(penaltyLawName(law)).c_str(), coarse.restitution, fine.restitution,
        finer.restitution, coarse.duration, fine.duration, finer.duration, coarse.apex, fine.apex,
        finer.apex);
    EXPECT_GT(coarse.restitution / fine.restitution, 8.0) << penaltyLawName(law);
    EXPECT_GT(fine.restitution / finer.restitution, 8.0) << penaltyLawName(law);
    EXPECT_GT(coarse.apex / fine.apex, 8.0) << penaltyLawName(law);
    EXPECT_GT(fine.apex / finer.apex, 8.0) << penaltyLawName(law);
  }
}

// Two free balls meeting head-on, no gravity: the relative coordinate is the
// same oscillator with the reduced mass m₁m₂/(m₁+m₂). Their stages are
// coupled: an RK4 that took the other ball at its step-start state would be
// first order.
TEST(PenaltyBounce, CoupledPairBouncesAsTheReducedMassOscillator) {
  const double k = 1e4, c = 20.0, m1 = 1.0, m2 = 3.0, approach = 1.0;
  const double reduced = m1 * m2 / (m1 + m2);
  const SpringDamperContact exact{reduced, k, c, 0.0, approach};
  for (const PenaltyLaw law : {PenaltyLaw::Clamped, PenaltyLaw::Unclamped}) {
    std::vector<double> errors;
    for (const double dt : {2e-3, 1e-3, 5e-4}) {
      WorldSettings settings = penaltySettings(IntegratorKind::Rk4, dt, k, c, law);
      settings.gravity = Vec3::Zero();
      World world(settings);
      // Velocities with zero total momentum, gap 4 mm (inside the margin).
      const BodyId a = addBall(world, "a", Vec3(-kRadius - 0.002, 0, 0),
                               Vec3(approach * m2 / (m1 + m2), 0, 0), m1);
      const BodyId b = addBall(world, "b", Vec3(kRadius + 0.002, 0, 0),
                               Vec3(-approach * m1 / (m1 + m2), 0, 0), m2);
      for (int i = 0; i < static_cast<int>(std::lround(0.1 / dt)); ++i) world.step();
      const double separation =
          world.body(b).linearVelocity().x() - world.body(a).linearVelocity().x();
      const double restitution = exact.exitSpeed(law) / approach;
      errors.push_back(std::abs(separation / approach / restitution - 1.0));
      EXPECT_NEAR(world.totalLinearMomentum().norm(), 0.0, 1e-12);
      EXPECT_LT(errors.back(), 0.01) << penaltyLawName(law) << " dt " << dt;
    }
    std::printf("pair %s: restitution errors %.3e %.3e %.3e\n",
                std::string(penaltyLawName(law)).c_str(), errors[0], errors[1], errors[2]);
    EXPECT_GT(errors[0] / errors[1], 8.0) << penaltyLawName(law);
    EXPECT_GT(errors[1] / errors[2], 8.0) << penaltyLawName(law);
  }
}

TEST(PenaltyBounce, StaticDepthIsMgOverKWithEveryIntegrator) {
  // At rest every integrator's fixed point has F = m g (+ the client's push),
  // so d = (m g + F) / k, whatever the law. Critically damped: it settles in
  // a few 1/ω = 10 ms.
  const double k = 1e4, c = 2.0 * std::sqrt(k * 1.0);
  for (const IntegratorKind integrator : kIntegrators) {
    for (const double dt : {1e-3, 5e-4}) {
      for (const PenaltyLaw law : {PenaltyLaw::Clamped, PenaltyLaw::Unclamped}) {
        for (const double push : {0.0, 5.0}) {
          World world(penaltySettings(integrator, dt, k, c, law));
          testing::addGround(world);
          const BodyId ball = addBall(world, "ball", Vec3(0, 0, kRadius), Vec3::Zero(), 1.0);
          for (int i = 0; i < static_cast<int>(std::lround(1.0 / dt)); ++i) {
            // A client's steady downward push: its own load, beside the contact's force.
            if (push != 0.0)
              world.applyWrench(ball, {Vec3(0, 0, -push), Vec3::Zero(), world.body(ball).position(), Wrench::Frame::World});
            world.step();
          }
          const double depth = kRadius - world.body(ball).position().z();
          EXPECT_NEAR(depth, (1.0 * kG + push) / k, 1e-6)
              << integratorName(integrator) << " dt " << dt << " " << penaltyLawName(law)
              << " push " << push;
          EXPECT_NEAR(stepImpulse(world), (1.0 * kG + push) * dt, 1e-6 * dt);
        }
      }
    }
  }
}

TEST(PenaltyBounce, BoxRestsAtTheSameDepthOnFourPoints) {
  // Stiffness is per manifold: four corners share k.
  const double k = 2e4, mass = 2.0, c = 2.0 * std::sqrt(k * mass);
  for (const IntegratorKind integrator : kIntegrators) {
    World world(penaltySettings(integrator, 1e-3, k, c, PenaltyLaw::Clamped));
    testing::addGround(world);
    BodyDef def;
    def.name = "box";
    def.shape = BoxShape{Vec3(0.2, 0.1, 0.05)};
    def.mass = mass;
    def.position = Vec3(0, 0, 0.05);
    const BodyId box = *world.createBody(def);
    for (int i = 0; i < 1500; ++i) world.step();
    EXPECT_EQ(world.contactPointCount(), 4);
    EXPECT_NEAR(0.05 - world.body(box).position().z(), mass * kG / k, 1e-6)
        << integratorName(integrator);
    EXPECT_LT(world.body(box).angularVelocity().norm(), 1e-6);
  }
}

TEST(PenaltyBounce, EulerMethodsTakeTheContactForceOfTheStepStart) {
  // One step from a ball 2 mm deep, sinking at 0.5 m/s: the force at the
  // start is F = k d − c v_z, and the Euler methods are what they say.
  const double k = 1e4, c = 40.0, h = 1e-3, d = 0.002, v = -0.5;
  const double force = k * d - c * v;
  for (const IntegratorKind integrator :
       {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler}) {
    World world(penaltySettings(integrator, h, k, c, PenaltyLaw::Clamped));
    testing::addGround(world);
    const BodyId ball = addBall(world, "ball", Vec3(0, 0, kRadius - d), Vec3(0, 0, v), 1.0);
    world.step();
    const double v1 = v + h * (force / 1.0 - kG);
    const double z1 = kRadius - d + h * (integrator == IntegratorKind::ExplicitEuler ? v : v1);
    EXPECT_NEAR(world.body(ball).linearVelocity().z(), v1, 1e-12) << integratorName(integrator);
    EXPECT_NEAR(world.body(ball).position().z(), z1, 1e-12) << integratorName(integrator);
    EXPECT_NEAR(stepImpulse(world), force * h, 1e-12);
    EXPECT_FALSE(world.body(ball).isPushed()) << "contact forces are not a client load";
  }
}

}  // namespace
}  // namespace rbsim
