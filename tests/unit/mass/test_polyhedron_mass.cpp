// Exact polyhedron mass properties (Mirtich), mesh validation, the Monte
// Carlo cross-check and principal axes, each against an expectation
// derived independently of the code under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "rbsim/physics/triangle_mesh.h"
#include "rbsim/physics/mass_properties.h"
#include "support/monte_carlo_mass.h"

namespace rbsim {
namespace {

constexpr double kRelTol = 1e-12;

void expectRelNear(double actual, double expected, double relTol = kRelTol) {
  EXPECT_NEAR(actual, expected, relTol * std::abs(expected)) << "expected " << expected;
}

void expectMatrixNear(const Mat3& actual, const Mat3& expected, double relTol = kRelTol) {
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), relTol * scale) << "actual\n"
                                                                       << actual << "\nexpected\n"
                                                                       << expected;
}

void expectVecNear(const Vec3& actual, const Vec3& expected, double absTol) {
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), absTol)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

// Box [center − h, center + h] as 8 vertices and 12 triangles, counter-
// clockwise seen from outside. Vertex i sits at the corner with
// x = bit 0, y = bit 1, z = bit 2 of i (0 = low side).
TriangleMesh makeBoxMesh(const Vec3& halfExtents, const Vec3& center = Vec3::Zero()) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    const Vec3 sign((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    mesh.vertices.push_back(center + sign.cwiseProduct(halfExtents));
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

TriangleMesh makeTetrahedronMesh(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  // Outward when (p1 − p0, p2 − p0, p3 − p0) is right-handed.
  return {{p0, p1, p2, p3}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
}

// An L-shaped prism, z in [0, height]: the union of the boxes
// [0, 2] × [0, 1] and [0, 1] × [1, 3] in x, y. Non-convex, which matters for
// the point-in-mesh test of the Monte Carlo estimate.
TriangleMesh makeLPrismMesh(double height) {
  const double outline[6][2] = {{1, 1}, {1, 3}, {0, 3}, {0, 0}, {2, 0}, {2, 1}};  // CCW
  TriangleMesh mesh;
  for (const auto& p : outline) mesh.vertices.emplace_back(p[0], p[1], 0.0);
  for (const auto& p : outline) mesh.vertices.emplace_back(p[0], p[1], height);
  // Vertex 0 is the reflex corner (1, 1), which sees the whole outline, so
  // a fan from it triangulates the caps.
  for (int k = 1; k + 1 < 6; ++k) {
    mesh.triangles.push_back({0, k + 1, k});      // bottom, facing −z
    mesh.triangles.push_back({6, 6 + k, 7 + k});  // top, facing +z
  }
  for (int k = 0; k < 6; ++k) {
    const int next = (k + 1) % 6;
    mesh.triangles.push_back({k, next, 6 + next});
    mesh.triangles.push_back({k, 6 + next, 6 + k});
  }
  return mesh;
}

// The L prism's exact properties assembled from its two boxes with the
// parallel-axis theorem, written out here rather than via shiftInertia.
MassProperties lPrismByBoxes(double height, double density) {
  struct Part {
    Vec3 half, center;
  };
  const Part parts[2] = {{Vec3(1.0, 0.5, height / 2), Vec3(1.0, 0.5, height / 2)},
                         {Vec3(0.5, 1.0, height / 2), Vec3(0.5, 2.0, height / 2)}};
  MassProperties total;
  Mat3 aboutOrigin = Mat3::Zero();
  Vec3 moment = Vec3::Zero();
  for (const Part& part : parts) {
    const Vec3 side = 2.0 * part.half;
    const double m = density * side.prod();
    const Vec3 s2 = side.cwiseProduct(side);
    Mat3 own = Mat3::Zero();
    own.diagonal() = m / 12.0 * Vec3(s2.y() + s2.z(), s2.z() + s2.x(), s2.x() + s2.y());
    const Vec3& c = part.center;
    aboutOrigin += own + m * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
    total.volume += side.prod();
    total.mass += m;
    moment += m * c;
  }
  total.centerOfMass = moment / total.mass;
  const Vec3& c = total.centerOfMass;
  total.inertia =
      aboutOrigin - total.mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
  return total;
}

void expectMatchesBox(const MassProperties& props, const Vec3& halfExtents, const Vec3& center,
                      double density, double relTol = kRelTol) {
  const MassProperties box = boxMassProperties(halfExtents, density);
  expectRelNear(props.volume, box.volume, relTol);
  expectRelNear(props.mass, box.mass, relTol);
  expectVecNear(props.centerOfMass, center, relTol * halfExtents.norm());
  expectMatrixNear(props.inertia, box.inertia, relTol);
}

Mat3 rotationAbout(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// ---------------------------------------------------------------- tetrahedra

TEST(PolyhedronMass, UnitTetrahedron) {
  // Vertices 0, e_x, e_y, e_z. V = 1/6, centroid (1/4, 1/4, 1/4). Second
  // moments about the origin (ρ = 1): ∫x² = 1/60, ∫xy = 1/120, so
  // Ixx = ∫(y² + z²) = 1/30 and Ixy = −1/120. About the centroid:
  // Ixx = 1/30 − (1/6)(1/16 + 1/16) = 1/80, Ixy = −1/120 + (1/6)(1/16) = 1/480.
  const TriangleMesh mesh =
      makeTetrahedronMesh(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ());
  ASSERT_TRUE(validateClosedMesh(mesh, "tetrahedron").ok());
  const double density = 2.5;
  const MassProperties props = polyhedronMassProperties(mesh, density);
  expectRelNear(props.volume, 1.0 / 6.0);
  expectRelNear(props.mass, density / 6.0);
  expectVecNear(props.centerOfMass, Vec3::Constant(0.25), 1e-15);
  Mat3 expected = Mat3::Constant(1.0 / 480.0);
  expected.diagonal().setConstant(1.0 / 80.0);
  expectMatrixNear(props.inertia, density * expected);
}

// Second moments of a tetrahedron by the covariance formula (Tonon 2004;
// Blow and Binstock, "How to find the inertia tensor (or other mass
// properties) of a 3D solid body represented by a triangle mesh"):
//   ∫ x xᵀ dV = V/20 (Σ_i v_i v_iᵀ + s sᵀ), s = Σ_i v_i.
MassProperties tetrahedronByCovariance(const std::vector<Vec3>& v, double density) {
  const double volume = (v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0])) / 6.0;
  const Vec3 s = v[0] + v[1] + v[2] + v[3];
  Mat3 covariance = s * s.transpose();
  for (const Vec3& p : v) covariance += p * p.transpose();
  covariance *= density * volume / 20.0;
  MassProperties props;
  props.volume = volume;
  props.mass = density * volume;
  props.centerOfMass = s / 4.0;
  const Vec3& c = props.centerOfMass;
  const Mat3 aboutOrigin = covariance.trace() * Mat3::Identity() - covariance;
  props.inertia =
      aboutOrigin - props.mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
  return props;
}

TEST(PolyhedronMass, IrregularRotatedTetrahedraMatchCovarianceFormula) {
  // Rotations make every face pick each projection plane in turn.
  const std::vector<Vec3> base = {Vec3(0.3, -0.2, 1.1), Vec3(2.1, 0.4, 0.9), Vec3(0.7, 1.9, 1.3),
                                  Vec3(0.9, 0.6, 2.8)};
  for (double angle : {0.0, 0.4, 1.3, 2.2, -2.9}) {
    SCOPED_TRACE(testing::Message() << "angle " << angle);
    const Mat3 rotation = rotationAbout(Vec3(1.0, -2.0, 0.5), angle);
    std::vector<Vec3> v;
    for (const Vec3& p : base) v.push_back(rotation * p + Vec3(-3.0, 1.0, 4.0));
    const TriangleMesh mesh = makeTetrahedronMesh(v[0], v[1], v[2], v[3]);
    ASSERT_TRUE(validateClosedMesh(mesh, "tetrahedron").ok());
    const MassProperties expected = tetrahedronByCovariance(v, 700.0);
    const MassProperties props = polyhedronMassProperties(mesh, 700.0);
    expectRelNear(props.volume, expected.volume);
    expectRelNear(props.mass, expected.mass);
    expectVecNear(props.centerOfMass, expected.centerOfMass, 1e-14);
    expectMatrixNear(props.inertia, expected.inertia);
  }
}

// ----------------------------------------------------------------- boxes

TEST(PolyhedronMass, CubeMatchesBoxClosedForm) {
  const TriangleMesh mesh = makeBoxMesh(Vec3::Constant(0.5));
  ASSERT_TRUE(validateClosedMesh(mesh, "cube").ok());
  expectMatchesBox(polyhedronMassProperties(mesh, 1000.0), Vec3::Constant(0.5), Vec3::Zero(),
                   1000.0);
}

TEST(PolyhedronMass, UnequalBoxMatchesBoxClosedForm) {
  const Vec3 half(0.1, 0.7, 2.3), center(0.3, -1.2, 5.0);
  const TriangleMesh mesh = makeBoxMesh(half, center);
  ASSERT_TRUE(validateClosedMesh(mesh, "box").ok());
  expectMatchesBox(polyhedronMassProperties(mesh, 1200.0), half, center, 1200.0);
}

TEST(PolyhedronMass, CubeFarFromOriginKeepsPrecision) {
  // Tolerance: the vertex coordinates ~1e6 m are rounded to half an ulp,
  // 2^-34 ≈ 5.8e-11 m, so each side of 2 m can be off by up to 1.2e-10 m
  // (5.8e-11 relative). The rounded mesh is still an exact axis-aligned box,
  // and its volume (3 sides) and inertia (m·L², 5 sides) differ from the
  // nominal box by up to ~3e-10 relative: 1e-9 leaves a margin of 3.
  // Integrating about the origin instead would compute an inertia of
  // ~1 kg·m² as a difference of terms of order 1e18 and fail by far.
  const Vec3 half = Vec3::Ones();
  const Vec3 center(1e6 + 0.3, -1e6 + 0.7, 1e6 + 0.1);
  const TriangleMesh mesh = makeBoxMesh(half, center);
  ASSERT_TRUE(validateClosedMesh(mesh, "far cube").ok());
  const MassProperties props = polyhedronMassProperties(mesh, 1.0);
  const MassProperties box = boxMassProperties(half, 1.0);
  expectRelNear(props.volume, box.volume, 1e-9);
  expectMatrixNear(props.inertia, box.inertia, 1e-9);
  expectVecNear(props.centerOfMass, center, 1e-9);  // 1e-15 relative to |center|

  // Against the box the rounded vertices actually describe, only the
  // integration's own round-off remains.
  const Vec3 actualHalf = 0.5 * (mesh.vertices[7] - mesh.vertices[0]);
  const MassProperties actualBox = boxMassProperties(actualHalf, 1.0);
  expectRelNear(props.volume, actualBox.volume, 1e-13);
  expectMatrixNear(props.inertia, actualBox.inertia, 1e-13);
}

TEST(PolyhedronMass, LPrismMatchesTwoBoxes) {
  const TriangleMesh mesh = makeLPrismMesh(0.5);
  ASSERT_TRUE(validateClosedMesh(mesh, "L prism").ok());
  const MassProperties expected = lPrismByBoxes(0.5, 3.0);
  const MassProperties props = polyhedronMassProperties(mesh, 3.0);
  expectRelNear(props.volume, expected.volume);
  expectRelNear(props.mass, expected.mass);
  expectVecNear(props.centerOfMass, expected.centerOfMass, 1e-14);
  expectMatrixNear(props.inertia, expected.inertia);
}

// ------------------------------------------------------------ validation

void expectInvalid(const TriangleMesh& mesh, const std::string& expectedText) {
  const Expected<bool> result = validateClosedMesh(mesh, "meshes/part.obj");
  ASSERT_FALSE(result.ok()) << "expected an error containing: " << expectedText;
  const std::string& message = result.error().message;
  EXPECT_EQ(message.rfind("meshes/part.obj: ", 0), 0u) << message;
  EXPECT_NE(message.find(expectedText), std::string::npos) << message;
}

TEST(ValidateClosedMesh, InvertedCubeIsRejected) {
  TriangleMesh mesh = makeBoxMesh(Vec3::Constant(0.5));
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  expectInvalid(mesh, "the winding is inverted");
}

TEST(ValidateClosedMesh, ReflectionTurnsTheMeshInsideOut) {
  const TriangleMesh mirrored = transformed(makeBoxMesh(Vec3::Constant(0.5)),
                                            Vec3(-1.0, 1.0, 1.0).asDiagonal(), Vec3::Zero());
  expectInvalid(mirrored, "the winding is inverted");
}

TEST(ValidateClosedMesh, OpenMeshIsRejected) {
  TriangleMesh mesh = makeBoxMesh(Vec3::Constant(0.5));
  mesh.triangles.pop_back();
  expectInvalid(mesh, "mesh is open: edge");
}

TEST(ValidateClosedMesh, InconsistentWindingIsRejected) {
  TriangleMesh mesh = makeBoxMesh(Vec3::Constant(0.5));
  std::swap(mesh.triangles[0][1], mesh.triangles[0][2]);
  std::swap(mesh.triangles[1][1], mesh.triangles[1][2]);  // the whole −z face
  expectInvalid(mesh, "inconsistent winding: triangles");
}

TEST(ValidateClosedMesh, NonManifoldEdgeIsRejected) {
  // Two tetrahedra sharing the edge 0-1 and nothing else: that edge has
  // four triangles.
  TriangleMesh mesh =
      makeTetrahedronMesh(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ());
  mesh.vertices.emplace_back(0.0, -1.0, 0.0);
  mesh.vertices.emplace_back(0.0, 0.0, -1.0);
  const TriangleMesh second =
      makeTetrahedronMesh(Vec3::Zero(), Vec3::UnitX(), Vec3(0, -1, 0), Vec3(0, 0, -1));
  for (auto t : second.triangles) {
    for (int& i : t) i = (i == 2) ? 4 : (i == 3) ? 5 : i;
    mesh.triangles.push_back(t);
  }
  ASSERT_TRUE(validateClosedMesh(second, "second").ok());
  expectInvalid(mesh, "is shared by 4 triangles");
}

TEST(ValidateClosedMesh, RepeatedVertexIsRejected) {
  TriangleMesh mesh = makeBoxMesh(Vec3::Constant(0.5));
  mesh.triangles[3] = {2, 5, 2};
  expectInvalid(mesh, "triangle 3 is degenerate: it repeats a vertex");
}

TEST(ValidateClosedMesh, ZeroAreaTriangleIsRejected) {
  TriangleMesh mesh = makeBoxMesh(Vec3::Constant(0.5));
  mesh.vertices.push_back(0.5 * (mesh.vertices[0] + mesh.vertices[1]));  // on edge 0-1
  mesh.triangles.push_back({0, 8, 1});
  expectInvalid(mesh, "triangle 12 is degenerate: zero area");
}

TEST(ValidateClosedMesh, OutOfRangeIndexIsRejected) {
  TriangleMesh mesh = makeBoxMesh(Vec3::Constant(0.5));
  mesh.triangles[5][1] = 8;
  expectInvalid(mesh, "triangle 5 has vertex index 8 out of range (8 vertices)");
  mesh.triangles[5][1] = -1;
  expectInvalid(mesh, "triangle 5 has vertex index -1 out of range (8 vertices)");
}

TEST(ValidateClosedMesh, FlatClosedMeshIsRejected) {
  // A tetrahedron squashed into the plane z = 0: closed, consistently wound,
  // no degenerate triangle, but no volume.
  const TriangleMesh flat =
      makeTetrahedronMesh(Vec3::Zero(), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0.5, 0.5, 0.0));
  expectInvalid(flat, "encloses no volume");
}

TEST(ValidateClosedMesh, EmptyMeshIsRejected) {
  expectInvalid(TriangleMesh{}, "no triangles");
}

// ----------------------------------------------------------- Monte Carlo

TEST(MonteCarloMass, LPrismWithinFourStandardErrors) {
  const TriangleMesh mesh = makeLPrismMesh(0.5);
  const MassProperties exact = lPrismByBoxes(0.5, 3.0);
  const int samples = 200000;
  const MonteCarloMassProperties mc = monteCarloMassProperties(mesh, 3.0, samples, 20240611ull);
  EXPECT_EQ(mc.samples, samples);

  const MassProperties& est = mc.estimate;
  const MassProperties& se = mc.standardError;
  EXPECT_LE(std::abs(est.volume - exact.volume), 4.0 * se.volume);
  EXPECT_LE(std::abs(est.mass - exact.mass), 4.0 * se.mass);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LE(std::abs(est.centerOfMass[k] - exact.centerOfMass[k]), 4.0 * se.centerOfMass[k])
        << "axis " << k;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_LE(std::abs(est.inertia(i, j) - exact.inertia(i, j)), 4.0 * se.inertia(i, j))
          << "element " << i << j;
    }
  }

  // The errors themselves: the solid fills p = 2/3 of its bounding box
  // (2 × 3 × 0.5 m = 3 m³), so SE(V) must be 3 sqrt(p (1 − p)/N) (binomial), and
  // all errors must be small enough for the comparison above to mean
  // something (~1/sqrt(N) relative).
  const double p = exact.volume / 3.0;
  expectRelNear(se.volume, 3.0 * std::sqrt(p * (1.0 - p) / samples), 0.01);
  EXPECT_NEAR(static_cast<double>(mc.insideSamples) / samples, p,
              4.0 * std::sqrt(p * (1 - p) / samples));
  EXPECT_LT(se.centerOfMass.maxCoeff(), 0.005);
  EXPECT_LT(se.inertia.maxCoeff(), 0.01 * exact.inertia.cwiseAbs().maxCoeff());
  EXPECT_GT(se.inertia.minCoeff(), 0.0);
}

