// Ray spans of each convex solid in its own frame (query/ray_shapes.h),
// against hit points and normals worked by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "unit/collision/geometry_test_helpers.h"
#include "physics/query/ray_shapes.h"

namespace rbsim {
namespace {

constexpr double kTol = 1e-12;

std::optional<RayEntry> cast(const ConvexGeometry& geometry, const Vec3& from, const Vec3& to) {
  return firstEntry(convexSpan(geometry, from, to - from), 1.0);
}

void expectHit(const std::optional<RayEntry>& hit, double fraction, const Vec3& normal) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_FALSE(hit->inside);
  EXPECT_NEAR(hit->fraction, fraction, kTol);
  EXPECT_NEAR((hit->normal - normal).norm(), 0.0, kTol) << hit->normal.transpose();
}

void expectInside(const std::optional<RayEntry>& hit) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_TRUE(hit->inside);
  EXPECT_EQ(hit->fraction, 0.0);
}

TEST(RayShapes, SphereAxisAlignedObliqueAndTangent) {
  const ConvexGeometry sphere = SphereShape{1.0};
  expectHit(cast(sphere, {-5, 0, 0}, {5, 0, 0}), 0.4, {-1, 0, 0});
  // The chord at y = 0.6 meets the unit circle at x = ±0.8.
  expectHit(cast(sphere, {-2, 0.6, 0}, {2, 0.6, 0}), 0.3, {-0.8, 0.6, 0});
  // Along the diagonal from (3, 3, 3)/√3 · 2: the surface at 1, half way.
  const Vec3 corner = Vec3(1, 1, 1).normalized();
  expectHit(cast(sphere, 3 * corner, -corner), 0.5, corner);
  // A tangent touches (the solid is closed); just beside it misses.
  expectHit(cast(sphere, {-2, 1, 0}, {2, 1, 0}), 0.5, {0, 1, 0});
  EXPECT_FALSE(cast(sphere, {-2, 1 + 1e-9, 0}, {2, 1 + 1e-9, 0}));
  // Too short, pointing away, ending exactly on the surface.
  EXPECT_FALSE(cast(sphere, {-5, 0, 0}, {-2, 0, 0}));
  EXPECT_FALSE(cast(sphere, {2, 0, 0}, {5, 0, 0}));
  expectHit(cast(sphere, {-5, 0, 0}, {-1, 0, 0}), 1.0, {-1, 0, 0});
  expectInside(cast(sphere, {0.2, 0.1, 0}, {5, 0, 0}));
  expectInside(cast(sphere, {1, 0, 0}, {5, 0, 0}));  // on the surface, leaving: closed
}

TEST(RayShapes, BoxFacesParallelRaysAndInside) {
  const ConvexGeometry box = BoxShape{Vec3(1, 2, 3)};
  expectHit(cast(box, {-5, 0, 0}, {5, 0, 0}), 0.4, {-1, 0, 0});
  expectHit(cast(box, {0, 0, 9}, {0, 0, -9}), 1.0 / 3.0, {0, 0, 1});
  expectHit(cast(box, {0, -4, 0}, {0, 4, 0}), 0.25, {0, -1, 0});
  // Oblique: slabs x from t = 0.5, y from 0.25: the x face at (−1, −1, 0).
  expectHit(cast(box, {-3, -3, 0}, {1, 1, 0}), 0.5, {-1, 0, 0});
  // Parallel to the y faces: inside the slab it hits the x face, on the
  // face plane too (closed), just outside it misses.
  expectHit(cast(box, {-5, 1.5, 0.5}, {5, 1.5, 0.5}), 0.4, {-1, 0, 0});
  expectHit(cast(box, {-5, 2, 0}, {5, 2, 0}), 0.4, {-1, 0, 0});
  EXPECT_FALSE(cast(box, {-5, 2 + 1e-9, 0}, {5, 2 + 1e-9, 0}));
  EXPECT_FALSE(cast(box, {-5, 0, 0}, {-2, 0, 0}));
  expectInside(cast(box, {0.5, -1, 2}, {0, 7, 0}));
}

TEST(RayShapes, CylinderSideCapsAndAxisParallel) {
  const ConvexGeometry cylinder = CylinderShape{1.0, 2.0};
  expectHit(cast(cylinder, {-5, 0, 0}, {5, 0, 0}), 0.4, {-1, 0, 0});
  expectHit(cast(cylinder, {0, 0, 5}, {0, 0, -5}), 0.3, {0, 0, 1});
  expectHit(cast(cylinder, {0, 0, -5}, {0, 0, 5}), 0.3, {0, 0, -1});
  // Parallel to the axis: inside the radius it hits the cap, outside it misses.
  expectHit(cast(cylinder, {0.5, -0.5, 5}, {0.5, -0.5, -5}), 0.3, {0, 0, 1});
  EXPECT_FALSE(cast(cylinder, {1.5, 0, 5}, {1.5, 0, -5}));
  // x = −3 + 6t, z = 4 − 8t: the side at t = 1/3 (z = 4/3, within the
  // caps) after the cap plane z = 2 at t = 1/4 (x = −1.5, outside).
  expectHit(cast(cylinder, {-3, 0, 4}, {3, 0, -4}), 1.0 / 3.0, {-1, 0, 0});
  // Oblique in the xy plane: the chord at y = 0.6 enters at x = −0.8.
  expectHit(cast(cylinder, {-2, 0.6, 1}, {2, 0.6, 1}), 0.3, {-0.8, 0.6, 0});
  // Above the top cap, through the rim's plane: misses.
  EXPECT_FALSE(cast(cylinder, {-5, 0, 2 + 1e-9}, {5, 0, 2 + 1e-9}));
  expectHit(cast(cylinder, {-2, 1, 0}, {2, 1, 0}), 0.5, {0, 1, 0});  // tangent to the side
  expectInside(cast(cylinder, {0, 0.5, -1.5}, {3, 3, 3}));
}

