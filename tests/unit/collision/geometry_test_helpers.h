#pragma once
// Shared by the collision-geometry tests: shapes, poses, random polytopes, and
// reference computations written independently of GJK and libccd (closest
// points by clamping, distances of polytopes by brute force over features,
// penetration depth by separating axes).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "physics/collision/collider.h"
#include "physics/collision/convex_hull.h"
#include "rbsim/physics/quaternion.h"
#include "scenes/scene_random.h"

namespace rbsim::testing {

// A geometry that owns itself, placed in the world.
struct Solid {
  std::shared_ptr<ConvexGeometry> geometry;
  Transform pose;
  PlacedConvex placed() const { return {geometry.get(), pose}; }
};

inline Solid makeSolid(ConvexGeometry geometry, const Vec3& position = Vec3::Zero(),
                       const Quaternion& orientation = Quaternion::identity()) {
  return {std::make_shared<ConvexGeometry>(std::move(geometry)),
          Transform::fromPose(position, orientation)};
}

inline std::shared_ptr<const ConvexHull> hullOf(const std::vector<Vec3>& points) {
  auto hull = buildConvexHull(points, "test points");
  if (!hull) throw std::runtime_error(hull.error().message);
  return std::make_shared<const ConvexHull>(std::move(hull).value());
}

inline Vec3 randomUnit(scenes::SceneRandom& random) {
  // Uniform on the sphere (Archimedes: z uniform, azimuth uniform).
  const double z = random.uniform(-1.0, 1.0);
  const double phi = random.uniform(0.0, 2.0 * M_PI);
  const double rho = std::sqrt(1.0 - z * z);
  return {rho * std::cos(phi), rho * std::sin(phi), z};
}

// `count` points scattered in an ellipsoid-ish blob of the given radii.
inline std::vector<Vec3> randomPoints(scenes::SceneRandom& random, int count, const Vec3& radii) {
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    points.push_back(randomUnit(random).cwiseProduct(radii) * random.uniform(0.3, 1.0));
  }
  return points;
}

inline std::vector<Vec3> worldVertices(const ConvexHull& hull, const Transform& pose) {
  std::vector<Vec3> result;
  for (const Vec3& v : hull.vertices) result.push_back(pose.apply(v));
  return result;
}

// --- Closest points by clamping (Ericson, Real-Time Collision Detection, ch. 5)

inline Vec3 closestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t =
      ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return a + t * ab;
}

// Point–triangle: the projection onto the plane if it falls inside (all
// three edge tests agree), else the nearest of the three edges.
inline double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  if (n.squaredNorm() > 0.0) {
    const Vec3 q = p - n.dot(p - a) / n.squaredNorm() * n;
    const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                        (a - c).cross(q - c).dot(n) >= 0;
    if (inside) return (p - q).norm();
  }
  return std::min({(p - closestOnSegment(p, a, b)).norm(), (p - closestOnSegment(p, b, c)).norm(),
                   (p - closestOnSegment(p, c, a)).norm()});
}

// Segment–segment: |p(s) − q(t)|² is a convex quadratic on [0,1]²; its
// minimum is the interior stationary point if that lies in the square, else
// on one of the four sides, where it is a point–segment problem.
inline double segmentSegmentDistance(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                     const Vec3& q1) {
  const Vec3 d1 = p1 - p0;
  const Vec3 d2 = q1 - q0;
  const Vec3 r = p0 - q0;
  const double a = d1.dot(d1), b = d1.dot(d2), c = d2.dot(d2), d = d1.dot(r), e = d2.dot(r);
  const double det = a * c - b * b;
  if (det > 1e-14 * a * c) {
    const double s = (b * e - c * d) / det;
    const double t = (a * e - b * d) / det;
    if (s >= 0 && s <= 1 && t >= 0 && t <= 1) return (p0 + s * d1 - q0 - t * d2).norm();
  }
  return std::min(
      {(p0 - closestOnSegment(p0, q0, q1)).norm(), (p1 - closestOnSegment(p1, q0, q1)).norm(),
       (q0 - closestOnSegment(q0, p0, p1)).norm(), (q1 - closestOnSegment(q1, p0, p1)).norm()});
}

