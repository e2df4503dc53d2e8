#pragma once
// Settings of contact detection and of the impulse-based contact solver:
// the numbers of a world file's `contact:` section (WorldSettings::contact).

namespace rbsim {

// Contact detection (collision/contact_generation.h).
struct ContactSettings {
  // Points closer than this (m) count as contacts even before they touch,
  // so that resting contact does not flicker on and off.
  double margin = 0.005;
};

// Which solver answers the impulse model's contacts.
enum class ContactSolverKind {
  // Sequential impulses with split impulses and shock propagation, every
  // contact (solver/contact_solver.h).
  SequentialImpulses,
  // Sub-steps with soft constraints and a relax pass (solver/
  // soft_step_solver.h) for islands in resting contact; islands with a
  // collision in the step or with joints still take sequential impulses.
  // The default: it holds large stacks (the pyramid of 4095 boxes) where
  // sequential impulses let them drift.
  SoftStep,
};

// The impulse-based contact solvers (solver/contact_solver.h,
// solver/soft_step_solver.h).

struct ContactSolverSettings {
  ContactSolverKind kind = ContactSolverKind::SoftStep;
  int velocityIterations = 10;
  int positionIterations = 4;            // split-impulse iterations
  double restitutionThreshold = 0.2;     // m/s: slower approaches do not bounce
  double stickVelocity = 0.01;           // m/s: below this slip a point counts as sticking
  double linearSlop = 0.0005;            // m of penetration left alone (avoids jitter)
  double baumgarte = 0.2;                // fraction of the penetration removed per step
  double maxCorrectionVelocity = 2.0;    // m/s: cap of the pseudo-velocity
  bool warmStarting = true;
  bool shockPropagation = true;          // the last sweep holds lower bodies still (stacks)
  // m: a gap this small counts as touching. Only touching (or overlapping)
  // points bounce; the world finds a colliding pair's time of impact to
  // within it and answers the collision there (world/impacts.h). Points with
  // a wider gap are speculative: they keep the gap from closing by more than
  // it is, and never bounce.
  double touchingDistance = 1e-9;

  // The soft-step solver's. Sub-steps of the step: each is one solve, one
  // position update and one relax sweep.
  int substeps = 8;
  // Hz: stiffness of the contacts' push-out, capped at an eighth of the
  // sub-step rate (and twice this against a static body). A contact gives
  // way like a spring of that frequency on its effective mass: a cube
  // resting on another sinks by 2 g/(2π f)², 2 µm at 500 Hz. Stiffer
  // lets columns of ten tilted cubes rock for seconds (the anchors' pile of
  // 1000: 0.3 J after 4 s at 1000 Hz, at rest within 2 s at 500 Hz).
  double contactHertz = 500.0;
  double contactDampingRatio = 10.0;  // heavily damped: a push-out, not a bounce
};

}  // namespace rbsim
