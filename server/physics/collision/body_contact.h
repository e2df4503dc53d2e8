#pragma once
// A contact manifold between two bodies of a world, as the detector reports
// it and the solver consumes it.

#include "physics/collision/contact_manifold.h"

namespace rbsim {

struct BodyContact {
  int bodyA = 0;  // dense index into world.bodies(); serial(A) < serial(B)
  int bodyB = 0;
  int pieceA = 0;  // which convex piece of each body (0 for planes, the triangle of a trimesh)
  int pieceB = 0;
  ContactManifold manifold;
};

}  // namespace rbsim
