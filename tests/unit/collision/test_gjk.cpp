// GJK distance (signed-volumes sub-algorithm) against brute force over the
// features of random polytopes and against closed forms for primitives.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry_test_helpers.h"
#include "physics/collision/gjk.h"
#include "physics/collision/signed_distance.h"

namespace rbsim {
namespace {

using testing::makeSolid;
using testing::randomUnit;
using testing::Solid;

// GJK's closest points must be consistent with its distance and lie in the
// solids (checked through the support function: p is in a convex solid iff
// d·p <= h(d) for all d; we sample directions).
void expectWitnessesConsistent(const GjkResult& r, const Solid& a, const Solid& b, double tol) {
  EXPECT_NEAR((r.pointB - r.pointA).norm(), r.distance, tol);
  scenes::SceneRandom random(99);
  for (int i = 0; i < 64; ++i) {
    const Vec3 d = randomUnit(random);
    EXPECT_LE(d.dot(r.pointA), d.dot(a.placed().support(d)) + tol);
    EXPECT_LE(d.dot(r.pointB), d.dot(b.placed().support(d)) + tol);
  }
}

TEST(Gjk, RandomPolytopesMatchBruteForceDistance) {
  scenes::SceneRandom random(2024);
  int compared = 0;
  int overlapping = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const auto hullA =
        testing::hullOf(testing::randomPoints(random, 4 + trial % 17, Vec3(1.0, 0.7, 0.5)));
    const auto hullB =
        testing::hullOf(testing::randomPoints(random, 4 + (trial * 7) % 23, Vec3(0.6, 0.9, 0.4)));
    // Centres from touching range to well apart, in random directions.
    const Solid a =
        makeSolid(hullA, Vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)),
                  random.rotation());
    const Solid b =
        makeSolid(hullB, a.pose.translation + randomUnit(random) * random.uniform(0.5, 3.0),
                  random.rotation());
    const auto va = testing::worldVertices(*hullA, a.pose);
    const auto vb = testing::worldVertices(*hullB, b.pose);
    const double separation = -testing::satDepth(va, *hullA, a.pose, vb, *hullB, b.pose).depth;
    const GjkResult r = gjkDistance(a.placed(), b.placed());
    EXPECT_TRUE(r.converged);
    if (separation > 1e-6) {
      ++compared;
      const double expected = testing::bruteForcePolytopeDistance(*hullA, a.pose, *hullB, b.pose);
      ASSERT_FALSE(r.overlap) << "trial " << trial;
      EXPECT_NEAR(r.distance, expected, 1e-9) << "trial " << trial;
      expectWitnessesConsistent(r, a, b, 1e-9);
    } else if (separation < -1e-6) {
      ++overlapping;
      EXPECT_TRUE(r.overlap) << "trial " << trial;
    }
  }
  // The sampling must exercise both outcomes.
  EXPECT_GT(compared, 100);
  EXPECT_GT(overlapping, 20);
}

