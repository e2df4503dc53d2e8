#pragma once
// Narrow phase: the contact manifold between two convex pieces, or a convex
// piece and a half-space. Dedicated routines where they pay in speed or
// quality (sphere–sphere, sphere–plane, box–plane, sphere–box, capsule pairs,
// box–box by separating axes and face clipping, convex–plane, hull–hull by
// SAT and clipping); general pairs by signed distance plus face clipping so
// that a face resting on a face gets more than one point.

#include "physics/collision/collider.h"
#include "physics/collision/contact_manifold.h"
#include "rbsim/physics/contact_settings.h"

namespace rbsim {

// What the narrow phase keeps of a pair of pieces from one step to the next
// (temporal coherence): a direction, in A's frame, along which the pieces
// were apart. Tested first the next time: if the pieces are still farther
// apart along it than the margin (with a slack that makes the test imply
// GJK's), the pair has no contact, without GJK. Only hull pairs of many
// edges use it; the answer is the same with or without it.
struct SeparationCache {
  Vec3 axis = Vec3::Zero();  // unit, A's frame, from A towards B; zero: nothing kept
};

// Returns false (and leaves out.pointCount = 0) when the pieces are farther
// apart than the margin. The normal points from a to b. Swapping a and b
// flips the normal and keeps the depths, except where two faces are within
// the reference-face hysteresis of each other (about 2% of the depth plus
// 0.5 mm): there the first piece's face is preferred, so that the manifold
// of a pair passed in a fixed order does not flicker between the two.
// Feature ids stay the same while the same features touch.
// `cache`, when given, is read and updated (see SeparationCache).
bool collideConvex(const PlacedConvex& a, const PlacedConvex& b, const ContactSettings& settings,
                   ContactManifold& out, SeparationCache* cache = nullptr);

// `plane` is the half-space of body A (world-frame normal and offset:
// normal · p <= offset is solid); the normal of the manifold is the plane's.
bool collidePlaneConvex(const Vec3& planeNormal, double planeOffset, const PlacedConvex& b,
                        const ContactSettings& settings, ContactManifold& out);

}  // namespace rbsim
