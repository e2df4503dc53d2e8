// Pendulums against their closed forms: the period of a physical pendulum on
// a hinge, a ball joint and a rod (the complete elliptic integral), the
// energy of a double pendulum over 10 s, each at two steps; the joint step
// is second order (halving dt divides the error by about four) and the same
// whatever the world's integrator. A spatial arm whose links tumble in 3-D
// with unequal principal moments about skew axes converges at second order
// too (the drift turns each body as a free rigid body does).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::hinge;
using testing::jointWorldSettings;

constexpr double kPi = std::numbers::pi;
constexpr IntegratorKind kIntegrators[] = {IntegratorKind::SemiImplicitEuler, IntegratorKind::ExplicitEuler,
                                           IntegratorKind::Rk4};

enum class Pivot { Hinge, Ball, Rod };

struct PendulumRun {
  double period = 0.0;         // s, measured
  double expected = 0.0;       // s, closed form
  double largestError = 0.0;   // largest joint error seen, m or rad
  double energyDrift = 0.0;    // largest |E − E₀| / (m g d)
  uint64_t hash = 0;
};

// A body on a pivot at the origin, its centre of mass `distance` away,
// released at rest `amplitude` from the vertical in the x–z plane; the hinge
// axis is y. `rolled`: a box turned 30° about its arm, so that the hinge is
// not a principal axis (the hinge's angular rows then carry a torque).
PendulumRun swing(Pivot pivot, bool rolled, double amplitude, IntegratorKind integrator, double dt,
                  double seconds = 10.0) {
  World world(jointWorldSettings(integrator, dt));
  const double distance = 0.5, mass = 1.0;
  const Vec3 arm(std::sin(amplitude), 0.0, -std::cos(amplitude));  // pivot to centre of mass
  Quaternion orientation = Quaternion::identity();
  Shape shape = SphereShape{0.05};
  if (rolled) {
    // The box's z axis along the arm (pointing away from the pivot), then a
    // roll of 30° about the arm.
    orientation = Quaternion::fromAxisAngle(arm, kPi / 6.0) * Quaternion::fromAxisAngle(Vec3::UnitY(), kPi - amplitude);
    shape = BoxShape{Vec3(0.04, 0.1, 0.15)};
  }
  const BodyId bob = addBody(world, "bob", shape, mass, distance * arm, orientation);
  JointDef def = hinge("pivot", BodyId{}, bob, Vec3::Zero(), Vec3::UnitY());
  if (pivot == Pivot::Ball) def.type = JointType::Spherical;
  if (pivot == Pivot::Rod) {
    def.type = JointType::Distance;
    def.anchorB = distance * arm;  // the bob's centre: it turns freely on the rod's end
  }
  const JointId joint = addJoint(world, def);

  PendulumRun run;
  // About the pivot, about y: the bob's own moment about y plus m d²; a rod
  // on the centre of mass leaves the bob's spin out (a point mass).
  const double own = pivot == Pivot::Rod ? 0.0 : Vec3::UnitY().dot(world.body(bob).inertiaWorld() * Vec3::UnitY());
  run.expected = testing::physicalPendulumPeriod(own + mass * distance * distance, mass, distance, amplitude);
  const double startEnergy = testing::mechanicalEnergy(world);
  std::vector<double> times, angles;
  const auto steps = static_cast<int>(std::lround(seconds / dt));
  for (int k = 0; k < steps; ++k) {
    world.step();
    const Vec3 x = world.body(bob).position();
    times.push_back(world.time());
    angles.push_back(std::atan2(x.x(), -x.z()));
    run.largestError = std::max(run.largestError, world.jointState(joint).error);
    run.energyDrift = std::max(run.energyDrift, std::abs(testing::mechanicalEnergy(world) - startEnergy) /
                                                    (mass * testing::kGravity * distance));
  }
  run.period = testing::meanPeriod(testing::zeroCrossings(times, angles));
  run.hash = world.stateHash();
  return run;
}

