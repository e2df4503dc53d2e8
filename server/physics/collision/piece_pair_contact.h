#pragma once
// The narrow phase for one piece pair of two bodies at poses of the caller's
// choosing: what the collision detector would report for that pair if the
// bodies stood there. The time-of-impact search moves a colliding pair along
// its flight and asks for the manifold at each trial time.

#include "physics/collision/collider.h"
#include "physics/collision/contact_generation.h"
#include "physics/collision/contact_manifold.h"
#include "rbsim/physics/transform.h"

namespace rbsim {

// `pieceA` and `pieceB` index the colliders' pieces (0 for a plane, the
// triangle for a trimesh), as in
// BodyContact. Same conventions as the detector: the normal points from A to
// B, and false (with out.pointCount = 0) when the pieces are farther apart
// than the margin.
bool collidePiecePair(const Collider& a, int pieceA, const Transform& poseA, const Collider& b,
                      int pieceB, const Transform& poseB, const ContactSettings& settings,
                      ContactManifold& out);

}  // namespace rbsim
