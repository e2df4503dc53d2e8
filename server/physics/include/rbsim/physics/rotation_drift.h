#pragma once
// Warnings for bodies whose rotation the Euler integrators cannot follow.
//
// Explicit Euler keeps L exact for a torque-free body (L is the state) and
// turns q about the step-start ω by θ = 2 atan(|ω| dt / 2) ≈ |ω| dt (the
// normalised q + ½ dt [0, ω] q). In the body frame that rotates L_b about
// u = ω/|ω| by −θ, where the true motion rotates it about an ω that itself
// moves. With J = I⁻¹, E = ½ Lᵀ J L and a = u × L, the energy after a step is
//   E' = E − θ ω·a + (θ²/2) (ω·(u × a) + aᵀ J a) + O(θ³),
// where ω·a = 0 and ω·(u × a) = (u·L)|ω| − ω·L = 0, so per step
//   ΔE = (θ²/2) aᵀ J a ≈ (dt²/2) (ω×L)ᵀ I⁻¹ (ω×L) ≥ 0:
// the energy only grows (zero for a spin about a principal axis, ω ∥ L), and
// the growth feeds itself, since it tilts L away from the axis it spins about.
// For a symmetric top (moments A, A, C > A) the transverse part x = |L⊥|² of
// L obeys x' = dt (1/A − 1/C)/A · x (|L|² − x): a logistic growth at the rate
// dt |L|² (1/A − 1/C)/A ≈ dt |ω|² C (C − A)/A², saturating only when L lies
// along the axis of least inertia, where E = |L|²/(2 I_min), the most energy
// that |L| allows. So the bound is not a slow drift over the run but a time
// ∝ 1/(|ω|² dt) after which the motion is lost, up to that ceiling.
//
// No closed form covers every shape, so the check integrates each body's own
// torque-free rotation with explicit Euler at the world's dt over the horizon
// (until its energy has grown by the threshold), after skipping the bodies
// whose ceiling is below the threshold. The drift per step is ∝ dt², so the
// time to reach a given growth is ∝ 1/dt: dt · t/T reaches it at T.
//
// Semi-implicit Euler, as defined here, takes the same orientation update
// for a torque-free body (L is unchanged, then q turns about the step-start
// ω) and drifts the same way: the warning covers both Euler methods.

#include <string>
#include <vector>

#include "rbsim/physics/world.h"

namespace rbsim {

struct RotationDriftWarning {
  std::string body;
  double angularSpeed = 0.0;   // rad/s, |ω| at load
  double thresholdTime = 0.0;  // s: when the rotational energy has grown by the threshold
  double energyCeiling = 0.0;  // |L|²/(2 I_min E) − 1: the most it can grow (relative)
  double suggestedStep = 0.0;  // s: the dt at which the threshold is reached at the horizon
  std::string message;         // for the log: the body, the figures, what to do
};

// The awake dynamic bodies whose rotational energy the world's integrator
// grows by more than `threshold` (relative) within `horizon` (s) at the
// world's dt, in body order. Empty for RK4.
std::vector<RotationDriftWarning> rotationDriftWarnings(const World& world, double horizon,
                                                        double threshold = 0.01);

}  // namespace rbsim