TEST(MonteCarloMass, StandardErrorsAreCalibrated) {
  // Over many independent seeds, z = (estimate − exact)/SE should have a
  // root mean square of 1. The groups are kept apart because the mistakes
  // they catch differ. Leaving the mass uncertainty out of the inertia's
  // error (taking the spread of the inside points only) barely changes the
  // products of inertia but underestimates the error of the moments, whose
  // mean is large next to their spread, by sqrt(1 + (1 − p) mean²/variance).
  // A tetrahedron fills only p = 1/6 of its bounding box, which makes that
  // factor large (RMS ≈ 1.4 instead of 1). With 200 runs each RMS is known
  // to about ±0.05.
  const std::vector<Vec3> v = {Vec3(0.3, -0.2, 1.1), Vec3(2.1, 0.4, 0.9), Vec3(0.7, 1.9, 1.3),
                               Vec3(0.9, 0.6, 2.8)};
  const TriangleMesh mesh = makeTetrahedronMesh(v[0], v[1], v[2], v[3]);
  const MassProperties exact = tetrahedronByCovariance(v, 3.0);
  double volumeZ2 = 0.0, centerZ2 = 0.0, momentZ2 = 0.0, productZ2 = 0.0;
  const int runs = 200;
  for (int run = 0; run < runs; ++run) {
    const MonteCarloMassProperties mc =
        monteCarloMassProperties(mesh, 3.0, 2000, 1000ull + static_cast<unsigned long long>(run));
    const MassProperties& se = mc.standardError;
    const double zv = (mc.estimate.volume - exact.volume) / se.volume;
    volumeZ2 += zv * zv;
    centerZ2 += (mc.estimate.centerOfMass - exact.centerOfMass)
                    .cwiseQuotient(se.centerOfMass)
                    .squaredNorm();
    const Mat3 z = (mc.estimate.inertia - exact.inertia).cwiseQuotient(se.inertia);
    momentZ2 += z.diagonal().squaredNorm();
    productZ2 += z(0, 1) * z(0, 1) + z(1, 2) * z(1, 2) + z(2, 0) * z(2, 0);
  }
  const double volumeRms = std::sqrt(volumeZ2 / runs);
  const double centerRms = std::sqrt(centerZ2 / (3 * runs));
  const double momentRms = std::sqrt(momentZ2 / (3 * runs));
  const double productRms = std::sqrt(productZ2 / (3 * runs));
  for (double rms : {volumeRms, centerRms, momentRms, productRms}) {
    EXPECT_GT(rms, 0.85) << "volume " << volumeRms << ", centre " << centerRms << ", moments "
                         << momentRms << ", products " << productRms;
    EXPECT_LT(rms, 1.15) << "volume " << volumeRms << ", centre " << centerRms << ", moments "
                         << momentRms << ", products " << productRms;
  }
}

