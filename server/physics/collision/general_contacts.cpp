// Contacts for pairs without a dedicated routine (those with a cylinder):
// the signed distance gives the normal and the depth, then the two solids'
// support features along it are clipped against each other (Gregorius,
// "Robust contact creation for physics simulations", GDC 2015), so that a
// cylinder standing or lying on a box gets a whole manifold where the
// distance query alone gives one point.

#include <cmath>
#include <vector>

#include "physics/collision/contact_routines.h"
#include "physics/collision/polygon_clipping.h"
#include "physics/collision/signed_distance.h"
#include "physics/collision/support_features.h"

namespace rbsim {

bool collideGeneral(const PlacedConvex& a, const PlacedConvex& b, const ContactSettings& settings,
                    ContactManifold& out) {
  const double margin = settings.margin;
  SignedDistance query = signedDistance(a, b);
  if (!query.normal.allFinite() || !std::isfinite(query.distance) ||
      std::abs(query.normal.squaredNorm() - 1.0) > 1e-6) {
    // EPA can return no direction at all (libccd issue #25, face-to-face
    // boxes): use the line of centres and the separation of the supports
    // along it, a sound if rougher axis.
    const Vec3 offset = b.pose.translation - a.pose.translation;
    query.normal = offset.norm() > 0.0 ? Vec3(offset.normalized()) : Vec3::UnitZ();
    query.pointA = a.support(query.normal);
    query.pointB = b.support(-query.normal);
    query.distance = query.normal.dot(query.pointB - query.pointA);
  }
  if (query.distance > margin) return false;
  const Vec3& normal = query.normal;

  const SupportFeature featureA = supportFeature(a, normal);
  const SupportFeature featureB = supportFeature(b, -normal);
  const bool polygonA = featureA.vertices.size() >= 3;
  const bool polygonB = featureB.vertices.size() >= 3;
  if (polygonA || polygonB) {
    // The reference face is the one that faces the other solid more squarely.
    const bool referenceIsA =
        polygonA && (!polygonB || featureA.normal.dot(normal) >= -featureB.normal.dot(normal));
    const SupportFeature& reference = referenceIsA ? featureA : featureB;
    const SupportFeature& incident = referenceIsA ? featureB : featureA;
    std::vector<ContactPoint> candidates;
    clipIncidentFeature(reference.vertices, reference.normal, incident.vertices, referenceIsA,
                        makeFeatureId(referenceIsA ? FeatureKind::FaceOfA : FeatureKind::FaceOfB,
                                      reference.id, incident.id, 0),
                        margin, candidates);
    if (!candidates.empty()) {
      reduceContacts(candidates, reference.normal, out);
      out.normal = referenceIsA ? reference.normal : Vec3(-reference.normal);
      return true;
    }
  } else if (featureA.vertices.size() == 2 && featureB.vertices.size() == 2) {
    const Vec3 alongA = featureA.vertices[1] - featureA.vertices[0];
    const Vec3 alongB = featureB.vertices[1] - featureB.vertices[0];
    if (alongA.cross(alongB).norm() <= kFlatSine * alongA.norm() * alongB.norm() &&
        addSideBySide(featureA.vertices[0], featureA.vertices[1], 0.0, featureB.vertices[0],
                      featureB.vertices[1], 0.0, normal,
                      makeFeatureId(FeatureKind::EdgeEdge, featureA.id, featureB.id, 0), settings,
                      out) > 0) {
      return true;
    }
  }

  ContactPoint point;
  point.pointA = query.pointA;
  point.pointB = query.pointB;
  point.depth = -query.distance;
  point.featureId = makeFeatureId(FeatureKind::Other, featureA.id, featureB.id, 0);
  out.normal = normal;
  out.add(point);
  return true;
}

}  // namespace rbsim
