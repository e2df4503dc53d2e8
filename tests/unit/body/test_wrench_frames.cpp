// Loads at points fixed in the body, with world-frame and body-frame forces
// (external_load.h), against the mechanics they must produce: the first-step
// accelerations, a 1 s tumble against an independent reference, and the
// steady precession of a symmetric top held up at its tip.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics/body/integrator.h"
#include "rbsim/physics/world.h"

namespace rbsim {
namespace {

// A 2 kg box of half extents (0.1, 0.2, 0.3) m: principal moments
// m/3 (b² + c², a² + c², a² + b²).
BodyDynamics boxDynamics() {
  BodyDynamics d;
  d.mass = 2.0;
  d.inverseMass = 0.5;
  d.inertiaBody = (2.0 / 3.0) * Vec3(0.04 + 0.09, 0.01 + 0.09, 0.01 + 0.04);
  d.inverseInertiaBody = d.inertiaBody.cwiseInverse();
  return d;
}

const Vec3 kCorner(0.1, -0.2, 0.3);  // m, body frame

std::vector<IntegratorKind> allIntegrators() {
  return {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler, IntegratorKind::Rk4};
}

TEST(WrenchFrames, AccumulatorTorqueIsTheSumOfTheLeverMoments) {
  // S = Σ rᵢ fᵢᵀ must give Σ (R rᵢ) × fᵢ at any rotation, plus the rest.
  const Vec3 r1(0.1, -0.2, 0.3), f1(0.3, -0.2, 0.5);
  const Vec3 r2(-0.4, 0.05, 0.2), f2(-1.0, 0.7, 0.1);
  const Vec3 couple(0.01, 0.02, -0.03);
  const Vec3 rb(0.2, 0.1, -0.1), fb(0.0, 1.5, -0.5), coupleBody(0.3, 0.0, 0.1);
  ExternalLoad load;
  load.addWorldWrench(f1, couple, r1);
  load.addWorldWrench(f2, Vec3::Zero(), r2);
  load.addBodyWrench(fb, coupleBody, rb);
  for (const Quaternion& q : {Quaternion::identity(), Quaternion::fromRollPitchYaw(0.3, -1.2, 2.5),
                              Quaternion::fromAxisAngle(Vec3(1, 1, 0).normalized(), 3.0)}) {
    const Mat3 rotation = q.toRotationMatrix();
    const Vec3 expected = (rotation * r1).cross(f1) + (rotation * r2).cross(f2) + couple +
                          rotation * (rb.cross(fb) + coupleBody);
    EXPECT_LT((load.torqueAt(rotation) - expected).norm(), 1e-15);
    EXPECT_LT((load.forceAt(rotation) - (f1 + f2 + rotation * fb)).norm(), 1e-15);
  }
}

// A world force at a box corner, the body at rest and turned: a = F/m and
// α = I_world⁻¹ ((R r_b) × F). The Euler schemes take the load at the start
// of the step, so one step reproduces them to rounding at any dt. RK4 also
// takes it where its stages have turned the body: from rest that is a turn
// of about ½ α h² at stage time h, so its mean torque differs by a relative
// α dt²/6; at dt = 1e-7 s that is below 1e-13.
TEST(WrenchFrames, WorldForceAtACornerGivesFOverMAndTheLeverMomentAfterOneStep) {
  const BodyDynamics body = boxDynamics();
  RigidState start;
  start.position = Vec3(1.0, -2.0, 3.0);
  start.orientation = Quaternion::fromRollPitchYaw(0.4, -0.7, 1.9);
  const Mat3 rotation = start.orientation.toRotationMatrix();
  const Vec3 force(0.3, -0.2, 0.5);  // N, world
  ExternalLoad load;
  load.addWorldWrench(force, Vec3::Zero(), kCorner);
  ForceInputs inputs;
  inputs.load = &load;

  const Vec3 expectedA = force / body.mass;
  const Mat3 invInertiaWorld =
      rotation * body.inverseInertiaBody.asDiagonal() * rotation.transpose();
  const Vec3 expectedAlpha = invInertiaWorld * (rotation * kCorner).cross(force);
  ASSERT_GT(expectedAlpha.norm(), 1.0);  // rad/s²: a real turn, not a rounding
  for (IntegratorKind kind : allIntegrators()) {
    const std::vector<double> steps = kind == IntegratorKind::Rk4 ? std::vector<double>{1e-7, 3e-7}
                                                                  : std::vector<double>{1e-3, 1e-5};
    for (double dt : steps) {
      const RigidState next = integrateStep(kind, start, rotation, body, inputs, dt);
      const Vec3 a = (next.linearMomentum - start.linearMomentum) * body.inverseMass / dt;
      // ω gained over the step, read in the start orientation.
      const Vec3 alpha =
          angularVelocityFrom(rotation, body.inverseInertiaBody, next.angularMomentum) / dt;
      EXPECT_LT((a - expectedA).norm(), 1e-12 * expectedA.norm())
          << integratorName(kind) << " dt " << dt;
      EXPECT_LT((alpha - expectedAlpha).norm(), 1e-12 * expectedAlpha.norm())
          << integratorName(kind) << " dt " << dt;
    }
  }
}

// The reference: the same loads written straight from their definitions, in
// other variables (body-frame ω and Euler's equations, q̇ = ½ q ⊗ ω_b), with
// no ExternalLoad, integrated by classical RK4 at a step 100 times smaller.
struct ReferenceState {
  Vec3 position, velocity, omegaBody;
  Quaternion orientation;
};

struct TumbleLoads {
  Vec3 worldForce{0.3, -0.2, 0.5};   // N, world, at kCorner
  Vec3 worldCouple{0.0, 0.02, 0.0};  // N·m, world
  Vec3 bodyForce{0.0, 0.4, 0.0};     // N, body frame
  Vec3 bodyPoint{-0.1, 0.0, 0.3};    // m, body frame, where bodyForce acts
};

ReferenceState referenceRate(const ReferenceState& s, const BodyDynamics& body,
                             const TumbleLoads& loads) {
  const Mat3 r = s.orientation.normalized().toRotationMatrix();
  const Vec3 forceWorld = loads.worldForce + r * loads.bodyForce;
  const Vec3 torqueBody = kCorner.cross(r.transpose() * loads.worldForce) +
                          r.transpose() * loads.worldCouple +
                          loads.bodyPoint.cross(loads.bodyForce);
  const Vec3 inertia = body.inertiaBody;
  const Vec3 iw = inertia.cwiseProduct(s.omegaBody);
  const Quaternion spin =
      s.orientation * Quaternion{0.0, s.omegaBody.x(), s.omegaBody.y(), s.omegaBody.z()};
  ReferenceState rate;
  rate.position = s.velocity;
  rate.velocity = forceWorld / body.mass;
  rate.omegaBody = (torqueBody - s.omegaBody.cross(iw)).cwiseQuotient(inertia);
  rate.orientation = {0.5 * spin.w, 0.5 * spin.x, 0.5 * spin.y, 0.5 * spin.z};
  return rate;
}

ReferenceState plus(const ReferenceState& s, const ReferenceState& rate, double h) {
  return {s.position + h * rate.position,
          s.velocity + h * rate.velocity,
          s.omegaBody + h * rate.omegaBody,
          {s.orientation.w + h * rate.orientation.w, s.orientation.x + h * rate.orientation.x,
           s.orientation.y + h * rate.orientation.y, s.orientation.z + h * rate.orientation.z}};
}

ReferenceState referenceRun(ReferenceState s, const BodyDynamics& body, const TumbleLoads& loads,
                            double h, int steps) {
  for (int i = 0; i < steps; ++i) {
    const ReferenceState k1 = referenceRate(s, body, loads);
    const ReferenceState k2 = referenceRate(plus(s, k1, 0.5 * h), body, loads);
    const ReferenceState k3 = referenceRate(plus(s, k2, 0.5 * h), body, loads);
    const ReferenceState k4 = referenceRate(plus(s, k3, h), body, loads);
    s = plus(plus(plus(plus(s, k1, h / 6), k2, h / 3), k3, h / 3), k4, h / 6);
    s.orientation = s.orientation.normalized();
  }
  return s;
}

double angleBetween(const Quaternion& a, const Quaternion& b) {
  const Quaternion d = a.conjugate() * b;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w));
}

