#include "physics/collision/ccd_support.h"

#include <ccd/ccd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "physics/collision/aabb.h"

namespace rbsim {

namespace {

// What libccd's callbacks receive as `const void* obj`.
//
// libccd 2.1 bounds only its GJK loop and MPR's last phase by
// max_iterations: EPA's loop and MPR's portal discovery and refinement stop
// only on their tolerances, and rounding can keep them from ever getting
// there (EPA re-adding a vertex that lies in the plane of the face it should
// stop on spins forever). Every one of those loops asks for a support point
// on each pass and gives up when that point is not beyond the origin. So each
// piece answers at most `budget` queries truthfully and then answers
// "behind the origin" (the pair's Minkowski point −2·reach·d̂), which ends any
// loop on its next pass; an answer reached that way is not trusted.
struct CcdObject {
  CcdObject(const PlacedConvex& piece, int supportBudget, double far)
      : shape(&piece),
        center(piece.pose.apply(interiorPoint(*piece.geometry))),
        budget(supportBudget),
        reach(far) {}

  const PlacedConvex* shape;
  Vec3 center;   // world: an interior point, MPR's portal origin
  int budget;    // truthful support queries allowed per libccd call
  double reach;  // m: how far behind the origin the refusals point
  mutable int calls = 0;
  mutable bool exhausted = false;

  Vec3 support(const Vec3& direction) const {
    if (calls++ < budget) return shape->support(direction);  // finite even for a NaN direction
    exhausted = true;
    const double length = direction.norm();
    return length > 0.0 ? Vec3(-reach / length * direction) : Vec3::Zero();
  }
  void reset() const {
    calls = 0;
    exhausted = false;
  }
};

Vec3 toVec3(const ccd_vec3_t* v) {
  return {v->v[0], v->v[1], v->v[2]};
}
void fromVec3(const Vec3& p, ccd_vec3_t* out) {
  out->v[0] = p.x();
  out->v[1] = p.y();
  out->v[2] = p.z();
}

void ccdSupportOf(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  fromVec3(static_cast<const CcdObject*>(object)->support(toVec3(direction)), out);
}

void ccdCenterOf(const void* object, ccd_vec3_t* center) {
  fromVec3(static_cast<const CcdObject*>(object)->center, center);
}

// GJK's first direction: from A's centre towards B's, rather than libccd's
// fixed +x, so that it starts near the answer.
void ccdFirstDirection(const void* objectA, const void* objectB, ccd_vec3_t* direction) {
  const Vec3 d = static_cast<const CcdObject*>(objectB)->center -
                 static_cast<const CcdObject*>(objectA)->center;
  fromVec3(d.squaredNorm() > 0.0 ? d : Vec3::UnitX(), direction);
}

// How far B must move along the unit `normal` to clear A: max over A of
// n·x minus min over B of n·x. Exact for the direction given.
double depthAlong(const PlacedConvex& a, const PlacedConvex& b, const Vec3& normal) {
  return normal.dot(a.support(normal) - b.support(-normal));
}

// libccd's answer, if it is one: return code 0, finite, unit direction.
struct CcdAnswer {
  bool usable = false;
  Vec3 normal = Vec3::UnitZ();
  Vec3 position = Vec3::Zero();
};
CcdAnswer readAnswer(int status, double depth, const ccd_vec3_t& direction,
                     const ccd_vec3_t& position) {
  CcdAnswer answer;
  answer.normal = toVec3(&direction);
  answer.position = toVec3(&position);
  const double length = answer.normal.norm();
  // A NaN direction (libccd#25: EPA normalises a zero witness when the
  // pieces touch face to face) fails these tests as well as a bad status.
  answer.usable =
      status == 0 && std::isfinite(depth) && std::isfinite(length) && std::abs(length - 1.0) < 1e-6;
  if (answer.usable) answer.normal /= length;
  return answer;
}

// World directions along which the pieces' faces and edges could separate
// them: the axes of the separating-axis theorem for boxes and hulls, the
// cylinder axis, world axes and the centre line otherwise. Each is tried
// both ways.
std::vector<Vec3> candidateAxes(const PlacedConvex& a, const PlacedConvex& b,
                                const Vec3& centerLine) {
  std::vector<Vec3> faces;
  std::vector<Vec3> edgesA;
  std::vector<Vec3> edgesB;
  const auto collect = [&faces](const PlacedConvex& piece, std::vector<Vec3>& edges) {
    const Mat3& r = piece.pose.rotation;
    if (std::holds_alternative<BoxShape>(*piece.geometry)) {
      for (int i = 0; i < 3; ++i) {
        faces.push_back(r.col(i));
        edges.push_back(r.col(i));
      }
    } else if (std::holds_alternative<CylinderShape>(*piece.geometry)) {
      faces.push_back(r.col(2));
    } else if (const auto* hull = std::get_if<std::shared_ptr<const ConvexHull>>(piece.geometry)) {
      for (const auto& face : (*hull)->faces) faces.push_back(r * face.normal);
      for (const auto& edge : (*hull)->edges) {
        edges.push_back(r * ((*hull)->vertices[static_cast<std::size_t>(edge[1])] -
                             (*hull)->vertices[static_cast<std::size_t>(edge[0])]));
      }
    }
  };
  collect(a, edgesA);
  collect(b, edgesB);
  std::vector<Vec3> axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), centerLine};
  axes.insert(axes.end(), faces.begin(), faces.end());
  // Edge–edge axes only while they stay cheap: this is a fallback path.
  constexpr std::size_t kMaxEdgePairs = 1024;
  if (edgesA.size() * edgesB.size() <= kMaxEdgePairs) {
    for (const Vec3& ea : edgesA)
      for (const Vec3& eb : edgesB) axes.push_back(ea.cross(eb));
  }
  std::vector<Vec3> result;
  for (const Vec3& axis : axes) {
    const double length = axis.norm();
    if (!(length > 1e-12 * std::max(1.0, axis.cwiseAbs().maxCoeff()))) continue;
    result.push_back(axis / length);
    result.push_back(-axis / length);
  }
  return result;
}

}  // namespace