// Distance between two disjoint convex polytopes: the minimum over
// vertex–face pairs (both ways) and edge–edge pairs.
inline double bruteForcePolytopeDistance(const ConvexHull& hullA, const Transform& poseA,
                                         const ConvexHull& hullB, const Transform& poseB) {
  const auto va = worldVertices(hullA, poseA);
  const auto vb = worldVertices(hullB, poseB);
  double best = std::numeric_limits<double>::infinity();
  const auto vertexFace = [&best](const std::vector<Vec3>& points, const ConvexHull& hull,
                                  const std::vector<Vec3>& vertices) {
    for (const auto& face : hull.faces) {
      for (std::size_t i = 1; i + 1 < face.vertices.size(); ++i) {
        const Vec3& a = vertices[static_cast<std::size_t>(face.vertices[0])];
        const Vec3& b = vertices[static_cast<std::size_t>(face.vertices[i])];
        const Vec3& c = vertices[static_cast<std::size_t>(face.vertices[i + 1])];
        for (const Vec3& p : points) best = std::min(best, pointTriangleDistance(p, a, b, c));
      }
    }
  };
  vertexFace(va, hullB, vb);
  vertexFace(vb, hullA, va);
  for (const auto& ea : hullA.edges) {
    for (const auto& eb : hullB.edges) {
      best = std::min(best, segmentSegmentDistance(va[static_cast<std::size_t>(ea[0])],
                                                   va[static_cast<std::size_t>(ea[1])],
                                                   vb[static_cast<std::size_t>(eb[0])],
                                                   vb[static_cast<std::size_t>(eb[1])]));
    }
  }
  return best;
}

// Separating axes of two convex polytopes (face normals of each, cross
// products of edge pairs). For each unit axis n, how far B must move along
// n to clear A is max_A n·x − min_B n·x; the polytopes are disjoint iff some
// axis gives a negative value, and when they overlap the penetration depth
// is the smallest value over the axes.
struct SatResult {
  double depth = std::numeric_limits<double>::infinity();
  Vec3 axis = Vec3::UnitZ();
};
inline SatResult satDepth(const std::vector<Vec3>& va, const ConvexHull& hullA,
                          const Transform& poseA, const std::vector<Vec3>& vb,
                          const ConvexHull& hullB, const Transform& poseB) {
  std::vector<Vec3> axes;
  for (const auto& f : hullA.faces) axes.push_back(poseA.rotate(f.normal));
  for (const auto& f : hullB.faces) axes.push_back(-poseB.rotate(f.normal));
  for (const auto& ea : hullA.edges) {
    const Vec3 da = poseA.rotate(hullA.vertices[static_cast<std::size_t>(ea[1])] -
                                 hullA.vertices[static_cast<std::size_t>(ea[0])]);
    for (const auto& eb : hullB.edges) {
      const Vec3 db = poseB.rotate(hullB.vertices[static_cast<std::size_t>(eb[1])] -
                                   hullB.vertices[static_cast<std::size_t>(eb[0])]);
      const Vec3 c = da.cross(db);
      if (c.norm() > 1e-9 * da.norm() * db.norm()) {
        axes.push_back(c.normalized());
        axes.push_back(-c.normalized());
      }
    }
  }
  SatResult result;
  for (const Vec3& n : axes) {
    double maxA = -std::numeric_limits<double>::infinity();
    double minB = std::numeric_limits<double>::infinity();
    for (const Vec3& p : va) maxA = std::max(maxA, n.dot(p));
    for (const Vec3& p : vb) minB = std::min(minB, n.dot(p));
    if (maxA - minB < result.depth) {
      result.depth = maxA - minB;
      result.axis = n;
    }
  }
  return result;
}

inline bool insideHull(const ConvexHull& hull, const Transform& pose, const Vec3& worldPoint,
                       double tolerance) {
  const Vec3 local = pose.applyInverse(worldPoint);
  for (const auto& f : hull.faces) {
    if (f.normal.dot(local) > f.offset + tolerance) return false;
  }
  return true;
}

// Axis-aligned box [−h, h]^3 corners.
inline std::vector<Vec3> boxCorners(const Vec3& half) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                         (i & 4) ? half.z() : -half.z());
  }
  return corners;
}

}  // namespace rbsim::testing
