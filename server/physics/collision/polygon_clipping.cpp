#include "physics/collision/polygon_clipping.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace rbsim {

namespace {

// A vertex of the polygon being clipped, with what made it (the clip
// feature in featureId's low 10 bits) and which edge leaves it towards the
// next vertex: an incident edge k (tag k) or a reference side j (tag 16 + j).
// Slots wrap at 16, enough to tell apart the features of any one manifold.
struct ClipVertex {
  Vec3 point;
  uint32_t feature = 0;
  uint32_t outEdge = 0;
};

constexpr uint32_t kCutFlag = 0x200;
uint32_t sideEdgeTag(std::size_t side) {
  return 16u + static_cast<uint32_t>(side & 0xF);
}
uint32_t cutFeature(std::size_t side, uint32_t edgeTag) {
  return kCutFlag | (static_cast<uint32_t>(side & 0xF) << 5) | (edgeTag & 0x1F);
}

// Sutherland–Hodgman against one plane: keeps side · p <= offset.
void clipByPlane(const std::vector<ClipVertex>& in, const Vec3& side, double offset,
                 std::size_t sideIndex, std::vector<ClipVertex>& out) {
  out.clear();
  if (in.empty()) return;
  const ClipVertex* previous = &in.back();
  double previousDistance = side.dot(previous->point) - offset;
  for (const ClipVertex& current : in) {
    const double distance = side.dot(current.point) - offset;
    const bool previousInside = previousDistance <= 0.0;
    const bool currentInside = distance <= 0.0;
    if (previousInside != currentInside) {
      const double t = previousDistance / (previousDistance - distance);
      // Entering, the cut continues along the incident edge; leaving, the
      // polygon runs along this side until it comes back in.
      out.push_back({previous->point + t * (current.point - previous->point),
                     cutFeature(sideIndex, previous->outEdge),
                     currentInside ? previous->outEdge : sideEdgeTag(sideIndex)});
    }
    if (currentInside) out.push_back(current);
    previous = &current;
    previousDistance = distance;
  }
}

// Cyrus–Beck: the part of [p0, p1] inside all side planes, as clip vertices
// (a segment would make Sutherland–Hodgman emit each cut twice).
void clipSegment(const Vec3& p0, const Vec3& p1, std::span<const Vec3> reference,
                 const Vec3& normal, std::vector<ClipVertex>& out) {
  out.clear();
  double t0 = 0.0;
  double t1 = 1.0;
  uint32_t feature0 = 0;
  uint32_t feature1 = 1;
  const Vec3 d = p1 - p0;
  const std::size_t count = reference.size();
  for (std::size_t j = 0; j < count; ++j) {
    const Vec3& a = reference[j];
    const Vec3 side = (reference[(j + 1) % count] - a).cross(normal);
    const double start = side.dot(p0 - a);  // <= 0 inside
    const double rate = side.dot(d);
    if (rate == 0.0) {
      if (start > 0.0) return;
      continue;
    }
    const double t = -start / rate;
    if (rate < 0.0) {  // entering this side's half-space
      if (t > t0) {
        t0 = t;
        feature0 = cutFeature(j, 0);
      }
    } else if (t < t1) {
      t1 = t;
      feature1 = cutFeature(j, 1);
    }
    if (t0 > t1) return;
  }
  out.push_back({p0 + t0 * d, feature0, 0});
  if (t1 > t0) out.push_back({p0 + t1 * d, feature1, 0});
}

bool insideAllSides(const Vec3& p, std::span<const Vec3> reference, const Vec3& normal) {
  const std::size_t count = reference.size();
  for (std::size_t j = 0; j < count; ++j) {
    const Vec3& a = reference[j];
    if ((reference[(j + 1) % count] - a).cross(normal).dot(p - a) > 0.0) return false;
  }
  return true;
}

// Does candidate value/position beat the best so far? Near-ties go to the
// point first in (x, y, z) order, so that the reduction does not depend on
// the order clipping produced the points in (a box and the same box as a
// hull list their corners differently, and must give the same manifold).
constexpr double kTie = 1e-9;  // relative to the values compared
bool before(const Vec3& p, const Vec3& q) {
  for (int k = 0; k < 3; ++k) {
    if (p[k] < q[k] - kTie) return true;
    if (p[k] > q[k] + kTie) return false;
  }
  return false;
}
// Candidates whose depths spread less than this form a flat patch (see
// reduceContacts): ten micrometres, a few times what a soft contact's
// springs leave between the points of a resting face (3 µm under a tower of
// 20 cubes). A wider band (0.1 mm) took the deepest point away from boxes
// settling on an edge, which then rocked: the anchors' pile of 1000 boxes
// kept 0.45 J after 4 s, against 1e-24 J with this one.
constexpr double kFlatSpread = 1e-5;  // m
bool better(double value, const Vec3& position, double best, const Vec3& bestPosition) {
  const double tolerance = kTie * std::max(1.0, std::abs(best));
  if (value > best + tolerance) return true;
  return value >= best - tolerance && before(position, bestPosition);
}

// Twice the signed area of triangle (a, b, c) seen along `normal`.
double signedArea(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal) {
  return (b - a).cross(c - a).dot(normal);
}

}  // namespace