TEST(MonteCarloMass, SameSeedSameResult) {
  const TriangleMesh mesh = makeLPrismMesh(0.5);
  const MonteCarloMassProperties a = monteCarloMassProperties(mesh, 1.0, 5000, 7ull);
  const MonteCarloMassProperties b = monteCarloMassProperties(mesh, 1.0, 5000, 7ull);
  const MonteCarloMassProperties c = monteCarloMassProperties(mesh, 1.0, 5000, 8ull);
  EXPECT_EQ(a.insideSamples, b.insideSamples);
  EXPECT_EQ(a.estimate.inertia, b.estimate.inertia);
  EXPECT_NE(a.estimate.inertia, c.estimate.inertia);
}

// ---------------------------------------------------------- principal axes

TEST(PrincipalAxes, RotatedBoxMesh) {
  // Box half extents (0.3, 0.5, 0.9): its moments about x, y, z are
  // m/3 (0.25 + 0.81), m/3 (0.09 + 0.81), m/3 (0.09 + 0.25), so in
  // ascending order the axes are the box's z, y, x.
  const Vec3 half(0.3, 0.5, 0.9);
  const Mat3 rotation = rotationAbout(Vec3(0.3, 1.0, -0.6), 0.85);
  const TriangleMesh mesh = transformed(makeBoxMesh(half), rotation, Vec3(4.0, -2.0, 1.0));
  ASSERT_TRUE(validateClosedMesh(mesh, "rotated box").ok());
  const MassProperties props = polyhedronMassProperties(mesh, 500.0);
  const PrincipalAxes principal = principalAxes(props.inertia);

  const double m = 500.0 * 8.0 * half.prod();
  const Vec3 expectedMoments(m / 3.0 * 0.34, m / 3.0 * 0.90, m / 3.0 * 1.06);
  for (int k = 0; k < 3; ++k) expectRelNear(principal.moments[k], expectedMoments[k]);
  const int boxAxis[3] = {2, 1, 0};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(std::abs(principal.axes.col(k).dot(rotation.col(boxAxis[k]))), 1.0, 1e-12)
        << "principal axis " << k;
  }
  EXPECT_NEAR(principal.axes.determinant(), 1.0, 1e-12);
  EXPECT_LE((principal.axes.transpose() * principal.axes - Mat3::Identity()).cwiseAbs().maxCoeff(),
            1e-12);
  expectMatrixNear(principal.axes * principal.moments.asDiagonal() * principal.axes.transpose(),
                   props.inertia);
}