// m: how far apart (centre distance plus size) two pieces may be for libccd.
constexpr double kMaxLibccdReach = 1e50;

namespace {

// libccd's settings for a pair of pieces of size `scale`, with our
// callbacks.
ccd_t ccdSettings(const PenetrationSettings& settings, double scale) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.first_dir = ccdFirstDirection;
  ccd.support1 = ccdSupportOf;
  ccd.support2 = ccdSupportOf;
  ccd.center1 = ccdCenterOf;
  ccd.center2 = ccdCenterOf;
  ccd.max_iterations = static_cast<unsigned long>(std::max(1, settings.maxIterations));
  // EPA compares squared lengths with epa_tolerance: how far a new support
  // point must lie from the nearest face to count as progress. It must stay
  // far above rounding (~1e-16 scale²), or EPA never stops on a flat face.
  // MPR compares lengths with mpr_tolerance.
  ccd.epa_tolerance = (settings.tolerance * scale) * (settings.tolerance * scale);
  ccd.mpr_tolerance = settings.tolerance * scale;
  ccd.dist_tolerance = settings.tolerance * scale;
  return ccd;
}

}  // namespace

std::optional<EpaBound> epaDepthBound(const PlacedConvex& a, const PlacedConvex& b,
                                      const PenetrationSettings& settings) {
  const double scale = std::max({geometrySize(*a.geometry), geometrySize(*b.geometry), 1e-300});
  const int budget = 4 * std::max(16, settings.maxIterations);
  const CcdObject objectA(a, budget, scale + 1.0);
  const CcdObject objectB(b, budget, scale + 1.0);
  const double reach = (objectB.center - objectA.center).norm() + scale;
  // As in penetration(): libccd only sees finite, bounded input.
  if (!(std::isfinite(reach) && reach < kMaxLibccdReach && a.pose.rotation.allFinite() &&
        b.pose.rotation.allFinite() && a.pose.translation.allFinite() &&
        b.pose.translation.allFinite()))
    return std::nullopt;
  const ccd_t ccd = ccdSettings(settings, scale);
  ccd_real_t depth = 0.0;
  ccd_vec3_t direction{};
  ccd_vec3_t position{};
  const int status = ccdGJKPenetration(&objectA, &objectB, &ccd, &depth, &direction, &position);
  const CcdAnswer answer = readAnswer(status, depth, direction, position);
  if (!answer.usable || objectA.exhausted || objectB.exhausted || !(depth >= 0.0))
    return std::nullopt;
  return EpaBound{depth, answer.normal};
}