TEST(RayShapes, CapsuleSideHemispheresAndAxisParallel) {
  const ConvexGeometry capsule = CapsuleShape{0.5, 1.0};
  expectHit(cast(capsule, {-5, 0, 0}, {5, 0, 0}), 0.45, {-1, 0, 0});
  expectHit(cast(capsule, {0, 0, 5}, {0, 0, -5}), 0.35, {0, 0, 1});
  expectHit(cast(capsule, {0, 0, -5}, {0, 0, 5}), 0.35, {0, 0, -1});
  // At z = 1.3, 0.3 above the top sphere's centre: x = −0.4 on it.
  expectHit(cast(capsule, {-5, 0, 1.3}, {5, 0, 1.3}), 0.46, {-0.8, 0, 0.6});
  // Parallel to the axis at x = 0.3: the top sphere at z = 1 + 0.4.
  expectHit(cast(capsule, {0.3, 0, 5}, {0.3, 0, -5}), 0.36, {0.6, 0, 0.8});
  EXPECT_FALSE(cast(capsule, {0.5 + 1e-9, 0, 5}, {0.5 + 1e-9, 0, -5}));
  expectInside(cast(capsule, {0, 0, 1.2}, {0, 0, 5}));
  // A capsule of zero half length is a sphere.
  expectHit(cast(CapsuleShape{0.5, 0.0}, {-5, 0, 0}, {5, 0, 0}), 0.45, {-1, 0, 0});
}

TEST(RayShapes, OctahedronHullFaces) {
  // |x| + |y| + |z| <= 1: faces ±x ±y ±z = 1, normals (±1, ±1, ±1)/√3.
  const ConvexGeometry octahedron = testing::hullOf(
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  // At y = 0.1, z = 0.2 from −x: −x + 0.3 = 1 at x = −0.7.
  expectHit(cast(octahedron, {-3, 0.1, 0.2}, {3, 0.1, 0.2}), 2.3 / 6.0, Vec3(-1, 1, 1).normalized());
  expectHit(cast(octahedron, {0.1, -0.2, 4}, {0.1, -0.2, -4}), 3.3 / 8.0, Vec3(1, -1, 1).normalized());
  // Parallel to the face x + y + z = 1: outside its plane it misses; in the
  // plane x + y + z = 0.9 it enters through the face x − y + z = 1 at
  // t = 0.475, at (0.4, −0.05, 0.55).
  EXPECT_FALSE(cast(octahedron, {2, 0, 0}, {2, 1, -1}));
  expectHit(cast(octahedron, {0.4, -1, 1.5}, {0.4, 1, -0.5}), 0.475, Vec3(1, -1, 1).normalized());
  expectInside(cast(octahedron, {0.1, 0.1, 0.1}, {3, 0, 0}));
  EXPECT_FALSE(cast(octahedron, {-3, 0.1, 0.2}, {-1, 0.1, 0.2}));
}

TEST(RayShapes, HalfSpace) {
  const Vec3 up = Vec3::UnitZ();
  expectHit(firstEntry(halfSpaceSpan(up, 0.0, {0, 0, 2}, {1, 0, -4}), 1.0), 0.5, up);
  EXPECT_FALSE(firstEntry(halfSpaceSpan(up, 0.0, {0, 0, 2}, {5, 0, 0}), 1.0));   // parallel, above
  EXPECT_FALSE(firstEntry(halfSpaceSpan(up, 0.0, {0, 0, 2}, {0, 0, 1}), 1.0));   // away
  EXPECT_FALSE(firstEntry(halfSpaceSpan(up, 0.0, {0, 0, 2}, {0, 0, -1}), 1.0));  // short
  expectInside(firstEntry(halfSpaceSpan(up, 0.0, {0, 0, -1}, {0, 0, 5}), 1.0));
  // A tilted plane: n = (0, 0.6, 0.8), offset 1.
  const Vec3 tilted(0, 0.6, 0.8);
  expectHit(firstEntry(halfSpaceSpan(tilted, 1.0, {0, 0, 5}, {0, 0, -10}), 1.0), 0.375, tilted);
}

}  // namespace
}  // namespace rbsim
