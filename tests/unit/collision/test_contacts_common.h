#pragma once
// Shared by the contact tests: solids placed in the world, hand-built hulls,
// and comparisons of manifolds.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "physics/collision/contact_generation.h"
#include "physics/collision/convex_hull.h"

namespace rbsim::testing {

inline constexpr double kTight = 1e-9;  // m: exact up to rounding
inline constexpr double kPi = std::numbers::pi;

inline Mat3 rotationAbout(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// A geometry and its pose, owning the geometry so that PlacedConvex can
// point at it.
struct Solid {
  ConvexGeometry geometry;
  Transform pose;

  PlacedConvex placed() const { return {&geometry, pose}; }
};

inline Solid solid(ConvexGeometry geometry, const Vec3& position,
                   const Mat3& rotation = Mat3::Identity()) {
  return {std::move(geometry), Transform{rotation, position}};
}

inline ContactManifold collide(const Solid& a, const Solid& b, double margin = 0.005) {
  ContactManifold manifold;
  collideConvex(a.placed(), b.placed(), ContactSettings{margin}, manifold);
  return manifold;
}

inline ContactManifold collidePlane(const Vec3& normal, double offset, const Solid& b,
                                    double margin = 0.005) {
  ContactManifold manifold;
  collidePlaneConvex(normal, offset, b.placed(), ContactSettings{margin}, manifold);
  return manifold;
}

// A hull from vertices and faces given as vertex loops in any winding: the
// loops are turned counter-clockwise seen from outside, the normals, offsets
// and edge list computed, independently of the library's own box tables.
inline std::shared_ptr<const ConvexHull> makeHull(const std::vector<Vec3>& vertices,
                                                  std::vector<std::vector<int>> faces) {
  auto hull = std::make_shared<ConvexHull>();
  hull->vertices = vertices;
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& v : vertices) centroid += v;
  centroid /= static_cast<double>(vertices.size());
  for (std::vector<int>& loop : faces) {
    const Vec3& p0 = vertices[static_cast<std::size_t>(loop[0])];
    Vec3 normal = (vertices[static_cast<std::size_t>(loop[1])] - p0)
                      .cross(vertices[static_cast<std::size_t>(loop[2])] - p0)
                      .normalized();
    if (normal.dot(p0 - centroid) < 0.0) {
      std::reverse(loop.begin(), loop.end());
      normal = -normal;
    }
    hull->faces.push_back({normal, normal.dot(p0), loop});
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k];
      const int b = loop[(k + 1) % loop.size()];
      if (a < b) hull->edges.push_back({a, b});
    }
  }
  computeHullTopology(*hull);
  return hull;
}

// A box as a hull, numbered unlike the library's box tables (vertices in
// another order, faces starting at other corners), so that comparing it
// with the box routine compares two independent paths.
inline std::shared_ptr<const ConvexHull> cubeHull(const Vec3& h) {
  std::vector<Vec3> vertices;
  for (const double z : {h.z(), -h.z()}) {
    vertices.push_back({h.x(), h.y(), z});
    vertices.push_back({-h.x(), h.y(), z});
    vertices.push_back({-h.x(), -h.y(), z});
    vertices.push_back({h.x(), -h.y(), z});
  }
  return makeHull(
      vertices,
      {{0, 1, 2, 3}, {5, 6, 7, 4}, {1, 0, 4, 5}, {2, 1, 5, 6}, {3, 2, 6, 7}, {0, 3, 7, 4}});
}

inline void expectNear(const Vec3& actual, const Vec3& expected, double tolerance) {
  EXPECT_NEAR((actual - expected).norm(), 0.0, tolerance)
      << "actual (" << actual.transpose() << "), expected (" << expected.transpose() << ")";
}

inline std::vector<double> sortedDepths(const ContactManifold& manifold) {
  std::vector<double> depths;
  for (int i = 0; i < manifold.pointCount; ++i) {
    depths.push_back(manifold.points[static_cast<std::size_t>(i)].depth);
  }
  std::sort(depths.begin(), depths.end());
  return depths;
}

// The point of the manifold whose point on B is nearest `pointB`.
inline const ContactPoint& nearestPoint(const ContactManifold& manifold, const Vec3& pointB) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < static_cast<std::size_t>(manifold.pointCount); ++i) {
    if ((manifold.points[i].pointB - pointB).norm() <
        (manifold.points[best].pointB - pointB).norm()) {
      best = i;
    }
  }
  return manifold.points[best];
}

// Every expected point on B is in the manifold with this depth, and the
// point on A lies `depth` along the normal from it.
inline void expectPoints(const ContactManifold& manifold, const std::vector<Vec3>& pointsB,
                         double depth, double tolerance = kTight) {
  ASSERT_EQ(manifold.pointCount, static_cast<int>(pointsB.size()));
  for (const Vec3& expected : pointsB) {
    const ContactPoint& point = nearestPoint(manifold, expected);
    expectNear(point.pointB, expected, tolerance);
    EXPECT_NEAR(point.depth, depth, tolerance);
    expectNear(point.pointA, expected + depth * manifold.normal, tolerance);
  }
}

// Two manifolds of the same pair describe the same contact: same normal and
// the same points (in any order).
inline void expectSameManifold(const ContactManifold& actual, const ContactManifold& expected,
                               double tolerance = 1e-9) {
  ASSERT_EQ(actual.pointCount, expected.pointCount);
  expectNear(actual.normal, expected.normal, tolerance);
  for (int i = 0; i < expected.pointCount; ++i) {
    const ContactPoint& want = expected.points[static_cast<std::size_t>(i)];
    const ContactPoint& got = nearestPoint(actual, want.pointB);
    expectNear(got.pointB, want.pointB, tolerance);
    expectNear(got.pointA, want.pointA, tolerance);
    EXPECT_NEAR(got.depth, want.depth, tolerance);
  }
}

// collideConvex(a, b) and (b, a) describe the same contact seen from either side.
inline void expectSymmetric(const Solid& a, const Solid& b, double tolerance = 1e-9) {
  const ContactManifold ab = collide(a, b);
  const ContactManifold ba = collide(b, a);
  ASSERT_GT(ab.pointCount, 0);
  ASSERT_EQ(ab.pointCount, ba.pointCount);
  expectNear(ba.normal, -ab.normal, tolerance);
  const std::vector<double> depthsAB = sortedDepths(ab);
  const std::vector<double> depthsBA = sortedDepths(ba);
  for (std::size_t i = 0; i < depthsAB.size(); ++i) {
    EXPECT_NEAR(depthsAB[i], depthsBA[i], tolerance);
  }
}

}  // namespace rbsim::testing
