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

// The impulse-based contact solver (solver/contact_solver.h).

struct ContactSolverSettings {
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
};

}  // namespace rbsim
