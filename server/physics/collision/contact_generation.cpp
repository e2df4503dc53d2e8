// The narrow phase's entry points: dispatch on the pair of geometry types to
// a dedicated routine, written for one order of the pair and flipped for the
// other, or to the general signed-distance-and-clipping routine.

#include "physics/collision/contact_generation.h"

#include <cassert>
#include <memory>
#include <utility>
#include <variant>

#include "physics/collision/box_features.h"
#include "physics/collision/contact_routines.h"

namespace rbsim {

void flipManifold(ContactManifold& manifold) {
  manifold.normal = -manifold.normal;
  for (int i = 0; i < manifold.pointCount; ++i) {
    ContactPoint& point = manifold.points[static_cast<std::size_t>(i)];
    std::swap(point.pointA, point.pointB);
  }
}

namespace {

// The dedicated routines, each for one order of its pair.
bool dedicated(const SphereShape& a, const Transform& poseA, const SphereShape& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  return collideSpheres(poseA.translation, a.radius, poseB.translation, b.radius, settings, out);
}
bool dedicated(const BoxShape& a, const Transform& poseA, const SphereShape& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  return collideBoxSphere(a, poseA, poseB.translation, b.radius, settings, out);
}
bool dedicated(const CapsuleShape& a, const Transform& poseA, const SphereShape& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  return collideCapsuleSphere(a, poseA, poseB.translation, b.radius, settings, out);
}
bool dedicated(const CylinderShape& a, const Transform& poseA, const SphereShape& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  return collideCylinderSphere(a, poseA, poseB.translation, b.radius, settings, out);
}
bool dedicated(const ConvexHull& a, const Transform& poseA, const SphereShape& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  return collideHullSphere(a, poseA, poseB.translation, b.radius, settings, out);
}
bool dedicated(const BoxShape& a, const Transform& poseA, const BoxShape& b, const Transform& poseB,
               const ContactSettings& settings, ContactManifold& out) {
  return collideBoxes(a, poseA, b, poseB, settings, out);
}
bool dedicated(const CapsuleShape& a, const Transform& poseA, const CapsuleShape& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  return collideCapsules(a, poseA, b, poseB, settings, out);
}
bool dedicated(const ConvexHull& a, const Transform& poseA, const CapsuleShape& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  return collideHullCapsule(a, poseA, b, poseB, settings, out);
}
// A box meets capsules and hulls as a hull: the hull routines' separating
// axes and clipping are exact for it, and a 15-axis special case per pair
// would buy speed we have not needed yet.
bool dedicated(const BoxShape& a, const Transform& poseA, const CapsuleShape& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out) {
  return collideHullCapsule(boxHull(a.halfExtents), poseA, b, poseB, settings, out);
}
bool dedicated(const ConvexHull& a, const Transform& poseA, const ConvexHull& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out,
               SeparationCache* cache) {
  return collideHulls(a, poseA, b, poseB, settings, out, cache);
}
bool dedicated(const BoxShape& a, const Transform& poseA, const ConvexHull& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out,
               SeparationCache* cache) {
  return collideHulls(boxHull(a.halfExtents), poseA, b, poseB, settings, out, cache);
}
// Both orders of box and hull keep their order: the face-axis hysteresis
// prefers the first solid's face, and a flipped call would prefer the other's.
bool dedicated(const ConvexHull& a, const Transform& poseA, const BoxShape& b,
               const Transform& poseB, const ContactSettings& settings, ContactManifold& out,
               SeparationCache* cache) {
  return collideHulls(a, poseA, boxHull(b.halfExtents), poseB, settings, out, cache);
}

template <class GeometryA, class GeometryB>
bool collidePair(const GeometryA& geometryA, const GeometryB& geometryB, const PlacedConvex& a,
                 const PlacedConvex& b, const ContactSettings& settings, ContactManifold& out,
                 SeparationCache* cache) {
  // The hull pairs keep a SeparationCache; they are written for both orders.
  if constexpr (requires { dedicated(geometryA, a.pose, geometryB, b.pose, settings, out, cache); }) {
    return dedicated(geometryA, a.pose, geometryB, b.pose, settings, out, cache);
  } else if constexpr (requires { dedicated(geometryA, a.pose, geometryB, b.pose, settings, out); }) {
    return dedicated(geometryA, a.pose, geometryB, b.pose, settings, out);
  } else if constexpr (requires {
                         dedicated(geometryB, b.pose, geometryA, a.pose, settings, out);
                       }) {
    if (!dedicated(geometryB, b.pose, geometryA, a.pose, settings, out)) return false;
    flipManifold(out);
    return true;
  } else {
    return collideGeneral(a, b, settings, out);
  }
}

template <class Geometry>
const Geometry& unwrap(const Geometry& geometry) {
  return geometry;
}
const ConvexHull& unwrap(const std::shared_ptr<const ConvexHull>& hull) {
  assert(hull != nullptr);
  return *hull;
}

}  // namespace

bool collideConvex(const PlacedConvex& a, const PlacedConvex& b, const ContactSettings& settings,
                   ContactManifold& out, SeparationCache* cache) {
  assert(a.geometry != nullptr && b.geometry != nullptr);
  out = ContactManifold{};
  const bool touching = std::visit(
      [&](const auto& geometryA, const auto& geometryB) {
        return collidePair(unwrap(geometryA), unwrap(geometryB), a, b, settings, out, cache);
      },
      *a.geometry, *b.geometry);
  if (!touching) out = ContactManifold{};
  return out.pointCount > 0;
}

}  // namespace rbsim
