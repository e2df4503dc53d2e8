// Convex hulls by qhull: the structure (vertices, merged polygon faces,
// edges) against what a cube or a tetrahedron must give, invariants on
// random point sets, and the rejection of inputs without volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>
#include <string>

#include "geometry_test_helpers.h"
#include "physics/collision/convex_hull.h"
#include "rbsim/physics/shapes.h"

namespace rbsim {
namespace {

using testing::boxCorners;
using testing::randomPoints;

// Every face planar, convex, counter-clockwise seen from outside (each turn
// of the polygon has a positive component along the outward normal), all
// vertices behind every face, and Euler's V − E + F = 2.
void expectWellFormed(const ConvexHull& hull, const std::vector<Vec3>& input) {
  for (const auto& face : hull.faces) {
    EXPECT_NEAR(face.normal.norm(), 1.0, 1e-12);
    const std::size_t n = face.vertices.size();
    ASSERT_GE(n, 3u);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& a = hull.vertices[static_cast<std::size_t>(face.vertices[i])];
      const Vec3& b = hull.vertices[static_cast<std::size_t>(face.vertices[(i + 1) % n])];
      const Vec3& c = hull.vertices[static_cast<std::size_t>(face.vertices[(i + 2) % n])];
      EXPECT_NEAR(face.normal.dot(a), face.offset, 1e-9) << "vertex off its face plane";
      EXPECT_GT((b - a).cross(c - b).dot(face.normal), 0.0)
          << "face not counter-clockwise from outside";
    }
    for (const Vec3& p : input)
      EXPECT_LE(face.normal.dot(p), face.offset + 1e-9) << "input point outside a face";
  }
  EXPECT_EQ(static_cast<int>(hull.vertices.size()) - static_cast<int>(hull.edges.size()) +
                static_cast<int>(hull.faces.size()),
            2);
  std::set<std::array<int, 2>> unique(hull.edges.begin(), hull.edges.end());
  EXPECT_EQ(unique.size(), hull.edges.size()) << "an edge listed twice";
  for (const auto& e : hull.edges) EXPECT_LT(e[0], e[1]);
}

TEST(ConvexHull, CubeWithInteriorPointsHasEightVerticesSixQuadsTwelveEdges) {
  std::vector<Vec3> points = boxCorners(Vec3::Constant(0.5));
  // Interior points, points on faces and on an edge, and a duplicate corner.
  points.insert(points.end(), {Vec3(0.1, -0.2, 0.3), Vec3::Zero(), Vec3(0.0, 0.0, 0.5),
                               Vec3(0.5, 0.5, 0.0), Vec3(-0.5, -0.5, -0.5)});
  const auto hull = buildConvexHull(points, "cube");
  ASSERT_TRUE(hull.ok()) << hull.error().message;
  EXPECT_EQ(hull->vertices.size(), 8u);
  for (const Vec3& v : hull->vertices) EXPECT_DOUBLE_EQ(v.cwiseAbs().minCoeff(), 0.5);
  ASSERT_EQ(hull->faces.size(), 6u);
  std::set<std::array<int, 3>> normals;
  for (const auto& face : hull->faces) {
    EXPECT_EQ(face.vertices.size(), 4u);
    EXPECT_NEAR(face.normal.cwiseAbs().maxCoeff(), 1.0, 1e-12) << "normal not along an axis";
    EXPECT_NEAR(face.offset, 0.5, 1e-12);
    normals.insert({static_cast<int>(std::lround(face.normal.x())),
                    static_cast<int>(std::lround(face.normal.y())),
                    static_cast<int>(std::lround(face.normal.z()))});
  }
  EXPECT_EQ(normals.size(), 6u) << "the six outward normals ±x, ±y, ±z";
  EXPECT_EQ(hull->edges.size(), 12u);
  for (const auto& e : hull->edges) {
    // A cube edge joins corners that differ in exactly one coordinate.
    const Vec3 d = hull->vertices[static_cast<std::size_t>(e[0])] -
                   hull->vertices[static_cast<std::size_t>(e[1])];
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
  }
  expectWellFormed(*hull, points);
}

TEST(ConvexHull, TetrahedronHasFourTriangles) {
  const std::vector<Vec3> points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const auto hull = buildConvexHull(points, "tetra");
  ASSERT_TRUE(hull.ok()) << hull.error().message;
  EXPECT_EQ(hull->vertices.size(), 4u);
  EXPECT_EQ(hull->faces.size(), 4u);
  EXPECT_EQ(hull->edges.size(), 6u);
  // The slanted face x + y + z = 1 has the normal (1,1,1)/√3, outward.
  bool found = false;
  for (const auto& face : hull->faces) {
    if (face.normal.minCoeff() > 0) {
      found = true;
      EXPECT_NEAR((face.normal - Vec3::Constant(1.0 / std::sqrt(3.0))).norm(), 0.0, 1e-12);
      EXPECT_NEAR(face.offset, 1.0 / std::sqrt(3.0), 1e-12);
    }
  }
  EXPECT_TRUE(found);
  expectWellFormed(*hull, points);
}

TEST(ConvexHull, RandomPointSetsGiveConsistentPolyhedra) {
  scenes::SceneRandom random(7);
  for (int trial = 0; trial < 20; ++trial) {
    const auto points = randomPoints(random, 5 + trial * 7, Vec3(1.0, 0.6, 0.3));
    const auto hull = buildConvexHull(points, "random");
    ASSERT_TRUE(hull.ok()) << hull.error().message;
    expectWellFormed(*hull, points);
    // Only hull vertices are kept, and each is an input point.
    for (const Vec3& v : hull->vertices) {
      EXPECT_TRUE(std::find(points.begin(), points.end(), v) != points.end());
    }
  }
}

TEST(ConvexHull, HullIsIndependentOfInputOrder) {
  scenes::SceneRandom random(11);
  auto points = randomPoints(random, 40, Vec3::Ones());
  const auto first = buildConvexHull(points, "forward");
  std::reverse(points.begin(), points.end());
  const auto second = buildConvexHull(points, "reversed");
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_EQ(first->faces.size(), second->faces.size());
  EXPECT_EQ(first->edges.size(), second->edges.size());
  std::set<std::array<double, 3>> a, b;
  for (const Vec3& v : first->vertices) a.insert({v.x(), v.y(), v.z()});
  for (const Vec3& v : second->vertices) b.insert({v.x(), v.y(), v.z()});
  EXPECT_EQ(a, b);
}

void expectRejected(const std::vector<Vec3>& points, const std::string& reason) {
  ::testing::internal::CaptureStdout();
  const auto hull = buildConvexHull(points, "parts/widget.obj");
  const std::string printed = ::testing::internal::GetCapturedStdout();
  ASSERT_FALSE(hull.ok());
  EXPECT_NE(hull.error().message.find("parts/widget.obj"), std::string::npos)
      << hull.error().message;
  EXPECT_NE(hull.error().message.find(reason), std::string::npos) << hull.error().message;
  EXPECT_TRUE(printed.empty()) << "printed to stdout: " << printed;
}

TEST(ConvexHull, RejectsInputsWithoutVolume) {
  expectRejected({}, "at least 4 distinct points, got 0");
  expectRejected({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                 "at least 4 distinct points, got 3");
  expectRejected(std::vector<Vec3>(10, Vec3(1, 2, 3)), "at least 4 distinct points, got 1");
  // Ten points, but only three distinct ones.
  std::vector<Vec3> triple;
  for (int i = 0; i < 10; ++i) triple.push_back(Vec3(i % 3, (i % 3) * 2.0, 0.0));
  expectRejected(triple, "at least 4 distinct points, got 3");

  std::vector<Vec3> line;
  for (int i = 0; i < 6; ++i) line.push_back(Vec3(1, 1, 1) * i + Vec3(0.5, 0, 0));
  expectRejected(line, "collinear");

  std::vector<Vec3> plane;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) plane.push_back(Vec3(i, j, 0.0));
  // The same grid tilted out of every coordinate plane.
  const Mat3 tilt = Quaternion::fromRollPitchYaw(0.3, -0.7, 1.1).toRotationMatrix();
  for (Vec3& p : plane) p = tilt * p + Vec3(3, -2, 1);
  expectRejected(plane, "coplanar");

  std::vector<Vec3> withNan = boxCorners(Vec3::Ones());
  withNan.push_back(Vec3(std::nan(""), 0, 0));
  expectRejected(withNan, "non-finite");
}

// The largest distance of `point` above the planes of the hull's faces.
double outsideOf(const ConvexHull& hull, const Vec3& point) {
  double outside = -1e300;
  for (const ConvexHull::Face& face : hull.faces)
    outside = std::max(outside, face.normal.dot(point) - face.offset);
  return outside;
}

std::vector<Vec3> pointsOnEllipsoid(int count, const Vec3& axes, unsigned seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> gauss;
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i)
    points.push_back(Vec3(gauss(random), gauss(random), gauss(random)).normalized().cwiseProduct(axes));
  return points;
}

