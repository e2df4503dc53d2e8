// Contacts with a half-space (the plane is body A, the manifold normal is
// the plane's): the vertices of the solid, or for round solids the deepest
// points of its support features, that lie below the plane plus the margin.
// A resting box thus gets its four bottom corners, a standing cylinder the
// polygon of its cap, a lying capsule or cylinder both ends of its side.

#include <cmath>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <variant>
#include <vector>

#include "physics/collision/box_features.h"
#include "physics/collision/contact_routines.h"
#include "physics/collision/polygon_clipping.h"
#include "physics/collision/support_features.h"

namespace rbsim {

namespace {

struct PlaneContacts {
  Vec3 normal;
  double offset;
  double margin;
  std::vector<ContactPoint> candidates;

  // Adds p (a point of the solid, world) if it is within the margin.
  void add(const Vec3& p, uint32_t feature) {
    const double separation = normal.dot(p) - offset;
    if (separation > margin) return;
    ContactPoint point;
    point.pointA = p - separation * normal;
    point.pointB = p;
    point.depth = -separation;
    point.featureId = makeFeatureId(FeatureKind::FaceOfA, 0, feature, 0);
    candidates.push_back(point);
  }
};

void addCylinder(const CylinderShape& cylinder, const Transform& pose, PlaneContacts& contacts) {
  const Vec3 down = pose.inverseRotate(-contacts.normal);
  if (std::abs(down.z()) >= kFlatCosine) {
    const bool top = down.z() > 0.0;
    for (int k = 0; k < kCylinderCapSides; ++k) {
      contacts.add(pose.apply(cylinderCapVertex(cylinder, top, k)),
                   static_cast<uint32_t>((top ? kCylinderCapSides : 0) + k));
    }
    return;
  }
  // Tilted or lying: the lowest point of each cap's rim (on a lying
  // cylinder, the two ends of the line it rests on).
  const Vec3 radial = Vec3(down.x(), down.y(), 0.0).normalized() * cylinder.radius;
  contacts.add(pose.apply(radial - Vec3(0.0, 0.0, cylinder.halfLength)), 2 * kCylinderCapSides);
  contacts.add(pose.apply(radial + Vec3(0.0, 0.0, cylinder.halfLength)), 2 * kCylinderCapSides + 1);
}

void addHullVertices(const ConvexHull& hull, const Transform& pose, PlaneContacts& contacts) {
  for (std::size_t v = 0; v < hull.vertices.size(); ++v) {
    contacts.add(pose.apply(hull.vertices[v]), static_cast<uint32_t>(v));
  }
}

}  // namespace

bool collidePlaneConvex(const Vec3& planeNormal, double planeOffset, const PlacedConvex& b,
                        const ContactSettings& settings, ContactManifold& out) {
  out = ContactManifold{};
  PlaneContacts contacts{planeNormal, planeOffset, settings.margin, {}};
  const Transform& pose = b.pose;
  std::visit(
      [&](const auto& geometry) {
        using Geometry = std::decay_t<decltype(geometry)>;
        if constexpr (std::is_same_v<Geometry, SphereShape>) {
          contacts.add(pose.translation - geometry.radius * planeNormal, 0);
        } else if constexpr (std::is_same_v<Geometry, CapsuleShape>) {
          // Each end is a sphere.
          for (const double end : {-1.0, 1.0}) {
            const Vec3 center = pose.apply(Vec3(0.0, 0.0, end * geometry.halfLength));
            contacts.add(center - geometry.radius * planeNormal, end < 0.0 ? 0u : 1u);
          }
        } else if constexpr (std::is_same_v<Geometry, BoxShape>) {
          for (int v = 0; v < 8; ++v) {
            contacts.add(pose.apply(boxVertex(geometry.halfExtents, v)), static_cast<uint32_t>(v));
          }
        } else if constexpr (std::is_same_v<Geometry, CylinderShape>) {
          addCylinder(geometry, pose, contacts);
        } else {
          addHullVertices(*geometry, pose, contacts);
        }
      },
      *b.geometry);
  if (contacts.candidates.empty()) return false;
  reduceContacts(contacts.candidates, planeNormal, out);
  out.normal = planeNormal;
  return true;
}

}  // namespace rbsim