TEST(Gjk, SphereSphereIsCentreDistanceMinusRadii) {
  scenes::SceneRandom random(1);
  for (int i = 0; i < 50; ++i) {
    const Vec3 ca(random.uniform(-3, 3), random.uniform(-3, 3), random.uniform(-3, 3));
    const Vec3 cb = ca + randomUnit(random) * random.uniform(1.3, 5.0);
    const Solid a = makeSolid(SphereShape{0.5}, ca, random.rotation());
    const Solid b = makeSolid(SphereShape{0.75}, cb, random.rotation());
    const SignedDistance r = signedDistance(a.placed(), b.placed());
    const Vec3 n = (cb - ca).normalized();
    EXPECT_NEAR(r.distance, (cb - ca).norm() - 1.25, 1e-12);
    EXPECT_NEAR((r.normal - n).norm(), 0.0, 1e-12);
    EXPECT_NEAR((r.pointA - (ca + 0.5 * n)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((r.pointB - (cb - 0.75 * n)).norm(), 0.0, 1e-12);
  }
}

TEST(Gjk, SphereBoxIsDistanceToTheClampedPoint) {
  scenes::SceneRandom random(2);
  const Vec3 half(0.5, 1.0, 0.25);
  const Solid box = makeSolid(BoxShape{half}, Vec3::Zero());
  for (int i = 0; i < 100; ++i) {
    const Vec3 c = randomUnit(random).cwiseProduct(Vec3(3, 4, 2));
    const Vec3 closest = c.cwiseMax(-half).cwiseMin(half);
    const double radius = 0.2;
    const double expected = (c - closest).norm() - radius;
    if ((c - closest).norm() < 0.3) continue;  // keep the centre clearly outside
    const Solid sphere = makeSolid(SphereShape{radius}, c);
    const SignedDistance r = signedDistance(box.placed(), sphere.placed());
    EXPECT_NEAR(r.distance, expected, 1e-9) << c.transpose();
    EXPECT_NEAR((r.pointA - closest).norm(), 0.0, 1e-9);
  }
}

TEST(Gjk, AxisAlignedSeparatedBoxes) {
  scenes::SceneRandom random(3);
  for (int i = 0; i < 100; ++i) {
    const Vec3 ha(random.uniform(0.1, 1), random.uniform(0.1, 1), random.uniform(0.1, 1));
    const Vec3 hb(random.uniform(0.1, 1), random.uniform(0.1, 1), random.uniform(0.1, 1));
    const Vec3 delta(random.uniform(-3, 3), random.uniform(-3, 3), random.uniform(-3, 3));
    // Per-axis gaps; the boxes are apart iff one is positive, and then the
    // distance is the norm of the positive ones.
    const Vec3 gap = (delta.cwiseAbs() - ha - hb).cwiseMax(0.0);
    if (gap.maxCoeff() < 1e-3) continue;
    const Solid a = makeSolid(BoxShape{ha}, Vec3(0.3, -0.2, 0.1));
    const Solid b = makeSolid(BoxShape{hb}, Vec3(0.3, -0.2, 0.1) + delta);
    const GjkResult r = gjkDistance(a.placed(), b.placed());
    EXPECT_NEAR(r.distance, gap.norm(), 1e-12);
    expectWitnessesConsistent(r, a, b, 1e-12);
  }
}

TEST(Gjk, CapsuleCapsuleIsSegmentDistanceMinusRadii) {
  scenes::SceneRandom random(4);
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    const CapsuleShape ca{0.2, random.uniform(0.0, 1.0)};
    const CapsuleShape cb{0.3, random.uniform(0.1, 1.5)};
    const Solid a = makeSolid(ca, Vec3(random.uniform(-1, 1), 0, 0), random.rotation());
    const Solid b =
        makeSolid(cb, Vec3(random.uniform(-1, 1), random.uniform(-2, 2), random.uniform(-2, 2)),
                  random.rotation());
    const Vec3 a0 = a.pose.apply(Vec3(0, 0, -ca.halfLength)),
               a1 = a.pose.apply(Vec3(0, 0, ca.halfLength));
    const Vec3 b0 = b.pose.apply(Vec3(0, 0, -cb.halfLength)),
               b1 = b.pose.apply(Vec3(0, 0, cb.halfLength));
    const double segment = testing::segmentSegmentDistance(a0, a1, b0, b1);
    if (segment < 1e-6) continue;  // crossing axes: tested with penetration
    ++checked;
    const SignedDistance r = signedDistance(a.placed(), b.placed());
    EXPECT_NEAR(r.distance, segment - 0.5, 1e-9);  // negative when they overlap: still exact
    EXPECT_NEAR((r.pointB - r.pointA).dot(r.normal), r.distance, 1e-12);
  }
  EXPECT_GT(checked, 150);
}

TEST(Gjk, CylinderClosedForms) {
  const Solid cylinder = makeSolid(CylinderShape{0.5, 1.0}, Vec3(1, 2, 3));
  const auto sphereAt = [](const Vec3& c) { return makeSolid(SphereShape{0.25}, c); };
  // Above the cap, beside the side, and off the rim (distance to the circle).
  EXPECT_NEAR(signedDistance(cylinder.placed(), sphereAt(Vec3(1.2, 2.1, 5)).placed()).distance,
              2 - 1 - 0.25, 1e-9);
  EXPECT_NEAR(signedDistance(cylinder.placed(), sphereAt(Vec3(3, 2, 3.5)).placed()).distance,
              2 - 0.5 - 0.25, 1e-9);
  const double rim = std::hypot(std::hypot(1.0, 1.0) - 0.5, 0.5);
  EXPECT_NEAR(signedDistance(cylinder.placed(), sphereAt(Vec3(2, 3, 4.5)).placed()).distance,
              rim - 0.25, 1e-9);
  // Two parallel cylinders side by side, and a box under the bottom cap.
  const Solid other = makeSolid(CylinderShape{0.5, 1.0}, Vec3(1 + 0.6 * 3, 2 + 0.8 * 3, 3.3));
  EXPECT_NEAR(gjkDistance(cylinder.placed(), other.placed()).distance, 3 - 1.0, 1e-9);
  const Solid box = makeSolid(BoxShape{Vec3(2, 2, 0.5)}, Vec3(1.5, 2, 3 - 1 - 0.5 - 0.125));
  EXPECT_NEAR(gjkDistance(cylinder.placed(), box.placed()).distance, 0.125, 1e-12);
  // A tilted cylinder over a box: the lowest rim point is at
  // z = c − h cos θ − R sin θ.
  const double tilt = 0.4;
  const Solid tilted = makeSolid(CylinderShape{0.5, 1.0}, Vec3(0, 0, 3),
                                 Quaternion::fromAxisAngle(Vec3::UnitX(), tilt));
  const Solid floor = makeSolid(BoxShape{Vec3(5, 5, 1)}, Vec3(0, 0, -1));
  EXPECT_NEAR(gjkDistance(tilted.placed(), floor.placed()).distance,
              3 - std::cos(tilt) - 0.5 * std::sin(tilt), 1e-9);
}

TEST(Gjk, DistanceIsSymmetricAndClosestPointsSwap) {
  scenes::SceneRandom random(5);
  const auto hull = testing::hullOf(testing::randomPoints(random, 25, Vec3(0.8, 0.5, 0.6)));
  const std::vector<ConvexGeometry> shapes = {SphereShape{0.4}, BoxShape{Vec3(0.3, 0.6, 0.2)},
                                              CapsuleShape{0.2, 0.5}, CylinderShape{0.3, 0.4},
                                              hull};
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    for (std::size_t j = 0; j < shapes.size(); ++j) {
      for (int k = 0; k < 10; ++k) {
        const Solid a = makeSolid(shapes[i], Vec3::Zero(), random.rotation());
        const Solid b =
            makeSolid(shapes[j], randomUnit(random) * random.uniform(1.6, 3.0), random.rotation());
        const SignedDistance ab = signedDistance(a.placed(), b.placed());
        const SignedDistance ba = signedDistance(b.placed(), a.placed());
        ASSERT_GT(ab.distance, 0.0);
        EXPECT_NEAR(ab.distance, ba.distance, 1e-9) << i << " " << j;
        EXPECT_NEAR((ab.pointA - ba.pointB).norm(), 0.0, 1e-6) << i << " " << j;
        EXPECT_NEAR((ab.pointB - ba.pointA).norm(), 0.0, 1e-6) << i << " " << j;
        EXPECT_NEAR((ab.normal + ba.normal).norm(), 0.0, 1e-6);
      }
    }
  }
}