TEST(SimplifiedHull, HoldsTheFullHullWithinItsToleranceWithFewerVertices) {
  const std::vector<Vec3> points = pointsOnEllipsoid(576, Vec3(0.1, 0.06, 0.15), 7);
  const auto full = buildConvexHull(points, "full");
  ASSERT_TRUE(static_cast<bool>(full));
  for (const double tolerance : {0.0005, 0.002, 0.01}) {
    const auto simplified = simplifiedConvexHullMesh(points, 1000, tolerance, "simplified");
    ASSERT_TRUE(static_cast<bool>(simplified));
    EXPECT_EQ(simplified->fullVertexCount, full->vertices.size());
    EXPECT_LE(simplified->outside, tolerance);
    const auto hull = buildConvexHull(simplified->mesh.vertices, "check");
    ASSERT_TRUE(static_cast<bool>(hull));
    EXPECT_LT(hull->vertices.size(), full->vertices.size()) << "tolerance " << tolerance;
    RecordProperty("vertices_at_" + std::to_string(tolerance), static_cast<int>(hull->vertices.size()));
    // Every vertex of the full hull within the tolerance of the simplified
    // hull's planes, and the reported distance is the largest.
    double largest = 0.0;
    for (const Vec3& v : full->vertices) largest = std::max(largest, outsideOf(*hull, v));
    EXPECT_LE(largest, tolerance + 1e-12);
    EXPECT_NEAR(largest, simplified->outside, 1e-12);
    // Its vertices are the full hull's own: an inner hull, never larger.
    for (const Vec3& v : simplified->mesh.vertices)
      EXPECT_LE(outsideOf(*full, v), 1e-12);
  }
}

