#include "physics/query/convex_sweep.h"

#include "physics/collision/gjk.h"

namespace rbsim {

namespace {

// Advances before giving up: a face is reached in one or two, a curved
// surface in a handful (Newton's quadratic convergence).
constexpr int kMaxAdvances = 32;

Vec3 reversedUnit(const Vec3& delta) {
  const double length = delta.norm();
  return length > 0.0 ? Vec3(-delta / length) : Vec3::Zero();
}

}  // namespace

std::optional<SweepContact> sweepAgainstConvex(const ConvexGeometry& moving, const Transform& start,
                                               const Vec3& delta, const PlacedConvex& target,
                                               double maxFraction) {
  const double tolerance = sweepTouchTolerance(geometrySize(moving), geometrySize(*target.geometry));
  const double movingRadius = coreRadius(moving);
  const double targetRadius = coreRadius(*target.geometry);
  double fraction = 0.0;
  // What the last advance saw: where the solids touch if the next distance
  // comes out as an overlap (an advance cannot pass the touch, but GJK's
  // own tolerance may call a gap of its size an overlap).
  std::optional<SweepContact> previous;
  for (int advance = 0; advance < kMaxAdvances; ++advance) {
    const PlacedConvex placed{&moving, {start.rotation, start.translation + fraction * delta}};
    const GjkResult closest = gjkDistance(placed, target, GjkShapes::Cores);
    if (closest.overlap || !(closest.distance > 0.0)) {
      if (previous) return previous;
      return SweepContact{0.0, closest.pointB, reversedUnit(delta)};
    }
    const Vec3 direction = (closest.pointB - closest.pointA).normalized();  // from the moving solid to the target
    const double gap = closest.distance - movingRadius - targetRadius;
    const Vec3 touched = closest.pointB - targetRadius * direction;
    const double closing = delta.dot(direction);  // how fast the gap closes, per unit fraction
    if (gap <= tolerance) {
      if (fraction == 0.0) return SweepContact{0.0, touched, reversedUnit(delta)};
      // The last bit of the gap in closed form, as a face would close it.
      double touch = closing > 0.0 ? fraction + gap / closing : fraction;
      touch = touch < maxFraction ? touch : maxFraction;
      if (movingRadius + targetRadius > 0.0) {
        // A round solid's normal turns as it slides over the last of the
        // gap. Its core is still the radii apart at the touch, so GJK
        // there gives the touch's own closest points, well defined.
        const PlacedConvex atTouch{&moving, {start.rotation, start.translation + touch * delta}};
        const GjkResult cores = gjkDistance(atTouch, target, GjkShapes::Cores);
        if (!cores.overlap && cores.distance > 0.0) {
          const Vec3 normal = (cores.pointB - cores.pointA).normalized();
          return SweepContact{touch, cores.pointB - targetRadius * normal, -normal};
        }
      }
      // Polytopes: the closest points' direction does not turn while the
      // same features approach (a face's normal, two edges' common
      // perpendicular), so the one found at the gap is the touch's.
      return SweepContact{touch, touched, -direction};
    }
    // A gap that does not close now never does (the distance is convex in
    // the fraction).
    if (!(closing > 0.0)) return std::nullopt;
    // Aim at half the tolerance: the advance lands with the solids still
    // apart, where their closest points have a direction.
    fraction += (gap - 0.5 * tolerance) / closing;
    if (fraction > maxFraction) return std::nullopt;
    previous = SweepContact{fraction, touched, -direction};
  }
  // Not settled within the cap (a sweep grazing a curved surface): the last
  // fraction is still short of any touch, and the caller gets it as the hit.
  return previous;
}

std::optional<SweepContact> sweepAgainstHalfSpace(const ConvexGeometry& moving, const Transform& start,
                                                  const Vec3& delta, const HalfSpace& target,
                                                  double maxFraction) {
  const Vec3& normal = target.normal;
  // The solid's deepest point along the half-space's inward direction.
  const Vec3 deepest = start.apply(supportPoint(moving, start.inverseRotate(-normal)));
  const double gap = normal.dot(deepest) - target.offset;
  if (gap <= sweepTouchTolerance(geometrySize(moving), 0.0))
    return SweepContact{0.0, deepest - gap * normal, reversedUnit(delta)};
  const double closing = -normal.dot(delta);
  if (!(closing > 0.0)) return std::nullopt;
  const double fraction = gap / closing;
  if (!(fraction <= maxFraction)) return std::nullopt;
  return SweepContact{fraction, deepest + fraction * delta, normal};
}

}  // namespace rbsim