TEST(PrincipalAxes, DiagonalTensorKeepsIdentityAxes) {
  // Also with two equal moments, where any axis in their plane is principal.
  for (const Vec3& diagonal : {Vec3(3.0, 1.0, 2.0), Vec3(1.0, 1.0, 0.4)}) {
    Mat3 inertia = diagonal.asDiagonal();
    inertia(0, 1) = inertia(1, 0) = 1e-13 * inertia.trace();  // below 1e-12 of the trace
    const PrincipalAxes principal = principalAxes(inertia);
    EXPECT_EQ(principal.axes, Mat3::Identity());
    EXPECT_EQ(principal.moments, diagonal);
  }
}

TEST(PrincipalAxes, DegenerateRotatedTensorGivesProperRotation) {
  const Mat3 rotation = rotationAbout(Vec3(1.0, 1.0, 0.2), 1.1);
  const Mat3 inertia = rotation * Vec3(2.0, 2.0, 0.5).asDiagonal() * rotation.transpose();
  const PrincipalAxes principal = principalAxes(inertia);
  expectRelNear(principal.moments[0], 0.5);
  expectRelNear(principal.moments[1], 2.0);
  expectRelNear(principal.moments[2], 2.0);
  EXPECT_NEAR(std::abs(principal.axes.col(0).dot(rotation.col(2))), 1.0, 1e-12);
  EXPECT_NEAR(principal.axes.determinant(), 1.0, 1e-12);
  expectMatrixNear(principal.axes * principal.moments.asDiagonal() * principal.axes.transpose(),
                   inertia);
}

