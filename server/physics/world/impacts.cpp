#include "physics/body/body.h"
#include "physics/world/impacts.h"

#include <algorithm>
#include <cstddef>

#include "physics/body/integrator.h"
#include "physics/collision/piece_pair_contact.h"

namespace rbsim {

namespace {

// Larger than any gap the search can meet, for pieces beyond the margin.
constexpr double kApart = 1e30;  // m
constexpr int kMaxIterations = 64;

double gapOf(const ContactManifold& manifold) {
  if (manifold.pointCount == 0) return kApart;
  double deepest = manifold.points[0].depth;
  for (int i = 1; i < manifold.pointCount; ++i)
    deepest = std::max(deepest, manifold.points[static_cast<std::size_t>(i)].depth);
  return -deepest;
}

}  // namespace

RigidState freeFlight(const FlyingBody& flying, IntegratorKind integrator, const Vec3& gravity, double t) {
  const Body& body = flying.body;
  if (body.isStatic() || t == 0.0) return body.state();
  ForceInputs inputs;
  inputs.gravity = gravity;
  inputs.load = flying.load != nullptr && flying.load->active ? flying.load : nullptr;
  return integrateStep(integrator, body.state(), body.rotation(), body.dynamics(), inputs, t);
}

std::optional<Impact> findImpact(const FlyingBody& a, const FlyingBody& b, const BodyContact& contact,
                                 const ImpactSearch& search, double dt, double predictedTime) {
  const Collider& colliderA = *a.body.description().collider;
  const Collider& colliderB = *b.body.description().collider;
  Impact trial;
  const auto gapAt = [&](double t) {
    const RigidState stateA = freeFlight(a, search.integrator, search.gravity, t);
    const RigidState stateB = freeFlight(b, search.integrator, search.gravity, t);
    collidePiecePair(colliderA, contact.pieceA,
                     Transform::fromPose(stateA.position, stateA.orientation), colliderB,
                     contact.pieceB, Transform::fromPose(stateB.position, stateB.orientation),
                     search.detection, trial.manifold);
    trial.time = t;
    return gapOf(trial.manifold);
  };
  const auto touching = [&](double gap) { return gap >= 0.0 && gap <= search.tolerance; };

  // Already touching or overlapping: the impact is now, with the detected geometry.
  const double startGap = gapOf(contact.manifold);
  if (startGap <= search.tolerance) return Impact{0.0, contact.manifold};
  // [low, high] brackets the first contact: apart at low, overlapping at high.
  double low = 0.0, lowGap = startGap;
  Impact best{0.0, contact.manifold};  // the latest trial known to be apart
  double high = dt, highGap = 0.0;
  const bool hinted = predictedTime > 0.0 && predictedTime < dt;
  if (hinted && search.method == ImpactSearchMethod::RegulaFalsi) {
    // Where the gap closes at its current rate: on a nearly straight flight
    // that is nearly the root, and one side of the bracket either way.
    const double gap = gapAt(predictedTime);
    if (touching(gap)) return trial;
    if (gap < 0.0) {
      high = predictedTime;
      highGap = gap;
    } else {
      low = predictedTime;
      lowGap = gap;
      best = trial;
      highGap = gapAt(dt);
    }
  } else {
    highGap = gapAt(dt);
    if (highGap > search.tolerance && hinted) {
      // A body that passes a thin piece within the step is apart again at dt.
      high = predictedTime;
      highGap = gapAt(predictedTime);
    }
  }
  if (highGap > search.tolerance) return std::nullopt;  // apart when the step ends
  if (touching(highGap)) return trial;

  int side = 0;                        // which end the last regula falsi step moved
  for (int i = 0; i < kMaxIterations; ++i) {
    double t = 0.5 * (low + high);
    if (search.method == ImpactSearchMethod::RegulaFalsi) {
      // Where the chord between the ends crosses zero; lowGap > 0 > highGap.
      t = (low * highGap - high * lowGap) / (highGap - lowGap);
      if (!(t > low && t < high)) t = 0.5 * (low + high);
    }
    if (!(t > low && t < high)) break;  // the interval is down to one double
    const double gap = gapAt(t);
    if (touching(gap)) return trial;
    if (gap > 0.0) {
      low = t;
      lowGap = gap;
      best = trial;
      if (side == 1) highGap *= 0.5;  // Illinois: the stale end's value is halved
      side = 1;
    } else {
      high = t;
      highGap = gap;
      if (side == -1) lowGap *= 0.5;
      side = -1;
    }
  }
  return best;
}

}  // namespace rbsim