TEST(JointPendulums, HingePeriodMatchesTheEllipticClosedFormAndIsSecondOrder) {
  for (const bool rolled : {false, true}) {
    for (const double amplitude : {10.0 * kPi / 180.0, kPi / 2.0}) {
      double errors[2];
      for (int d = 0; d < 2; ++d) {
        const double dt = d == 0 ? 1e-3 : 5e-4;
        SCOPED_TRACE(::testing::Message() << (rolled ? "rolled box" : "sphere") << ", amplitude "
                                          << amplitude << " rad, dt " << dt);
        const PendulumRun run = swing(Pivot::Hinge, rolled, amplitude, IntegratorKind::SemiImplicitEuler, dt);
        errors[d] = std::abs(run.period - run.expected) / run.expected;
        std::printf("hinge %s %.0f deg dt %g: period error %.2e, joint error %.1e, energy %.2e\n",
                    rolled ? "rolled box" : "sphere", amplitude * 180.0 / kPi, dt, errors[d], run.largestError,
                    run.energyDrift);
        EXPECT_LT(errors[d], 1e-4) << "period " << run.period << " s, closed form " << run.expected << " s";
        EXPECT_LT(run.largestError, 1e-11) << "the hinge holds its anchor and axis";
        EXPECT_LT(run.energyDrift, 1e-4) << "a frictionless hinge keeps the energy";
      }
      // Second order: the 90° error is far above what the crossing
      // interpolation adds, so halving dt shows the order.
      if (amplitude > 1.0) {
        EXPECT_LT(errors[1], 0.35 * errors[0]) << errors[0] << " then " << errors[1];
      }
    }
  }
}

TEST(JointPendulums, BallJointAndRodPendulumsMatchTheirClosedForms) {
  for (const Pivot pivot : {Pivot::Ball, Pivot::Rod}) {
    for (const double dt : {1e-3, 5e-4}) {
      SCOPED_TRACE(::testing::Message() << (pivot == Pivot::Ball ? "ball joint" : "rod") << ", dt " << dt);
      const PendulumRun run = swing(pivot, false, kPi / 2.0, IntegratorKind::SemiImplicitEuler, dt);
      std::printf("%s 90 deg dt %g: period error %.2e, joint error %.1e, energy %.2e\n",
                  pivot == Pivot::Ball ? "ball joint" : "rod", dt, std::abs(run.period - run.expected) / run.expected,
                  run.largestError, run.energyDrift);
      EXPECT_LT(std::abs(run.period - run.expected) / run.expected, 1e-4)
          << "period " << run.period << " s, closed form " << run.expected << " s";
      EXPECT_LT(run.largestError, 1e-11);
      EXPECT_LT(run.energyDrift, 1e-4);
    }
  }
}