Penetration penetration(const PlacedConvex& a, const PlacedConvex& b,
                        const PenetrationSettings& settings) {
  // GJK inside EPA needs at most maxIterations queries and EPA's start up
  // to 32 more (libccd's points on a sphere); EPA itself needed fewer than
  // 70 on cylinder pairs at the default tolerance.
  const double scale = std::max({geometrySize(*a.geometry), geometrySize(*b.geometry), 1e-300});
  const int budget = 4 * std::max(16, settings.maxIterations);
  // Refusals reach at least 1 m behind the origin: libccd's zero tests are
  // absolute (DBL_EPSILON), and a refusal must not read as "on the origin".
  const CcdObject objectA(a, budget, scale + 1.0);
  const CcdObject objectB(b, budget, scale + 1.0);

  const ccd_t ccd = ccdSettings(settings, scale);

  // libccd dereferences a null face when its arithmetic meets NaN: from a
  // non-finite pose (found by fuzz_checkpoint: a body whose restored
  // momentum overflowed its position in one step), or from products of
  // coordinates beyond ~1e100 m (EPA and MPR multiply three of them). Such
  // pairs skip libccd and get the candidate axes' answer below.
  // The same goes for a pose whose rotation is not one (found by
  // fuzz_checkpoint: a compound part restored with entries near 1e259, whose
  // box reached that far though its centre sat at the origin): the pieces'
  // world boxes must stay within that reach too. And pieces whose boxes are
  // apart cannot overlap: libccd has nothing to measure there.
  const Aabb worldBoxA = transformedAabb(geometryBounds(*a.geometry), a.pose);
  const Aabb worldBoxB = transformedAabb(geometryBounds(*b.geometry), b.pose);
  const auto within = [](const Aabb& box) {
    return box.min.allFinite() && box.max.allFinite() &&
           box.min.cwiseAbs().maxCoeff() < kMaxLibccdReach &&
           box.max.cwiseAbs().maxCoeff() < kMaxLibccdReach;
  };
  const double reach = (objectB.center - objectA.center).norm() + scale;
  const bool libccdCanRun = std::isfinite(reach) && reach < kMaxLibccdReach &&
                            a.pose.rotation.allFinite() && b.pose.rotation.allFinite() &&
                            within(worldBoxA) && within(worldBoxB) && worldBoxA.overlaps(worldBoxB);
  Penetration result;
  ccd_real_t depth = 0.0;
  ccd_vec3_t direction{};
  ccd_vec3_t position{};
  // obj1 = A, obj2 = B: libccd's direction is then the way B must move to
  // clear A, which is our A-to-B normal with no sign change.
  CcdAnswer answer;
  if (libccdCanRun) {
    result.epaStatus = ccdGJKPenetration(&objectA, &objectB, &ccd, &depth, &direction, &position);
    answer = readAnswer(result.epaStatus, depth, direction, position);
    answer.usable = answer.usable && !objectA.exhausted && !objectB.exhausted;
  }
  result.method = PenetrationMethod::Epa;
  if (!answer.usable && libccdCanRun) {
    depth = 0.0;
    direction = {};
    position = {};
    objectA.reset();
    objectB.reset();
    result.mprStatus = ccdMPRPenetration(&objectA, &objectB, &ccd, &depth, &direction, &position);
    answer = readAnswer(result.mprStatus, depth, direction, position);
    answer.usable = answer.usable && !objectA.exhausted && !objectB.exhausted;
    result.method = PenetrationMethod::Mpr;
  }

  Vec3 normal = answer.normal;
  result.depth = answer.usable ? depthAlong(a, b, normal) : std::numeric_limits<double>::infinity();
  // The candidate axes (face normals, edge crosses, world axes, the line of
  // centres) bound the depth from above. They stand in when libccd fails,
  // and they also catch a libccd answer that reports success but is not the
  // minimum (seen for two lying cylinders: EPA gave 1.199 m where 0.001 m
  // along another axis separates them).
  for (const Vec3& axis : candidateAxes(a, b, objectB.center - objectA.center)) {
    const double d = depthAlong(a, b, axis);
    if (d < result.depth - settings.tolerance * scale) {
      result.depth = d;
      normal = axis;
      result.method = PenetrationMethod::SupportEstimate;
    }
  }
  result.normal = normal;

  // Where: libccd's point when it lies in both bounding boxes (EPA's point
  // can be far off when the pieces differ much in size, libccd#17), else
  // the middle of the boxes' intersection.
  const Aabb boxA = placedBounds(*a.geometry, a.pose);
  const Aabb boxB = placedBounds(*b.geometry, b.pose);
  const Aabb overlap{boxA.min.cwiseMax(boxB.min), boxA.max.cwiseMin(boxB.max)};
  const Vec3 supportA = a.support(normal);
  const Vec3 supportB = b.support(-normal);
  Vec3 where;
  if (answer.usable && answer.position.allFinite() &&
      overlap.fattened(settings.tolerance * scale).contains({answer.position, answer.position})) {
    where = answer.position;
  } else if (!overlap.isEmpty()) {
    where = overlap.center();
  } else {
    where = 0.5 * (supportA + supportB);
  }
  result.pointA = where + (normal.dot(supportA) - normal.dot(where)) * normal;
  result.pointB = where + (normal.dot(supportB) - normal.dot(where)) * normal;
  return result;
}

}  // namespace rbsim
