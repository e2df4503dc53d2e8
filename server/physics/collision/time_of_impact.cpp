#include "physics/collision/time_of_impact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

#include "physics/body/integrator.h"
#include "physics/collision/broad_phase.h"
#include "physics/collision/triangle_mesh_contacts.h"

namespace rbsim {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Distance from a piece placed in the world down to a half-space: the height
// of its lowest point, with the points and the normal oriented from the
// plane to the piece.
SignedDistance planeToPiece(const HalfSpace& plane, const PlacedConvex& piece) {
  SignedDistance result;
  const Vec3 lowest = piece.support(-plane.normal);
  result.distance = plane.normal.dot(lowest) - plane.offset;
  result.pointB = lowest;
  result.pointA = lowest - result.distance * plane.normal;
  result.normal = plane.normal;
  return result;
}

SignedDistance swapped(SignedDistance distance) {
  std::swap(distance.pointA, distance.pointB);
  distance.normal = -distance.normal;
  return distance;
}

// Largest distance from a geometry's own origin to its surface.
double geometryRadius(const ConvexGeometry& geometry) {
  return std::visit(
      [](const auto& g) -> double {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, SphereShape>) {
          return g.radius;
        } else if constexpr (std::is_same_v<T, BoxShape>) {
          return g.halfExtents.norm();
        } else if constexpr (std::is_same_v<T, CapsuleShape>) {
          return g.halfLength + g.radius;
        } else if constexpr (std::is_same_v<T, CylinderShape>) {
          return std::hypot(g.radius, g.halfLength);
        } else {
          double radius = 0.0;
          for (const Vec3& vertex : g->vertices) radius = std::max(radius, vertex.norm());
          return radius;
        }
      },
      geometry);
}

// How many distance pairs a collider takes part in (a plane counts once).
int partCount(const Collider& collider) {
  return static_cast<int>(collider.pieces.size()) + (collider.plane ? 1 : 0) +
         (collider.triangles ? collider.triangles->triangleCount() : 0);
}

}  // namespace

SignedDistance colliderDistance(const Collider& a, const Transform& poseA, const Collider& b,
                                const Transform& poseB, const DistanceSettings& settings) {
  SignedDistance best;
  best.distance = kInfinity;
  const auto consider = [&best](const SignedDistance& candidate) {
    if (candidate.distance < best.distance) best = candidate;
  };
  if (a.plane) {
    const HalfSpace plane = worldHalfSpace(*a.plane, poseA);
    for (const ConvexPiece& piece : b.pieces)
      consider(planeToPiece(plane, {&piece.geometry, poseB * piece.placement}));
  }
  if (b.plane) {
    const HalfSpace plane = worldHalfSpace(*b.plane, poseB);
    for (const ConvexPiece& piece : a.pieces)
      consider(swapped(planeToPiece(plane, {&piece.geometry, poseA * piece.placement})));
  }
  if (a.triangles) {
    for (const ConvexPiece& piece : b.pieces)
      consider(triangleMeshDistance(*a.triangles, poseA, {&piece.geometry, poseB * piece.placement},
                                    settings));
  }
  if (b.triangles) {
    for (const ConvexPiece& piece : a.pieces)
      consider(swapped(triangleMeshDistance(*b.triangles, poseB,
                                            {&piece.geometry, poseA * piece.placement}, settings)));
  }
  for (const ConvexPiece& pieceA : a.pieces) {
    const PlacedConvex placedA{&pieceA.geometry, poseA * pieceA.placement};
    for (const ConvexPiece& pieceB : b.pieces) {
      consider(signedDistance(placedA, {&pieceB.geometry, poseB * pieceB.placement}, settings));
    }
  }
  return best;
}

// ---------------------------------------------------------------- bisection

PoseAtFraction integratedMotion(const Body& body, IntegratorKind integrator, const Vec3& gravity,
                                double dt, const ExternalLoad* externalLoad) {
  if (body.isStatic()) {
    return [pose = Transform{body.rotation(), body.position()}](double) { return pose; };
  }
  return [state = body.state(), rotation = body.rotation(), dynamics = body.dynamics(),
          load = externalLoad != nullptr ? *externalLoad : ExternalLoad{}, gravity, integrator,
          dt](double fraction) {
    ForceInputs inputs;
    inputs.gravity = gravity;
    inputs.load = load.active ? &load : nullptr;
    const RigidState moved =
        integrateStep(integrator, state, rotation, dynamics, inputs, fraction * dt);
    return Transform::fromPose(moved.position, moved.orientation);
  };
}

PoseAtFraction interpolatedMotion(const RigidState& start, const RigidState& end) {
  return [motion = SweptMotion::between(start, end)](double fraction) {
    return motion.poseAt(fraction);
  };
}

// Bisection for the collision time of one pair, the trial time written as a
// fraction of the step: [low, high] always brackets the first contact, with
// the bodies apart at `low` and overlapping at `high`.
TimeOfImpact bisectCollisionTime(const Collider& a, const PoseAtFraction& motionA,
                                 const Collider& b, const PoseAtFraction& motionB,
                                 const BisectionSettings& settings) {
  TimeOfImpact result;
  const auto probe = [&](double fraction) {
    const SignedDistance d =
        colliderDistance(a, motionA(fraction), b, motionB(fraction), settings.distance);
    result.fraction = fraction;
    result.distance = d.distance;
    result.normal = d.normal;
    result.pointA = d.pointA;
    result.pointB = d.pointB;
    ++result.iterations;
    return d.distance;
  };
  const auto finish = [&result](ImpactStatus status) {
    result.status = status;
    return result;
  };

  const double atStart = probe(0.0);
  if (atStart <= 0.0) return finish(ImpactStatus::Overlapping);
  if (atStart <= settings.tolerance) return finish(ImpactStatus::Hit);
  TimeOfImpact lastApart = result;  // the state at `low`, reported if the cap is hit
  const double atEnd = probe(1.0);
  if (atEnd > settings.tolerance) return finish(ImpactStatus::Separated);
  if (atEnd > 0.0) return finish(ImpactStatus::Hit);

  double low = 0.0;
  double high = 1.0;
  for (int halving = 0; halving < settings.maxIterations; ++halving) {
    const double middle = 0.5 * (low + high);
    const double distance = probe(middle);
    if (distance <= 0.0) {
      high = middle;
    } else if (distance <= settings.tolerance) {
      return finish(ImpactStatus::Hit);
    } else {
      low = middle;
      lastApart = result;
    }
  }
  lastApart.iterations = result.iterations;
  lastApart.status = ImpactStatus::NoProgress;
  return lastApart;
}