TEST(Gjk, DegenerateAndDuplicateSupportPointsTerminate) {
  // Box against box face to face: many support ties; a thin box and a
  // point-like sphere core; a far-away pair (large coordinates).
  const Solid a = makeSolid(BoxShape{Vec3::Constant(0.5)}, Vec3::Zero());
  const Solid b = makeSolid(BoxShape{Vec3::Constant(0.5)}, Vec3(0, 0, 1.5));
  GjkResult r = gjkDistance(a.placed(), b.placed());
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.distance, 0.5, 1e-12);
  EXPECT_LT(r.iterations, 10);

  const Solid flat = makeSolid(BoxShape{Vec3(1, 1, 1e-9)}, Vec3::Zero());
  const Solid point = makeSolid(SphereShape{1e-3}, Vec3(0.2, 0.3, 0.7));
  EXPECT_NEAR(signedDistance(flat.placed(), point.placed()).distance, 0.7 - 1e-9 - 1e-3, 1e-12);

  const Vec3 far(1e5, -2e5, 3e4);
  const Solid farA = makeSolid(BoxShape{Vec3::Constant(0.5)}, far);
  const Solid farB = makeSolid(BoxShape{Vec3::Constant(0.5)}, far + Vec3(1.25, 0, 0));
  r = gjkDistance(farA.placed(), farB.placed());
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.distance, 0.25, 1e-9);
}

TEST(Gjk, IterationCapIsReported) {
  const Solid a = makeSolid(CylinderShape{0.5, 1.0}, Vec3::Zero());
  const Solid b = makeSolid(CylinderShape{0.5, 1.0}, Vec3(1.3, 0.4, 2.3),
                            Quaternion::fromRollPitchYaw(0.3, 0.2, 0.1));
  const GjkResult capped =
      gjkDistance(a.placed(), b.placed(), GjkShapes::Full, GjkSettings{2, 1e-12});
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.iterations, 2);
  const GjkResult full = gjkDistance(a.placed(), b.placed());
  EXPECT_TRUE(full.converged);
  EXPECT_GE(capped.distance, full.distance - 1e-12) << "the capped result is an upper bound";
}

}  // namespace
}  // namespace rbsim
