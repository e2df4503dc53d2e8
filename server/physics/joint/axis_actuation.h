#pragma once
// What acts along a joint's axis besides the joint itself, over one step:
// the velocity motor, the position drive, viscous damping and dry friction
// (joint_definition.h). Each is a law between the impulse Λ it gives over
// the step and the axis rate w the step ends with, and each law is monotone
// (more rate, less push):
//   motor     w = target while |Λ| < cap; Λ = ±cap otherwise (a bounded
//             velocity constraint, as Box2D's and Jolt's motors are);
//   drive     Λ = clamp(−h (k (e + s w) + c (w − v)), ±cap): the spring
//             at the position e + s w (e = position − target now, s the
//             time the rate w will move it for before the spring is next
//             looked at) and the damper at the rate w relative to the
//             target rate v (a trajectory's), both implicit (backward
//             Euler), so that no stiffness makes the step unstable;
//             Catto's soft constraints ("Soft Step", Box2D v3) are the
//             same law;
//             with a rate limit R the drive pushes no faster than R:
//             beyond +R its impulse is min(Λ, 0), beyond −R max(Λ, 0),
//             and at ±R it holds the rate with what it would give (a
//             servo at its top speed);
//   damping   Λ = −h c w, implicit as well;
//   friction  w = 0 while |Λ| < h f (static); Λ = −h f sign(w) otherwise.
// Given the rate the axis would end with without them (w_free) and the
// axis's effective inverse mass a (the rate one unit of impulse along it
// adds, with the joints holding), the axis ends at the one w with
//   w = w_free + a Λ,   Λ ∈ L(w) = the sum of the laws.
// L is piecewise affine in w, so the root is found exactly: no iteration
// and no tolerance, and a motor at its cap gives exactly α = cap / I.

#include <limits>

namespace rbsim {

struct AxisLaw {
  double h = 0.0;  // s: how long the laws act for (the impulses are efforts times it)
  bool motor = false;
  double motorTarget = 0.0;  // rad/s or m/s
  double motorCap = 0.0;     // N·m·s or N·s over h
  bool drive = false;
  double driveError = 0.0;      // position − target, rad or m
  double driveLookahead = 0.0;  // s: s above
  double driveStiffness = 0.0;  // N·m/rad or N/m
  double driveDamping = 0.0;    // N·m·s/rad or N·s/m
  double driveTargetRate = 0.0;  // rad/s or m/s: v below
  double driveCap = std::numeric_limits<double>::infinity();  // N·m·s or N·s over h
  double driveRateLimit = std::numeric_limits<double>::infinity();  // rad/s or m/s, > 0: R above
  double damping = 0.0;      // N·m·s/rad or N·s/m
  double frictionCap = 0.0;  // N·m·s or N·s over h

  bool acts() const { return motor || drive || damping > 0.0 || frictionCap > 0.0; }
};

struct AxisImpulse {
  double total = 0.0;      // Λ: every law's impulse
  double actuation = 0.0;  // the motor's or drive's share of it
  double rate = 0.0;       // w, the rate it leaves the axis at
};

// The exact solution of w = freeRate + inverseMass Λ, Λ ∈ L(w);
// inverseMass > 0.
AxisImpulse solveAxisLaw(const AxisLaw& law, double freeRate, double inverseMass);

// The motor's and the drive's impulse over law.h on an axis held at `rate`
// by something else (a stop, a loop: the laws cannot move it): the drive's
// spring and damper there, capped, and the motor's cap towards its target
// (nothing at its target).
double actuationAtRate(const AxisLaw& law, double rate);

}  // namespace rbsim