void clipIncidentFeature(std::span<const Vec3> reference, const Vec3& referenceNormal,
                         std::span<const Vec3> incident, bool referenceIsA, uint32_t featureBase,
                         double margin, std::vector<ContactPoint>& out) {
  if (reference.size() < 3 || incident.empty()) return;
  std::vector<ClipVertex> polygon;
  if (incident.size() == 1) {
    if (insideAllSides(incident[0], reference, referenceNormal)) {
      polygon.push_back({incident[0], 0, 0});
    }
  } else if (incident.size() == 2) {
    clipSegment(incident[0], incident[1], reference, referenceNormal, polygon);
  } else {
    polygon.reserve(incident.size() + reference.size());
    for (std::size_t k = 0; k < incident.size(); ++k) {
      const auto slot = static_cast<uint32_t>(k & 0xF);
      polygon.push_back({incident[k], slot, slot});
    }
    std::vector<ClipVertex> clipped;
    clipped.reserve(polygon.capacity());
    const std::size_t count = reference.size();
    for (std::size_t j = 0; j < count && !polygon.empty(); ++j) {
      const Vec3& a = reference[j];
      const Vec3 side = (reference[(j + 1) % count] - a).cross(referenceNormal);
      clipByPlane(polygon, side, side.dot(a), j, clipped);
      polygon.swap(clipped);
    }
  }

  const double offset = referenceNormal.dot(reference[0]);
  for (const ClipVertex& vertex : polygon) {
    const double separation = referenceNormal.dot(vertex.point) - offset;
    if (separation > margin) continue;
    const Vec3 onReference = vertex.point - separation * referenceNormal;
    ContactPoint point;
    point.pointA = referenceIsA ? onReference : vertex.point;
    point.pointB = referenceIsA ? vertex.point : onReference;
    point.depth = -separation;
    point.featureId = featureBase | (vertex.feature & 0x3FFu);
    out.push_back(point);
  }
}

void reduceContacts(std::span<const ContactPoint> candidates, const Vec3& normal,
                    ContactManifold& out) {
  out.pointCount = 0;
  if (candidates.size() <= 4) {
    for (const ContactPoint& point : candidates) out.add(point);
    return;
  }
  const auto position = [&](std::size_t i) -> const Vec3& { return candidates[i].pointB; };

  // The first point is the deepest, unless the candidates' depths spread
  // less than kFlatSpread: then the contact is a flat patch, and the first
  // point is the one farthest from the candidates' centroid, chosen by
  // where the points are and not by how deep. At rest the points of a
  // face contact differ in depth by what the solver leaves (a soft
  // contact's springs share the load unevenly), and a choice that followed
  // those differences would swap the manifold's points back and forth,
  // each swap starting a point cold. The deepest point of a flat patch is
  // one of its corners, which the area the reduction keeps nearly always
  // holds, and it is at most kFlatSpread deeper than the points kept.
  double deepest = candidates[0].depth, shallowest = candidates[0].depth;
  Vec3 centroid = Vec3::Zero();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    deepest = std::max(deepest, candidates[i].depth);
    shallowest = std::min(shallowest, candidates[i].depth);
    centroid += position(i);
  }
  centroid /= static_cast<double>(candidates.size());
  const bool flat = deepest - shallowest < kFlatSpread;
  const auto key = [&](std::size_t i) {
    if (!flat) return candidates[i].depth;
    Vec3 offset = position(i) - centroid;
    offset -= offset.dot(normal) * normal;
    return offset.squaredNorm();
  };
  std::size_t first = 0;
  for (std::size_t i = 1; i < candidates.size(); ++i) {
    if (better(key(i), position(i), key(first), position(first))) first = i;
  }

  std::size_t second = first;
  double bestDistance = 0.0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    Vec3 offset = position(i) - position(first);
    offset -= offset.dot(normal) * normal;
    if (offset.squaredNorm() > kTie &&
        better(offset.squaredNorm(), position(i), bestDistance, position(second))) {
      bestDistance = offset.squaredNorm();
      second = i;
    }
  }

  std::size_t third = first;
  double bestArea = 0.0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const double area = signedArea(position(first), position(second), position(i), normal);
    if (std::abs(area) > kTie &&
        better(std::abs(area), position(i), std::abs(bestArea), position(third))) {
      bestArea = area;
      third = i;
    }
  }

  out.add(candidates[first]);
  if (second == first) return;  // every candidate at the same place
  out.add(candidates[second]);
  if (third == first) return;  // all on one line
  out.add(candidates[third]);

  // Orient the triangle counter-clockwise about the normal; the fourth point
  // is the one outside an edge that adds the most area.
  std::array<std::size_t, 3> triangle{first, second, third};
  if (bestArea < 0.0) std::swap(triangle[1], triangle[2]);
  std::size_t fourth = first;
  double bestGain = 0.0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    double gain = 0.0;
    for (std::size_t e = 0; e < 3; ++e) {
      gain = std::max(gain, -signedArea(position(triangle[e]), position(triangle[(e + 1) % 3]),
                                        position(i), normal));
    }
    if (gain > kTie && better(gain, position(i), bestGain, position(fourth))) {
      bestGain = gain;
      fourth = i;
    }
  }
  if (fourth != first) out.add(candidates[fourth]);
}

}  // namespace rbsim
