#pragma once
// Face clipping, the heart of every polyhedral manifold (Gregorius, "Robust
// contact creation for physics simulations", GDC 2015): the incident feature
// of one solid is clipped against the side planes of the reference face of
// the other (Sutherland–Hodgman, Ericson §8.3.4), the points that end up no
// higher than the margin above the reference face become contacts, and the
// manifold is reduced to four of them.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/collision/contact_manifold.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

// Appends the contacts of an incident feature (1 point, 2 a segment, >= 3 a
// convex polygon, world) against a reference face (world polygon,
// counter-clockwise seen from outside its solid; unit outward normal).
// Each point's featureId is featureBase | (which incident vertex, or which
// incident edge cut by which reference side, in the low 10 bits), so ids
// persist while the same features touch. Depth is measured from the
// reference plane; the point on the reference solid is the incident point
// projected onto that plane.
void clipIncidentFeature(std::span<const Vec3> reference, const Vec3& referenceNormal,
                         std::span<const Vec3> incident, bool referenceIsA, uint32_t featureBase,
                         double margin, std::vector<ContactPoint>& out);

// Keeps at most four of `candidates` (all sharing `normal`): the deepest
// one (of a flat patch, whose depths spread less than 10 µm, the one
// farthest from its centroid instead, so that the choice does not follow
// a resting body's micrometre tilts), the one farthest from it, then the
// two that enclose the largest area, which is what keeps a resting body
// from rocking (Gregorius 2015).
// The manifold's normal is left to the caller.
void reduceContacts(std::span<const ContactPoint> candidates, const Vec3& normal,
                    ContactManifold& out);

}  // namespace rbsim
