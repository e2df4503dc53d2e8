#pragma once
// The narrow phase's dedicated routines, one family per file, and the
// conventions they share. Internal to collision/: callers use
// collideConvex / collidePlaneConvex (contact_generation.h), which dispatch here.
//
// Every routine writes the manifold with its normal pointing from its first
// solid to its second, depth = normal · (pointA − pointB) (> 0 penetrating),
// keeps points whose depth is at least −margin, and returns whether it
// wrote any point.

#include <cstdint>

#include "physics/collision/contact_generation.h"
#include "physics/collision/convex_hull.h"
#include "rbsim/physics/shapes.h"
#include "rbsim/physics/transform.h"

namespace rbsim {

// Two directions within about 3° count as parallel: a face "faces" the
// normal, a segment "lies" on a face. Loose enough that a resting body keeps
// its full manifold while the solver lets it wobble by a fraction of a
// degree; tight enough that a visibly tilted body gets its one real point.
inline constexpr double kFlatSine = 0.05;
inline constexpr double kFlatCosine = 0.9987492177719089;  // sqrt(1 − kFlatSine²)

// Hysteresis of the separating-axis choice (Gregorius, "Robust contact
// creation for physics simulations", GDC 2015): an edge axis wins only if
// clearly shallower than the best face axis, and B's face only if clearly
// shallower than A's, so that near-ties do not flip the reference feature
// (and with it every point and feature id) from one step to the next.
// Separations are negative when penetrating, so a factor < 1 moves the bar up.
inline constexpr double kRelativeEdgeTolerance = 0.90;
inline constexpr double kRelativeFaceTolerance = 0.98;
inline constexpr double kAbsoluteTolerance = 0.0005;  // m

// Cross products of edges shorter than this sine of their angle are skipped:
// the axis is ill-defined and a face axis covers that configuration.
inline constexpr double kParallelEdgeSine = 0.005;

// Feature ids: [31:30] kind, [29:20] first feature, [19:10] second, [9:0] third.
// For a clipped face contact: reference face, incident face and the clip
// feature (incident vertex or incident edge × reference side). Fields wrap
// past 1024, which only risks a missed warm start on huge hulls.
enum class FeatureKind : uint32_t { FaceOfA = 0, FaceOfB = 1, EdgeEdge = 2, Other = 3 };
inline uint32_t makeFeatureId(FeatureKind kind, uint32_t first, uint32_t second, uint32_t third) {
  return (static_cast<uint32_t>(kind) << 30) | ((first & 0x3FFu) << 20) |
         ((second & 0x3FFu) << 10) | (third & 0x3FFu);
}

// Turns a manifold of (b, a) into the manifold of (a, b).
void flipManifold(ContactManifold& manifold);

// sphere_contacts.cpp
bool collideSpheres(const Vec3& centerA, double radiusA, const Vec3& centerB, double radiusB,
                    const ContactSettings& settings, ContactManifold& out);
bool collideBoxSphere(const BoxShape& box, const Transform& boxPose, const Vec3& center,
                      double radius, const ContactSettings& settings, ContactManifold& out);
bool collideCapsuleSphere(const CapsuleShape& capsule, const Transform& capsulePose,
                          const Vec3& center, double radius, const ContactSettings& settings,
                          ContactManifold& out);
bool collideCylinderSphere(const CylinderShape& cylinder, const Transform& cylinderPose,
                           const Vec3& center, double radius, const ContactSettings& settings,
                           ContactManifold& out);
bool collideHullSphere(const ConvexHull& hull, const Transform& hullPose, const Vec3& center,
                       double radius, const ContactSettings& settings, ContactManifold& out);

// capsule_contacts.cpp
bool collideCapsules(const CapsuleShape& capsuleA, const Transform& poseA,
                     const CapsuleShape& capsuleB, const Transform& poseB,
                     const ContactSettings& settings, ContactManifold& out);
// Segments lying side by side, apart along the unit `normal` (A -> B), each
// grown by its radius: a point at each end of the stretch of A that B
// overlaps, paired with its closest point on B; ids featureBase | 0 and | 1.
// Returns how many points it added (none when the stretch is empty).
int addSideBySide(const Vec3& startA, const Vec3& endA, double radiusA, const Vec3& startB,
                  const Vec3& endB, double radiusB, const Vec3& normal, uint32_t featureBase,
                  const ContactSettings& settings, ContactManifold& out);
bool collideHullCapsule(const ConvexHull& hull, const Transform& hullPose,
                        const CapsuleShape& capsule, const Transform& capsulePose,
                        const ContactSettings& settings, ContactManifold& out);

// box_box_contact.cpp
bool collideBoxes(const BoxShape& boxA, const Transform& poseA, const BoxShape& boxB,
                  const Transform& poseB, const ContactSettings& settings, ContactManifold& out);

// hull_contacts.cpp (a box pairs with a hull through boxHull). collideHulls
// takes the bounded search on pairs of many edges and gives the exhaustive
// test's contact (tests compare the two).
bool collideHullsExhaustive(const ConvexHull& hullA, const Transform& poseA,
                            const ConvexHull& hullB, const Transform& poseB,
                            const ContactSettings& settings, ContactManifold& out);
bool collideHulls(const ConvexHull& hullA, const Transform& poseA, const ConvexHull& hullB,
                  const Transform& poseB, const ContactSettings& settings, ContactManifold& out,
                  SeparationCache* cache = nullptr);

// general_contacts.cpp: signed distance plus clipping of the support features,
// for the pairs without a dedicated routine (those with a cylinder).
bool collideGeneral(const PlacedConvex& a, const PlacedConvex& b, const ContactSettings& settings,
                    ContactManifold& out);

}  // namespace rbsim
