#pragma once
// Colliding contacts at the time of impact.
//
// A contact whose bodies close faster than the restitution threshold and
// meet within the step is a collision (a colliding contact in Baraff's terms). Its
// impulse must act with the geometry of the moment the surfaces meet: there
// the normal, the contact points and the lever arms are those of touching
// bodies, and the bodies leave with exactly −e v_rel. Answering it at the
// step's start instead (a speculative contact) takes the normal up to |v| dt
// before contact and bounces the body from where it was, which adds energy at
// every bounce and turns oblique impacts the wrong way.
//
// The time of impact t* is the first root of the pair's gap along the
// bodies' free flight: each body moved from the step's start by the world's
// integrator over t, with gravity and its external load, as a free body would
// be. The world then integrates each colliding body in three parts: free
// flight to t*, the impulses there, free flight over the rest of the step, so
// that the bounce itself adds nothing to what the integrator does in flight.

#include <optional>

#include "physics/body/external_load.h"
#include "physics/body/body.h"
#include "rbsim/physics/rigid_state.h"
#include "physics/collision/body_contact.h"
#include "physics/collision/contact_generation.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/world_settings.h"

namespace rbsim {

// How the root is found. Regula falsi (the Illinois variant: Dowell and
// Jarratt, BIT 11, 1971) converges superlinearly on the smooth gap of a free
// flight; bisection is the classic backtracking (Baraff's rigid-body notes), halving
// the interval until the gap is within the tolerance. Both stop at the same
// condition, so they answer the same to the tolerance.
enum class ImpactSearchMethod { RegulaFalsi, Bisection };

struct ImpactSearch {
  ImpactSearchMethod method = ImpactSearchMethod::RegulaFalsi;
  double tolerance = 1e-9;  // m: a gap in [0, tolerance] counts as touching
  IntegratorKind integrator = IntegratorKind::SemiImplicitEuler;
  Vec3 gravity = Vec3::Zero();  // m/s²
  ContactSettings detection;    // the margin of the manifolds it computes
};

struct Impact {
  double time = 0.0;  // s after the step's start, in [0, dt]
  // The pair's manifold at `time`: touching (deepest gap within the
  // tolerance), or as detected at the step's start when they already overlap.
  ContactManifold manifold;
};

// A body as it flies free: the body and the external load on it this step
// (null for none; the world keeps loads, not bodies).
struct FlyingBody {
  const Body& body;
  const ExternalLoad* load = nullptr;
};

// The state of a body after t (s) of free flight from its current state with
// the world's integrator, gravity and its external load; a static body stays.
RigidState freeFlight(const FlyingBody& flying, IntegratorKind integrator, const Vec3& gravity, double t);

// The first time in [0, dt] at which the pieces of `contact` (detected at the
// bodies' current poses) touch while both bodies fly free; nullopt when they
// are apart at dt and at `predictedTime` (s, where the gap would close at its
// current rate: a body fast enough to pass a thin piece within the step is
// apart at both ends of it). Both bodies must have colliders.
std::optional<Impact> findImpact(const FlyingBody& a, const FlyingBody& b, const BodyContact& contact,
                                 const ImpactSearch& search, double dt, double predictedTime);

}  // namespace rbsim
