// Signed distance when overlapping: penetration depth, normal (from A to B)
// and witness points against closed forms and against separating axes, with
// the libccd failure cases of danfis/libccd#25 and #17.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry_test_helpers.h"
#include "physics/collision/ccd_support.h"
#include "physics/collision/signed_distance.h"

namespace rbsim {
namespace {

using testing::makeSolid;
using testing::randomUnit;
using testing::Solid;

void expectVecNear(const Vec3& actual, const Vec3& expected, double tol) {
  EXPECT_LE((actual - expected).norm(), tol)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

// Invariant of every answer: pointB − pointA = distance × normal, unit normal.
void expectConsistent(const SignedDistance& r) {
  EXPECT_TRUE(std::isfinite(r.distance));
  EXPECT_NEAR(r.normal.norm(), 1.0, 1e-12);
  expectVecNear(r.pointB - r.pointA, r.distance * r.normal, 1e-9);
}

TEST(SignedDistance, LibccdDirectionIsConvertedToAToB) {
  // B to the +x side of A: B must move along +x, whichever method answers.
  const Solid a = makeSolid(BoxShape{Vec3::Constant(0.5)}, Vec3::Zero());
  const Solid b = makeSolid(BoxShape{Vec3::Constant(0.5)}, Vec3(0.8, 0.1, -0.05));
  const Penetration ab = penetration(a.placed(), b.placed());
  const Penetration ba = penetration(b.placed(), a.placed());
  EXPECT_NE(ab.method, PenetrationMethod::SupportEstimate);
  expectVecNear(ab.normal, Vec3::UnitX(), 1e-9);
  expectVecNear(ba.normal, -Vec3::UnitX(), 1e-9);
  EXPECT_NEAR(ab.depth, 0.2, 1e-9);
  EXPECT_NEAR(ba.depth, 0.2, 1e-9);
  // Moving B by depth × normal leaves the boxes just touching.
  const Solid moved =
      makeSolid(BoxShape{Vec3::Constant(0.5)}, b.pose.translation + ab.depth * ab.normal);
  EXPECT_NEAR(signedDistance(a.placed(), moved.placed()).distance, 0.0, 1e-9);
}

TEST(SignedDistance, OverlappingSpheres) {
  scenes::SceneRandom random(1);
  for (int i = 0; i < 50; ++i) {
    const Vec3 ca(random.uniform(-3, 3), random.uniform(-3, 3), random.uniform(-3, 3));
    const Vec3 cb = ca + randomUnit(random) * random.uniform(0.01, 1.2);
    const SignedDistance r = signedDistance(makeSolid(SphereShape{0.5}, ca).placed(),
                                            makeSolid(SphereShape{0.75}, cb).placed());
    EXPECT_NEAR(r.distance, (cb - ca).norm() - 1.25, 1e-12);
    expectVecNear(r.normal, (cb - ca).normalized(), 1e-9);
    expectVecNear(r.pointA, ca + 0.5 * r.normal, 1e-12);
    expectVecNear(r.pointB, cb - 0.75 * r.normal, 1e-12);
  }
  // Concentric: the depth is the sum of the radii, in some direction.
  const SignedDistance r = signedDistance(makeSolid(SphereShape{0.5}, Vec3(1, 1, 1)).placed(),
                                          makeSolid(SphereShape{0.75}, Vec3(1, 1, 1)).placed());
  EXPECT_NEAR(r.distance, -1.25, 1e-12);
  expectConsistent(r);
}

TEST(SignedDistance, AxisAlignedBoxOverlapIsTheSmallestAxisOverlap) {
  scenes::SceneRandom random(2);
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 ha(random.uniform(0.2, 1), random.uniform(0.2, 1), random.uniform(0.2, 1));
    const Vec3 hb(random.uniform(0.2, 1), random.uniform(0.2, 1), random.uniform(0.2, 1));
    const Vec3 delta(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
    const Vec3 overlap = ha + hb - delta.cwiseAbs();
    if (overlap.minCoeff() <= 1e-3) continue;
    // A unique smallest overlap, so that the normal is determined.
    Vec3 sorted = overlap;
    std::sort(sorted.data(), sorted.data() + 3);
    if (sorted[1] - sorted[0] < 1e-3) continue;
    int axis = 0;
    const double depth = overlap.minCoeff(&axis);
    const Vec3 normal = (delta[axis] >= 0 ? 1.0 : -1.0) * Vec3::Unit(axis);
    const Vec3 base(0.5, -1.0, 2.0);
    const SignedDistance r = signedDistance(makeSolid(BoxShape{ha}, base).placed(),
                                            makeSolid(BoxShape{hb}, base + delta).placed());
    ++checked;
    EXPECT_NEAR(r.distance, -depth, 1e-9) << i;
    expectVecNear(r.normal, normal, 1e-9);
    expectConsistent(r);
  }
  EXPECT_GT(checked, 50);
}

TEST(SignedDistance, RandomPolytopeOverlapMatchesSeparatingAxes) {
  scenes::SceneRandom random(3);
  int checked = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const auto hullA =
        testing::hullOf(testing::randomPoints(random, 6 + trial % 11, Vec3(1.0, 0.7, 0.5)));
    const auto hullB =
        testing::hullOf(testing::randomPoints(random, 6 + trial % 13, Vec3(0.6, 0.9, 0.4)));
    const Solid a = makeSolid(hullA, Vec3::Zero(), random.rotation());
    const Solid b =
        makeSolid(hullB, randomUnit(random) * random.uniform(0.0, 0.8), random.rotation());
    const auto va = testing::worldVertices(*hullA, a.pose);
    const auto vb = testing::worldVertices(*hullB, b.pose);
    const auto sat = testing::satDepth(va, *hullA, a.pose, vb, *hullB, b.pose);
    if (sat.depth < 1e-3) continue;
    ++checked;
    const SignedDistance r = signedDistance(a.placed(), b.placed());
    EXPECT_NEAR(r.distance, -sat.depth, 1e-9) << "trial " << trial;
    expectConsistent(r);
  }
  EXPECT_GT(checked, 80);
}

TEST(SignedDistance, FaceToFaceStackedCubesGiveAFiniteVerticalNormal) {
  // danfis/libccd#25: GJK+EPA returns a NaN direction for two cubes stacked
  // face to face; the answer must still be +z with the overlap as depth.
  const Solid bottom = makeSolid(BoxShape{Vec3::Constant(0.5)}, Vec3::Zero());
  for (const Vec3& lateral : {Vec3(0, 0, 0), Vec3(0.3, -0.2, 0)}) {
    for (double overlap : {0.1, 1e-3, 1e-6, 0.0}) {
      const Solid top =
          makeSolid(BoxShape{Vec3::Constant(0.5)}, lateral + Vec3(0, 0, 1.0 - overlap));
      const SignedDistance r = signedDistance(bottom.placed(), top.placed());
      SCOPED_TRACE(::testing::Message()
                   << "overlap " << overlap << " lateral " << lateral.transpose());
      expectConsistent(r);
      expectVecNear(r.normal, Vec3::UnitZ(), 1e-9);
      EXPECT_NEAR(r.distance, -overlap, 1e-9);
      // The witness sits over the shared square, on the touching faces.
      EXPECT_NEAR(r.pointA.z(), 0.5, 1e-9);
      EXPECT_LE((r.pointA.head<2>() - lateral.head<2>() / 2).cwiseAbs().maxCoeff(),
                0.5 - 0.15 + 1e-9);
      const SignedDistance flipped = signedDistance(top.placed(), bottom.placed());
      expectVecNear(flipped.normal, -Vec3::UnitZ(), 1e-9);
      EXPECT_NEAR(flipped.distance, -overlap, 1e-9);
    }
  }
}

TEST(SignedDistance, SmallBoxDeepInABigBoxGivesASanePoint) {
  // danfis/libccd#17: EPA's contact point is poor when the sizes differ a lot.
  const Vec3 bigHalf = Vec3::Constant(5.0);
  const Vec3 smallHalf = Vec3::Constant(0.1);
  const Vec3 smallCenter(1.0, 2.0, 0.5);
  const Solid big = makeSolid(BoxShape{bigHalf}, Vec3::Zero());
  const Solid small = makeSolid(BoxShape{smallHalf}, smallCenter);
  const SignedDistance r = signedDistance(big.placed(), small.placed());
  expectConsistent(r);
  // The nearest way out is +y: 5 + 0.1 − 2.
  EXPECT_NEAR(r.distance, -3.1, 1e-9);
  expectVecNear(r.normal, Vec3::UnitY(), 1e-9);
  // pointB on the small box (its −y face), pointA on the big box's +y face,
  // both right over the small box.
  EXPECT_NEAR(r.pointB.y(), 1.9, 1e-9);
  EXPECT_NEAR(r.pointA.y(), 5.0, 1e-9);
  for (const Vec3& p : {r.pointA, r.pointB}) {
    EXPECT_NEAR(p.x(), 1.0, 0.1 + 1e-6);
    EXPECT_NEAR(p.z(), 0.5, 0.1 + 1e-6);
  }
}

TEST(SignedDistance, CrossingCapsulesAndDeepSphereInBox) {
  // Capsule axes that cross: depth rA + rB along the common normal.
  const Solid a = makeSolid(CapsuleShape{0.2, 1.0}, Vec3::Zero(),
                            Quaternion::fromAxisAngle(Vec3::UnitY(), M_PI / 2));
  const Solid b = makeSolid(CapsuleShape{0.3, 1.0}, Vec3(0.1, -0.2, 0.0),
                            Quaternion::fromAxisAngle(Vec3::UnitX(), M_PI / 2));
  const SignedDistance capsules = signedDistance(a.placed(), b.placed());
  EXPECT_NEAR(capsules.distance, -0.5, 1e-12);
  EXPECT_NEAR(std::abs(capsules.normal.z()), 1.0, 1e-12);
  expectConsistent(capsules);

  // A sphere whose centre is inside a box: depth r + distance to the nearest face.
  const Solid box = makeSolid(BoxShape{Vec3(1, 1, 0.5)}, Vec3::Zero());
  const Solid sphere = makeSolid(SphereShape{0.2}, Vec3(0.3, -0.1, 0.35));
  const SignedDistance deep = signedDistance(box.placed(), sphere.placed());
  EXPECT_NEAR(deep.distance, -(0.2 + 0.15), 1e-9);
  expectVecNear(deep.normal, Vec3::UnitZ(), 1e-9);
  expectConsistent(deep);
}

TEST(SignedDistance, OverlappingCylinders) {
  // Stacked coaxially: the caps overlap by 0.05 along z.
  const Solid a = makeSolid(CylinderShape{0.5, 1.0}, Vec3::Zero());
  const Solid b = makeSolid(CylinderShape{0.4, 0.5}, Vec3(0.05, 0.0, 1.45));
  const SignedDistance stacked = signedDistance(a.placed(), b.placed());
  EXPECT_NEAR(stacked.distance, -0.05, 1e-9);
  expectVecNear(stacked.normal, Vec3::UnitZ(), 1e-9);
  // Side by side, parallel: overlap 0.1 across the axes.
  const Solid c = makeSolid(CylinderShape{0.5, 1.0}, Vec3(0.9 * 0.6, 0.9 * 0.8, 0.1));
  const SignedDistance side = signedDistance(a.placed(), c.placed());
  // Curved: the depth is within EPA's tolerance (1e-6 × size); the normal,
  // on which the depth depends only to second order, within about its root.
  EXPECT_NEAR(side.distance, -0.1, 2e-6);
  expectVecNear(side.normal, Vec3(0.6, 0.8, 0), 5e-3);
  expectConsistent(side);
}

TEST(SignedDistance, LyingCylindersSideBySideOverlapByTheirGap) {
  // Regression: libccd's EPA reported success with a depth of 1.199 m along
  // -x for this pose; two parallel cylinders 0.599 m apart (radii 0.3)
  // overlap by 0.001 m along the line joining their axes.
  const Quaternion lying = Quaternion::fromAxisAngle(Vec3::UnitX(), M_PI / 2);  // axis along y
  const Solid a = makeSolid(CylinderShape{0.3, 0.5}, Vec3::Zero(), lying);
  const Solid b = makeSolid(CylinderShape{0.3, 0.5}, Vec3(0.599, 0.2, 0.0), lying);
  const SignedDistance d = signedDistance(a.placed(), b.placed());
  EXPECT_NEAR(d.distance, -0.001, 1e-6);
  expectVecNear(d.normal, Vec3::UnitX(), 5e-3);
  const SignedDistance reversed = signedDistance(b.placed(), a.placed());
  EXPECT_NEAR(reversed.distance, -0.001, 1e-6);
  expectVecNear(reversed.normal, -Vec3::UnitX(), 5e-3);
}

TEST(SignedDistance, TolerancesAtRoundingLevelStillTerminate) {
  // With EPA's tolerance at the level of rounding, libccd 2.1's EPA loop
  // never ends on two boxes face to face; the support budget must end it,
  // and the answer must still be right (from MPR or the axis estimate).
  const PenetrationSettings tight{64, 1e-15};
  for (const Vec3& offset : {Vec3(0.2, 0.1, 0.9), Vec3(0.0, 0.0, 0.95), Vec3(0.9, 0.05, 0.0)}) {
    const Solid a = makeSolid(BoxShape{Vec3::Constant(0.5)}, Vec3::Zero());
    const Solid b = makeSolid(BoxShape{Vec3::Constant(0.5)}, offset);
    const Penetration p = penetration(a.placed(), b.placed(), tight);
    int axis = 0;
    const double depth = (Vec3::Ones() - offset.cwiseAbs()).minCoeff(&axis);
    EXPECT_NEAR(p.depth, depth, 1e-9);
    expectVecNear(p.normal, Vec3::Unit(axis), 1e-9);
  }
  const Solid c = makeSolid(CylinderShape{0.5, 1.0}, Vec3::Zero());
  const Solid d = makeSolid(CylinderShape{0.5, 1.0}, Vec3(0.3, 0.2, 1.9),
                            Quaternion::fromRollPitchYaw(0.1, 0.2, 0.3));
  const Penetration p = penetration(c.placed(), d.placed(), tight);
  EXPECT_TRUE(std::isfinite(p.depth));
  EXPECT_GT(p.depth, 0.0);
}

TEST(SignedDistance, SignChangesContinuouslyThroughContact) {
  // A rotated box sliding down onto a hull, through first contact.
  scenes::SceneRandom random(8);
  const auto hull = testing::hullOf(testing::randomPoints(random, 30, Vec3(1, 1, 0.5)));
  const Solid base = makeSolid(hull, Vec3::Zero(), random.rotation());
  const Quaternion q = random.rotation();
  double previous = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 36; ++i) {
    const Solid box = makeSolid(BoxShape{Vec3(0.3, 0.2, 0.1)}, Vec3(0.1, 0.05, 2.0 - 0.05 * i), q);
    const SignedDistance r = signedDistance(base.placed(), box.placed());
    expectConsistent(r);
    EXPECT_LT(r.distance, previous + 1e-9) << "step " << i;  // deeper as it descends
    if (i > 0) {
      EXPECT_LT(previous - r.distance, 0.05 + 1e-9) << "no jump larger than the step";
    }
    previous = r.distance;
  }
  EXPECT_LT(previous, 0.0);
}

}  // namespace
}  // namespace rbsim

