#pragma once
// Settings of the impulse-based contact solver (see contact_solver.h).

namespace rbsim {

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
  // Points with a gap wider than this (m) are left out of the solve. The
  // default keeps every point within the contact margin (speculative
  // contacts: an approaching body is stopped as the gap closes); the
  // backtracking mode uses its tolerance so that it finds the time of
  // collision itself.
  double speculativeDistance = 1e30;
};

}  // namespace rbsim
