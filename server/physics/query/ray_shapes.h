#pragma once
// Where a line crosses each convex solid of the collision layer, in the
// solid's own frame (centred at its origin; cylinder and capsule along z),
// and the first hit of a ray that follows the line.
//
// Each routine gives the span of the line origin + t direction (t over all
// reals; direction need not be unit, so t is a fraction of it) inside the
// closed solid: the t where the line enters and leaves, and the outward
// unit normal where it enters. Solids are convex, so the span is one
// interval. Closed: a line that only touches the surface (a tangent, a ray
// along a face) has a span, of one point or along the face.
//
// Sources: Ericson, "Real-Time Collision Detection" (2005), 5.3.2 (ray and
// sphere), 5.3.3 (slabs: ray and box), 5.3.7 (ray and cylinder, capsules
// as a cylinder and two spheres), 5.3.8 (ray and convex polyhedron: clipping
// against the faces' half-spaces, Cyrus and Beck 1978); Haines, Günther and
// Akenine-Möller, "Precision improvements for ray/sphere intersection",
// Ray Tracing Gems (2019), for the sphere's well-conditioned roots.

#include <limits>
#include <optional>

#include "physics/collision/convex_geometry.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct RaySpan {
  double enter = std::numeric_limits<double>::infinity();   // empty until set
  double exit = -std::numeric_limits<double>::infinity();
  Vec3 normal = Vec3::Zero();  // unit, outward, where the line enters (zero if it never does)

  bool isEmpty() const { return !(enter <= exit); }
  static RaySpan everywhere() {
    const double inf = std::numeric_limits<double>::infinity();
    return {-inf, inf, Vec3::Zero()};
  }
};

RaySpan sphereSpan(double radius, const Vec3& origin, const Vec3& direction);
RaySpan boxSpan(const Vec3& halfExtents, const Vec3& origin, const Vec3& direction);
RaySpan cylinderSpan(double radius, double halfLength, const Vec3& origin, const Vec3& direction);
RaySpan capsuleSpan(double radius, double halfLength, const Vec3& origin, const Vec3& direction);
RaySpan hullSpan(const ConvexHull& hull, const Vec3& origin, const Vec3& direction);
// The half-space normal · p <= offset (normal unit, out of the solid).
RaySpan halfSpaceSpan(const Vec3& normal, double offset, const Vec3& origin, const Vec3& direction);
RaySpan convexSpan(const ConvexGeometry& geometry, const Vec3& origin, const Vec3& direction);

// Where a ray along the line, t in [0, maxFraction], first meets the solid
// whose span is given. A ray that starts inside the closed solid (enter < 0
// <= exit, so also one that starts on the surface and leaves it) hits it at
// t = 0, with `inside` set: its normal is the caller's to choose (the
// queries give the ray's reversed direction, as Jolt does for a convex
// shape treated as solid). Nothing when the span ends before 0 or starts
// after maxFraction.
struct RayEntry {
  double fraction = 0.0;
  Vec3 normal = Vec3::Zero();  // the span's entry normal; zero when inside
  bool inside = false;
};
std::optional<RayEntry> firstEntry(const RaySpan& span, double maxFraction);

}  // namespace rbsim