TEST(JointPendulums, JointedBodiesTakeTheJointStepWhateverTheWorldsIntegrator) {
  // The joint step is the same for every integrator setting: bit for bit.
  uint64_t hashes[3];
  for (int k = 0; k < 3; ++k) {
    const PendulumRun run = swing(Pivot::Hinge, true, kPi / 2.0, kIntegrators[k], 1e-3, 2.0);
    hashes[k] = run.hash;
    EXPECT_LT(run.largestError, 1e-11);
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
}

// Two equal spheres on two hinges, released with both arms horizontal: a
// chaotic motion whose energy the joint step must keep.
double doublePendulumEnergyError(double dt, IntegratorKind integrator) {
  World world(jointWorldSettings(integrator, dt));
  const double length = 0.5, mass = 1.0;
  const BodyId upper = addBody(world, "upper", SphereShape{0.05}, mass, Vec3(length, 0, 0));
  const BodyId lower = addBody(world, "lower", SphereShape{0.05}, mass, Vec3(2 * length, 0, 0));
  addJoint(world, hinge("shoulder", BodyId{}, upper, Vec3::Zero(), Vec3::UnitY()));
  const JointId elbow = addJoint(world, hinge("elbow", upper, lower, Vec3(length, 0, 0), Vec3::UnitY()));
  const double start = testing::mechanicalEnergy(world);
  double worst = 0.0, worstJoint = 0.0;
  const auto steps = static_cast<int>(std::lround(10.0 / dt));
  for (int k = 0; k < steps; ++k) {
    world.step();
    worst = std::max(worst, std::abs(testing::mechanicalEnergy(world) - start));
    worstJoint = std::max(worstJoint, world.jointState(elbow).error);
  }
  EXPECT_LT(worstJoint, 1e-11);
  return worst / (2.0 * mass * testing::kGravity * length);
}

TEST(JointPendulums, DoublePendulumKeepsItsEnergyWithin1e3Over10sAtSecondOrder) {
  const double coarse = doublePendulumEnergyError(1e-3, IntegratorKind::SemiImplicitEuler);
  const double fine = doublePendulumEnergyError(5e-4, IntegratorKind::Rk4);
  EXPECT_LT(coarse, 1e-3);
  EXPECT_LT(fine, 1e-3);
  std::printf("double pendulum energy error over 10 s: %.2e (dt 1 ms), %.2e (dt 0.5 ms)\n", coarse, fine);
  EXPECT_LT(fine, 0.4 * coarse) << "second order: " << coarse << " then " << fine;
}

// Four boxes with unequal moments, turned off their principal axes, on
// hinges along z, y and two skew axes; gravity and an effort on the first
// hinge; no damping. Where its links' centres of mass are after 0.5 s at
// dt, dt/2 and dt/4, against the same arm at dt/32: the error falls by four
// with each halving (the drift holding ω fixed over the step made it fall
// by two: 3.9e-4 m at 1 ms, where it is now 1.4e-5 m).
std::vector<Vec3> spatialArmAfterHalfASecond(double dt) {
  WorldSettings settings = jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt);
  World world(settings);
  const BodyId a = addBody(world, "a", BoxShape{Vec3(0.05, 0.06, 0.2)}, 3.0, Vec3(0, 0, 0.2),
                           Quaternion::fromAxisAngle(Vec3(1, 2, 0).normalized(), 0.2));
  const BodyId b = addBody(world, "b", BoxShape{Vec3(0.25, 0.04, 0.03)}, 2.0, Vec3(0.25, 0, 0.42),
                           Quaternion::fromAxisAngle(Vec3(0, 1, 1).normalized(), 0.3));
  const BodyId c = addBody(world, "c", BoxShape{Vec3(0.03, 0.2, 0.05)}, 1.2, Vec3(0.5, 0.2, 0.42));
  const BodyId d = addBody(world, "d", BoxShape{Vec3(0.04, 0.04, 0.1)}, 0.6, Vec3(0.5, 0.42, 0.35));
  addJoint(world, hinge("j1", BodyId{}, a, Vec3(0, 0, 0), Vec3::UnitZ()));
  addJoint(world, hinge("j2", a, b, Vec3(0, 0, 0.42), Vec3::UnitY()));
  addJoint(world, hinge("j3", b, c, Vec3(0.5, 0, 0.42), Vec3(1, 0.3, 0.2).normalized()));
  addJoint(world, hinge("j4", c, d, Vec3(0.5, 0.42, 0.42), Vec3(0, 0.2, -1).normalized()));
  EXPECT_TRUE(world.setJointEffort(world.findJoint("j1"), 0.8).ok());
  for (int k = 0; k < static_cast<int>(std::lround(0.5 / dt)); ++k) world.step();
  std::vector<Vec3> centres;
  for (const BodyId id : {a, b, c, d}) centres.push_back(world.body(id).position());
  return centres;
}

TEST(JointPendulums, ASpatialArmTumblingIn3DConvergesAtSecondOrder) {
  const std::vector<Vec3> reference = spatialArmAfterHalfASecond(1e-3 / 32);
  double errors[3];
  int k = 0;
  for (const double dt : {1e-3, 5e-4, 2.5e-4}) {
    const std::vector<Vec3> centres = spatialArmAfterHalfASecond(dt);
    double worst = 0.0;
    for (std::size_t i = 0; i < centres.size(); ++i) worst = std::max(worst, (centres[i] - reference[i]).norm());
    errors[k++] = worst;
  }
  std::printf("spatial arm after 0.5 s: centres of mass off by %.3g m (1 ms), %.3g (0.5 ms), %.3g (0.25 ms)\n", errors[0],
              errors[1], errors[2]);
  EXPECT_LT(errors[0], 2e-5) << "m at dt = 1 ms";
  EXPECT_GT(errors[0] / errors[1], 3.6) << "second order from 1 to 0.5 ms";
  EXPECT_GT(errors[1] / errors[2], 3.6) << "second order from 0.5 to 0.25 ms";
}

}  // namespace
}  // namespace rbsim
