// Random rays against random convex solids, checked by the library's
// signed distance (GJK apart, libccd overlapping), which knows nothing of
// rays: a hit point lies on the surface with the normal pointing out of it
// (the point moved out along the normal by ε is ε away), and no point of
// the ray before the hit is inside the solid. A miss leaves the whole ray
// outside.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "physics/collision/signed_distance.h"
#include "physics/query/ray_shapes.h"
#include "unit/collision/geometry_test_helpers.h"

namespace rbsim {
namespace {

ConvexGeometry randomGeometry(scenes::SceneRandom& random, int kind) {
  switch (kind) {
    case 0: return SphereShape{random.uniform(0.2, 1.5)};
    case 1: return BoxShape{Vec3(random.uniform(0.1, 1.5), random.uniform(0.1, 1.5), random.uniform(0.1, 1.5))};
    case 2: return CylinderShape{random.uniform(0.1, 1.0), random.uniform(0.1, 1.5)};
    case 3: return CapsuleShape{random.uniform(0.1, 1.0), random.uniform(0.0, 1.5)};
    default: return testing::hullOf(testing::randomPoints(random, 12, Vec3(1.2, 0.8, 0.5)));
  }
}

// The signed distance (m) of a world point from the placed solid.
double signedDistanceOf(const Vec3& point, const testing::Solid& solid) {
  static const ConvexGeometry dot = SphereShape{1e-9};
  const PlacedConvex probe{&dot, Transform::fromPose(point, Quaternion::identity())};
  return signedDistance(solid.placed(), probe).distance + 1e-9;
}

TEST(RayCrossCheck, HitsLieOnTheSurfaceAndNothingBeforeThemIsInside) {
  scenes::SceneRandom random(0x7A75);
  int hits = 0, misses = 0, insides = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int kind = trial % 5;
    const testing::Solid solid =
        testing::makeSolid(randomGeometry(random, kind),
                           Vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)),
                           random.rotation());
    const double size = geometrySize(*solid.geometry);
    // From a point around the solid (now and then inside it) towards a
    // point near it, so that about half the rays hit.
    const Vec3 from = solid.pose.translation + testing::randomUnit(random) * random.uniform(0.0, 4.0 * size);
    const Vec3 aim = solid.pose.translation + testing::randomUnit(random) * random.uniform(0.0, 1.5 * size);
    const Vec3 delta = (aim - from).normalized() * random.uniform(0.5, 8.0) * size;
    const Vec3 localOrigin = solid.pose.applyInverse(from);
    const Vec3 localDelta = solid.pose.inverseRotate(delta);
    const std::optional<RayEntry> hit = firstEntry(convexSpan(*solid.geometry, localOrigin, localDelta), 1.0);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " kind " << kind);
    if (hit && hit->inside) {
      ++insides;
      EXPECT_LE(signedDistanceOf(from, solid), 1e-9 * size);
      continue;
    }
    const double end = hit ? hit->fraction : 1.0;
    // Before the hit (or along the whole ray), nothing is inside.
    for (int k = 0; k < 16; ++k) {
      const Vec3 point = from + (end * k / 16.0) * delta;
      ASSERT_GT(signedDistanceOf(point, solid), -1e-9 * size) << "sample " << k;
    }
    if (!hit) {
      ++misses;
      ASSERT_GT(signedDistanceOf(from + delta, solid), -1e-9 * size);
      continue;
    }
    ++hits;
    const Vec3 point = from + hit->fraction * delta;
    const Vec3 normal = solid.pose.rotate(hit->normal);
    EXPECT_NEAR(normal.norm(), 1.0, 1e-12);
    // On the surface: out along the normal by ε is ε away (GJK, apart),
    // and the normal faces the ray.
    const double epsilon = 1e-3 * size;
    EXPECT_NEAR(signedDistanceOf(point + epsilon * normal, solid), epsilon, 1e-9 * size);
    EXPECT_LE(normal.dot(delta), 0.0);
  }
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 300);
  EXPECT_GT(insides, 50);
}

}  // namespace
}  // namespace rbsim