TEST(PrincipalAxes, AxesAreAlwaysAProperRotation) {
  // The eigenvector signs are arbitrary, so about half of these come out of
  // the solver as reflections and must be fixed.
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 axis(uniform(rng), uniform(rng), uniform(rng));
    const Mat3 rotation = rotationAbout(axis, 3.0 * uniform(rng));
    const Vec3 moments(1.0 + 0.2 * uniform(rng), 2.0 + 0.2 * uniform(rng),
                       2.5 + 0.2 * uniform(rng));
    const Mat3 inertia = rotation * moments.asDiagonal() * rotation.transpose();
    const PrincipalAxes principal = principalAxes(inertia);
    EXPECT_NEAR(principal.axes.determinant(), 1.0, 1e-12) << "trial " << trial;
    EXPECT_LE((principal.moments - moments).cwiseAbs().maxCoeff(), 1e-12) << "trial " << trial;
    expectMatrixNear(principal.axes * principal.moments.asDiagonal() * principal.axes.transpose(),
                     inertia);
  }
}

TEST(PrincipalAxes, ShiftInertiaRoundTrip) {
  // Moving the reference point away and back again restores the tensor,
  // and the shifted tensor of a cube about a corner matches 2/3 m s².
  const MassProperties cube = polyhedronMassProperties(makeBoxMesh(Vec3::Constant(1.0)), 1.0);
  const Mat3 corner = shiftInertia(cube.inertia, cube.mass, Vec3::Ones());
  expectRelNear(corner(0, 0), 2.0 / 3.0 * cube.mass * 4.0);
  expectRelNear(corner(0, 1), -cube.mass);
  expectMatrixNear(shiftInertia(corner, -cube.mass, Vec3::Ones()), cube.inertia);
}

}  // namespace
}  // namespace rbsim