TEST(WrenchFrames, Rk4TumbleUnderBodyPointLoadsMatchesAnIndependentReferenceOverOneSecond) {
  const BodyDynamics body = boxDynamics();
  const TumbleLoads loads;
  const Vec3 omega0(0.5, -1.0, 2.0);  // rad/s, world
  RigidState start;
  start.position = Vec3(0.5, 0.0, -1.0);
  start.orientation = Quaternion::fromRollPitchYaw(0.4, -0.7, 1.9);
  const Mat3 r0 = start.orientation.toRotationMatrix();
  start.linearMomentum = body.mass * Vec3(0.1, 0.0, 0.2);
  start.angularMomentum = r0 * body.inertiaBody.cwiseProduct(r0.transpose() * omega0);

  ExternalLoad load;
  load.addWorldWrench(loads.worldForce, loads.worldCouple, kCorner);
  load.addBodyWrench(loads.bodyForce, Vec3::Zero(), loads.bodyPoint);
  ForceInputs inputs;
  inputs.load = &load;

  for (double dt : {1e-3, 5e-4}) {
    const int steps = static_cast<int>(std::lround(1.0 / dt));
    RigidState state = start;
    for (int i = 0; i < steps; ++i)
      state = rk4Step(state, state.orientation.toRotationMatrix(), body, inputs, dt);

    const ReferenceState reference = referenceRun({start.position, start.linearMomentum / body.mass,
                                                   r0.transpose() * omega0, start.orientation},
                                                  body, loads, dt / 100, steps * 100);
    const double angle = angleBetween(state.orientation, reference.orientation);
    EXPECT_LT(angle, 1e-8) << "dt " << dt;
    EXPECT_LT((state.position - reference.position).norm(), 1e-10) << "dt " << dt;
    const Mat3 r = state.orientation.toRotationMatrix();
    const Vec3 omegaBody =
        r.transpose() * angularVelocityFrom(r, body.inverseInertiaBody, state.angularMomentum);
    EXPECT_LT((omegaBody - reference.omegaBody).norm(), 1e-8) << "dt " << dt;
    std::printf("dt %g: orientation %.3g rad, position %.3g m from the reference\n", dt, angle,
                (state.position - reference.position).norm());
  }
}