// -------------------------------------------------- conservative advancement

SweptMotion SweptMotion::between(const RigidState& start, const RigidState& end) {
  SweptMotion motion;
  motion.startPosition = start.position;
  motion.startOrientation = start.orientation;
  motion.displacement = end.position - start.position;
  // end = delta · start, delta a rotation in the world frame; ±delta are the
  // same rotation, and w >= 0 picks the shorter arc.
  Quaternion delta = end.orientation * start.orientation.conjugate();
  if (delta.w < 0.0) delta = {-delta.w, -delta.x, -delta.y, -delta.z};
  const double sinHalfAngle = delta.vec().norm();
  if (sinHalfAngle > 0.0) {
    motion.rotationAxis = delta.vec() / sinHalfAngle;
    motion.rotationAngle = 2.0 * std::atan2(sinHalfAngle, delta.w);
  }
  return motion;
}

SweptMotion SweptMotion::fromVelocities(const RigidState& start, const Vec3& linearVelocity,
                                        const Vec3& angularVelocity, double dt) {
  SweptMotion motion;
  motion.startPosition = start.position;
  motion.startOrientation = start.orientation;
  motion.displacement = linearVelocity * dt;
  const double rate = angularVelocity.norm();
  if (rate > 0.0) {
    motion.rotationAxis = angularVelocity / rate;
    motion.rotationAngle = rate * dt;
  }
  return motion;
}

Transform SweptMotion::poseAt(double fraction) const {
  const Quaternion turned =
      Quaternion::fromAxisAngle(rotationAxis, fraction * rotationAngle) * startOrientation;
  return Transform::fromPose(startPosition + fraction * displacement, turned);
}

double boundingRadius(const Collider& collider) {
  if (collider.plane) return kInfinity;
  if (collider.triangles) return colliderRadius(collider);
  double radius = 0.0;
  for (const ConvexPiece& piece : collider.pieces)
    radius = std::max(radius, piece.placement.translation.norm() + geometryRadius(piece.geometry));
  return radius;
}

TimeOfImpact conservativeAdvancement(const Collider& a, const SweptMotion& motionA,
                                     const Collider& b, const SweptMotion& motionB,
                                     const CcdSettings& settings) {
  // Only a body that turns needs its radius (a plane's is infinite).
  const double turnA =
      motionA.rotationAngle > 0.0 ? motionA.rotationAngle * boundingRadius(a) : 0.0;
  const double turnB =
      motionB.rotationAngle > 0.0 ? motionB.rotationAngle * boundingRadius(b) : 0.0;
  const Vec3 relativeDisplacement = motionA.displacement - motionB.displacement;
  // With one pair of parts (or a plane, whose normal all pairs share) the
  // distance is a separation along the closest direction, and only the
  // motion along it counts. Between compounds, each piece pair has its own
  // direction: bound by the whole relative displacement.
  const bool oneDirection = partCount(a) * partCount(b) == 1 || a.plane || b.plane;

  TimeOfImpact result;
  const auto separated = [&result] {
    TimeOfImpact none;
    none.iterations = result.iterations;
    return none;
  };
  double fraction = 0.0;
  for (int iteration = 1; iteration <= settings.maxIterations; ++iteration) {
    const SignedDistance d = colliderDistance(a, motionA.poseAt(fraction), b,
                                              motionB.poseAt(fraction), settings.distance);
    result.fraction = fraction;
    result.distance = d.distance;
    result.normal = d.normal;
    result.pointA = d.pointA;
    result.pointB = d.pointB;
    result.iterations = iteration;
    if (d.distance <= settings.tolerance) {
      result.status =
          iteration == 1 && d.distance <= 0.0 ? ImpactStatus::Overlapping : ImpactStatus::Hit;
      return result;
    }
    const double linear =
        oneDirection ? relativeDisplacement.dot(d.normal) : relativeDisplacement.norm();
    const double approachPerStep = linear + turnA + turnB;  // m per unit fraction
    if (!(approachPerStep > 0.0)) return separated();       // not closing (or not finite)
    fraction += d.distance / approachPerStep;
    if (fraction >= 1.0) return separated();
  }
  result.status = ImpactStatus::NoProgress;  // result.fraction is still before any contact
  return result;
}

TimeOfImpact continuousTimeOfImpact(const Body& a, const RigidState& endA, const Body& b,
                                    const RigidState& endB, const CcdSettings& settings) {
  const Collider* colliderA = a.description().collider.get();
  const Collider* colliderB = b.description().collider.get();
  if (colliderA == nullptr || colliderB == nullptr) return {};
  return conservativeAdvancement(*colliderA, SweptMotion::between(a.state(), endA), *colliderB,
                                 SweptMotion::between(b.state(), endB), settings);
}

}  // namespace rbsim