namespace rbsim {
namespace {

// Found by tests/fuzz/fuzz_checkpoint (regressions/checkpoint/
// nan_pose_crashes_libccd): a body restored with a momentum of 1e300 had a
// NaN pose after one step, and libccd's EPA dereferenced a null pointer on
// it. Non-finite poses, and pieces beyond libccd's range, skip libccd.
TEST(Penetration, NonFiniteOrFarOutPosesGiveAnAnswerNotACrash) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Solid box = makeSolid(BoxShape{Vec3::Constant(0.5)}, Vec3::Zero());
  const Solid lost = makeSolid(SphereShape{0.5}, Vec3(nan, 0.0, 0.0));
  const Penetration p = penetration(box.placed(), lost.placed());
  EXPECT_FALSE(std::isfinite(p.depth) && p.normal.allFinite() && p.pointA.allFinite())
      << "no meaningful answer exists for a NaN pose, but there must be one without a crash";
  for (const double far : {1e60, 1e200, 1e298}) {
    const Solid c = makeSolid(SphereShape{0.5}, Vec3(far, far, far));
    const Solid d = makeSolid(SphereShape{0.5}, Vec3(far, far, far));
    EXPECT_EQ(penetration(c.placed(), d.placed()).method, PenetrationMethod::SupportEstimate) << far;
  }
}

}  // namespace
}  // namespace rbsim