// A symmetric top (transverse moment A about the centre of mass, axial C,
// mass m) free in gravity g, held up by a constant world-frame force m g ẑ at
// the body point r_tip = −l e₃ on its axis, below the centre of mass (the
// top stands on its tip, the tip pushed up; nothing holds the tip in place).
// The net force is zero, so the centre of mass stays put and the motion is a
// rotation about it, driven by the torque about the centre of mass
//   τ = (R r_tip) × (m g ẑ) = −m g l (e₃ × ẑ) = m g l (ẑ × e₃),
// the same function of the orientation as gravity's torque on a heavy top
// whose centre of mass is l above a fixed pivot, (l e₃) × (−m g ẑ). The
// equations dL/dt = τ, L = I ω are therefore those of the heavy top with A
// the moment about the centre of mass (the pivot's A + m l² does not enter:
// no point but the centre of mass is fixed). Steady precession at rate Ω
// about ẑ, with e₃ at θ from ẑ: ω = Ω ẑ + ψ̇ e₃, ω₃ = ω·e₃ = Ω cos θ + ψ̇,
//   L = A Ω (ẑ − cos θ e₃) + C ω₃ e₃,   dL/dt = Ω ẑ × L = (C ω₃ − A Ω cos θ) Ω ẑ × e₃,
// and dL/dt = τ gives A cos θ Ω² − C ω₃ Ω + m g l = 0. With the tip above
// the centre of mass (r_tip = +l e₃) the torque changes sign and so does the
// m g l term: the top hangs from its tip like a gyroscopic pendulum.
TEST(WrenchFrames, SymmetricTopHeldUpAtItsTipPrecessesAtTheSlowRoot) {
  const double m = 1.0, g = 9.81, l = 0.05;      // kg, m/s², m
  const double radius = 0.1, halfLength = 0.02;  // m: a squat disc, C > A
  const double a = m * (3 * radius * radius + 4 * halfLength * halfLength) / 12;
  const double c = m * radius * radius / 2;
  const double theta = 0.3, omega3 = 60.0;  // rad, rad/s
  const double disc = c * c * omega3 * omega3 - 4 * a * std::cos(theta) * m * g * l;
  ASSERT_GT(disc, 0.0);
  const double slow = (c * omega3 - std::sqrt(disc)) / (2 * a * std::cos(theta));  // rad/s

  for (double dt : {1e-3, 5e-4}) {
    WorldSettings settings;
    settings.dt = dt;
    settings.gravity = Vec3(0.0, 0.0, -g);
    settings.integrator = IntegratorKind::Rk4;
    World world(settings);
    BodyDef def;
    def.name = "top";
    def.shape = CylinderShape{radius, halfLength};
    def.mass = m;
    // e₃ = R ẑ = (0, −sin θ, cos θ): azimuth −90°.
    def.orientation = Quaternion::fromAxisAngle(Vec3::UnitX(), theta);
    const Vec3 e3 = def.orientation.rotate(Vec3::UnitZ());
    def.angularVelocity = slow * Vec3::UnitZ() + (omega3 - slow * std::cos(theta)) * e3;
    const auto created = world.createBody(def);
    ASSERT_TRUE(created.ok()) << created.error().message;
    const BodyId top = *created;
    ASSERT_NEAR(world.body(top).dynamics().inertiaBody.x(), a, 1e-15);
    ASSERT_NEAR(world.body(top).dynamics().inertiaBody.z(), c, 1e-15);

    const auto axisAzimuth = [&] {
      const Vec3 axis = world.body(top).rotation() * Vec3::UnitZ();
      return std::atan2(axis.y(), axis.x());
    };
    const double seconds = 3.0;
    const int steps = static_cast<int>(std::lround(seconds / dt));
    double azimuth = axisAzimuth(), turned = 0.0, maxTilt = 0.0;
    for (int i = 0; i < steps; ++i) {
      world.applyWrench(top, {Vec3(0.0, 0.0, m * g), Vec3::Zero(), Vec3(0.0, 0.0, -l), Wrench::Frame::WorldAtBodyPoint});
      world.step();
      const double next = axisAzimuth();
      turned += std::remainder(next - azimuth, 2 * M_PI);
      azimuth = next;
      const Vec3 axis = world.body(top).rotation() * Vec3::UnitZ();
      maxTilt = std::max(maxTilt, std::abs(std::acos(axis.z()) - theta));
    }
    const double measured = turned / seconds;
    std::printf("dt %g: precession %.12f rad/s, slow root %.12f rad/s, relative %.3g\n", dt,
                measured, slow, std::abs(measured - slow) / slow);
    EXPECT_LT(std::abs(measured - slow), 1e-6 * slow) << "dt " << dt;
    EXPECT_LT(maxTilt, 1e-6) << "steady precession keeps θ";
    EXPECT_LT(world.body(top).position().norm(), 1e-9) << "the centre of mass stays put";
  }
}

}  // namespace
}  // namespace rbsim