TEST(SimplifiedHull, TheVertexBudgetEndsTheGrowthAndSaysHowFarOff) {
  const std::vector<Vec3> points = pointsOnEllipsoid(576, Vec3(0.1, 0.1, 0.1), 8);
  const auto simplified = simplifiedConvexHullMesh(points, 24, 0.0, "budget");
  ASSERT_TRUE(static_cast<bool>(simplified));
  EXPECT_LE(simplified->mesh.vertices.size(), 24u);
  // 24 points cannot hold a 576-point sphere of radius 0.1 m to 1 mm.
  EXPECT_GT(simplified->outside, 0.001);
  const auto hull = buildConvexHull(simplified->mesh.vertices, "check");
  ASSERT_TRUE(static_cast<bool>(hull));
  double largest = 0.0;
  for (const Vec3& v : points) largest = std::max(largest, outsideOf(*hull, v));
  EXPECT_NEAR(largest, simplified->outside, 1e-12);
}

TEST(SimplifiedHull, ZeroToleranceKeepsEveryVertexOfACube) {
  std::vector<Vec3> cube;
  for (int i = 0; i < 8; ++i) cube.push_back(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
  const auto simplified = simplifiedConvexHullMesh(cube, 100, 0.0, "cube");
  ASSERT_TRUE(static_cast<bool>(simplified));
  EXPECT_EQ(simplified->mesh.vertices.size(), 8u);
  EXPECT_EQ(simplified->outside, 0.0);
  EXPECT_FALSE(static_cast<bool>(simplifiedConvexHullMesh(cube, 100, -1.0, "cube")));
  EXPECT_FALSE(static_cast<bool>(simplifiedConvexHullMesh(cube, 3, 0.0, "cube")));
}

}  // namespace
}  // namespace rbsim
