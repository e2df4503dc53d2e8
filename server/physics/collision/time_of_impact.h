#pragma once
// Time of collision within one step, two ways:
//
//  - bisectCollisionTime: backing up to the time of collision by bisection,
//    as Baraff's notes do it (Baraff, "Rigid Body Simulation", SIGGRAPH
//    course notes, on finding the collision time). The pose of each body at
//    a fraction s of the step comes from a function, which may integrate a
//    copy of the body's state from the step's start by s·dt
//    (integratedMotion) or interpolate between the start and end states
//    (interpolatedMotion). If the bodies overlap at the end of the step, the
//    step is halved until the signed distance lies in (0, tolerance]. It only
//    sees what the end state shows: a body that passes right through another
//    within the step goes unnoticed (tunnelling).
//
//  - conservativeAdvancement: continuous collision detection for fast bodies
//    (Mirtich, "Impulse-based dynamic simulation of rigid body systems",
//    thesis, 1996, §2.4; Zhang, Redon, Lee and Kim, "Continuous collision
//    detection for articulated models using Taylor models and temporal
//    culling", 2007). Over a step each body moves on a SweptMotion: its centre
//    along a straight line and its orientation about a fixed axis at a
//    constant rate. No point of a body then approaches the other, along the
//    closest direction n, faster than μ = (ΔxA − ΔxB)·n + θA rA + θB rB per
//    unit of s (Δx the displacement over the step, θ the angle turned, r the
//    largest distance of the body's surface from its centre), so advancing s
//    by d/μ cannot jump past the first contact. Repeated until d is within
//    the tolerance. It finds impacts that the end state no longer shows.
//
// Both work on colliders (compounds and planes included; a plane must not
// turn) and report the fraction of the step; the time is fraction · dt.
// Normals point from A to B.

#include <functional>

#include "physics/body/external_load.h"
#include "physics/body/body.h"
#include "rbsim/physics/integrator_kind.h"
#include "rbsim/physics/rigid_state.h"
#include "physics/collision/collider.h"
#include "physics/collision/signed_distance.h"
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/transform.h"

namespace rbsim {

enum class ImpactStatus {
  Separated,    // no contact within the step (fraction = 1)
  Hit,          // first contact at `fraction`: 0 < distance <= tolerance there
  Overlapping,  // already penetrating at the start of the step (fraction = 0)
  NoProgress,   // iteration cap hit; `fraction` is still a time before contact
};

struct TimeOfImpact {
  ImpactStatus status = ImpactStatus::Separated;
  double fraction = 1.0;        // of the step, in [0, 1]
  double distance = 0.0;        // m, signed distance at `fraction`
  Vec3 normal = Vec3::UnitZ();  // unit, world, from A to B at `fraction`
  Vec3 pointA = Vec3::Zero();   // m, world: closest points at `fraction`
  Vec3 pointB = Vec3::Zero();
  int iterations = 0;  // distance queries made
};

// Signed distance between two colliders placed at body poses: the minimum
// over their piece pairs (and plane–piece pairs, a plane's distance being the
// height of the piece's lowest point above it). Two planes: +infinity.
SignedDistance colliderDistance(const Collider& a, const Transform& poseA, const Collider& b,
                                const Transform& poseB, const DistanceSettings& settings = {});

// ---------------------------------------------------------------- bisection

// The body-to-world pose at a fraction s ∈ [0, 1] of the step.
using PoseAtFraction = std::function<Transform(double fraction)>;

// Integrates a copy of the body from its current state by s·dt with the
// world's integrator, gravity and the external load given (exact
// for whatever the integrator does within one step, so the time found is
// that of the motion the step really takes).
// A static body stays where it is.
PoseAtFraction integratedMotion(const Body& body, IntegratorKind integrator, const Vec3& gravity,
                                double dt, const ExternalLoad* load = nullptr);
// Interpolates between two states of a body: the centre linearly, the
// orientation at a constant rate about a fixed axis (slerp). Cheap, and
// needs only the states before and after a step.
PoseAtFraction interpolatedMotion(const RigidState& start, const RigidState& end);

struct BisectionSettings {
  double tolerance = 1e-4;  // m: the distance accepted as "touching"
  int maxIterations = 60;   // halvings; 2⁻⁶⁰ of a step is below double resolution
  DistanceSettings distance;
};

TimeOfImpact bisectCollisionTime(const Collider& a, const PoseAtFraction& motionA,
                                 const Collider& b, const PoseAtFraction& motionB,
                                 const BisectionSettings& settings = {});

// -------------------------------------------------- conservative advancement

// A body's motion over one step as conservative advancement models it.
struct SweptMotion {
  Vec3 startPosition = Vec3::Zero();  // m, world, centre of mass
  Quaternion startOrientation = Quaternion::identity();
  Vec3 displacement = Vec3::Zero();   // m, world, of the centre over the whole step
  Vec3 rotationAxis = Vec3::UnitZ();  // unit, world
  double rotationAngle = 0.0;         // rad over the whole step, >= 0

  // Between two states (the orientation by the shorter arc).
  static SweptMotion between(const RigidState& start, const RigidState& end);
  // Constant velocities from `start` for dt (s).
  static SweptMotion fromVelocities(const RigidState& start, const Vec3& linearVelocity,
                                    const Vec3& angularVelocity, double dt);
  static SweptMotion stationary(const RigidState& state) { return between(state, state); }

  Transform poseAt(double fraction) const;
};

// Largest distance (m) from the body origin to any point of the collider;
// infinite for a plane.
double boundingRadius(const Collider& collider);

struct CcdSettings {
  double tolerance = 1e-4;  // m: stop when the distance is at most this
  int maxIterations = 32;
  DistanceSettings distance;
};

TimeOfImpact conservativeAdvancement(const Collider& a, const SweptMotion& motionA,
                                     const Collider& b, const SweptMotion& motionB,
                                     const CcdSettings& settings = {});

// For the solver, on a pair of bodies flagged for CCD: `a` and `b` as they
// are at the start of the step, `endA` and `endB` the states the integrator
// gives them at its end. Separated when either body has no collider.
TimeOfImpact continuousTimeOfImpact(const Body& a, const RigidState& endA, const Body& b,
                                    const RigidState& endB, const CcdSettings& settings = {});

}  // namespace rbsim
