// Closed-form mass properties of the primitives, checked against textbook
// values worked out by hand and against an independent integration by
// slices.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "rbsim/physics/mass_properties.h"

namespace rbsim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRelTol = 1e-12;

void expectRelNear(double actual, double expected, double relTol = kRelTol) {
  EXPECT_NEAR(actual, expected, relTol * std::abs(expected)) << "expected " << expected;
}

void expectInertiaNear(const Mat3& actual, const Mat3& expected, double relTol = kRelTol) {
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), relTol * scale) << "actual\n"
                                                                       << actual << "\nexpected\n"
                                                                       << expected;
}

// A solid of revolution about z cut into thin discs: the disc at height z has
// radius² R²(z), so
//   V   = ∫ π R² dz,
//   Izz = ρ ∫ π R⁴/2 dz                (disc about its axis),
//   Ixx = ρ ∫ (π R⁴/4 + π R² z²) dz    (disc about a diameter, shifted by z).
// For spheres, cylinders and capsules R² is a polynomial of degree <= 2 on
// each piece, so the integrands have degree <= 4 and 3-point Gauss–Legendre
// quadrature is exact on each piece: an independent route to the closed
// forms, with no parallel-axis bookkeeping for the caps.
struct Piece {
  double z0 = 0.0, z1 = 0.0;  // m
  std::function<double(double)> radiusSquared;
};

struct SliceResult {
  double volume = 0.0, ixx = 0.0, izz = 0.0;
};

SliceResult integrateSlices(const std::vector<Piece>& pieces, double density) {
  const double node = std::sqrt(3.0 / 5.0);
  const double nodes[3] = {-node, 0.0, node};
  const double weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  SliceResult result;
  for (const Piece& piece : pieces) {
    const double half = 0.5 * (piece.z1 - piece.z0), mid = 0.5 * (piece.z1 + piece.z0);
    for (int k = 0; k < 3; ++k) {
      const double z = mid + half * nodes[k];
      const double r2 = piece.radiusSquared(z);
      const double w = half * weights[k];
      result.volume += w * kPi * r2;
      result.izz += w * density * kPi * r2 * r2 / 2.0;
      result.ixx += w * density * (kPi * r2 * r2 / 4.0 + kPi * r2 * z * z);
    }
  }
  return result;
}

std::vector<Piece> capsulePieces(double r, double h) {
  return {{-h - r, -h, [=](double z) { return r * r - (z + h) * (z + h); }},
          {-h, h, [=](double) { return r * r; }},
          {h, h + r, [=](double z) { return r * r - (z - h) * (z - h); }}};
}

void expectMatchesSlices(const MassProperties& props, const SliceResult& slices, double density) {
  expectRelNear(props.volume, slices.volume);
  expectRelNear(props.mass, density * slices.volume);
  expectInertiaNear(props.inertia, Vec3(slices.ixx, slices.ixx, slices.izz).asDiagonal());
  EXPECT_EQ(props.centerOfMass, Vec3::Zero());
}

TEST(PrimitiveMass, SphereMatchesTextbook) {
  // r = 0.3 m steel: m = ρ 4/3 π r³ = 7800 · 0.036 π = 280.8 π kg, I = 2/5 m r².
  const MassProperties props = sphereMassProperties(0.3, 7800.0);
  expectRelNear(props.volume, 0.036 * kPi);
  expectRelNear(props.mass, 280.8 * kPi);
  expectInertiaNear(props.inertia, Mat3::Identity() * (0.4 * 280.8 * kPi * 0.09));
  EXPECT_EQ(props.centerOfMass, Vec3::Zero());
}

TEST(PrimitiveMass, SphereMatchesSlices) {
  const double r = 0.3, density = 7800.0;
  const SliceResult slices =
      integrateSlices({{-r, r, [=](double z) { return r * r - z * z; }}}, density);
  expectMatchesSlices(sphereMassProperties(r, density), slices, density);
}

TEST(PrimitiveMass, BoxMatchesTextbook) {
  // Sides 1 × 2 × 3 m at 2 kg/m³: m = 12 kg, Ixx = m/12 (2² + 3²) = 13,
  // Iyy = m/12 (1² + 3²) = 10, Izz = m/12 (1² + 2²) = 5 kg·m².
  const MassProperties props = boxMassProperties(Vec3(0.5, 1.0, 1.5), 2.0);
  expectRelNear(props.volume, 6.0);
  expectRelNear(props.mass, 12.0);
  expectInertiaNear(props.inertia, Vec3(13.0, 10.0, 5.0).asDiagonal());
  EXPECT_EQ(props.centerOfMass, Vec3::Zero());
}

TEST(PrimitiveMass, CylinderMatchesTextbook) {
  // r = 0.2 m, length 1.5 m, 1000 kg/m³: m = 1000 π 0.04 · 1.5 = 60 π kg,
  // Izz = m r²/2 = 1.2 π, Ixx = m (3 r² + L²)/12 = 60 π · 2.37/12 = 11.85 π.
  const MassProperties props = cylinderMassProperties(0.2, 0.75, 1000.0);
  expectRelNear(props.volume, 0.06 * kPi);
  expectRelNear(props.mass, 60.0 * kPi);
  expectInertiaNear(props.inertia, Vec3(11.85 * kPi, 11.85 * kPi, 1.2 * kPi).asDiagonal());
}

TEST(PrimitiveMass, CylinderMatchesSlices) {
  const double r = 0.2, h = 0.75, density = 1000.0;
  const SliceResult slices = integrateSlices({{-h, h, [=](double) { return r * r; }}}, density);
  expectMatchesSlices(cylinderMassProperties(r, h, density), slices, density);
}

TEST(PrimitiveMass, CapsuleMatchesHandComputedValue) {
  // r = 0.5 m, cylinder length 2 m, ρ = 1. Cylinder: m_c = π/2,
  // Izz = m_c r²/2 = π/16, Ixx = m_c (r²/4 + h²/3) = 19π/96. Caps together:
  // m = π/6, Izz = 2/5 m r² = π/60; each cap (m_h = π/12) about the centre,
  // via its centroid at 3r/8: m_h (2/5 r² − (3r/8)² + (h + 3r/8)²) = m_h · 1.475.
  // Totals: V = 2π/3, Izz = 19π/240, Ixx = 19π/96 + 59π/240 = 71π/160.
  const MassProperties props = capsuleMassProperties(0.5, 1.0, 1.0);
  expectRelNear(props.volume, 2.0 * kPi / 3.0);
  expectRelNear(props.mass, 2.0 * kPi / 3.0);
  expectInertiaNear(props.inertia,
                    Vec3(71.0 * kPi / 160.0, 71.0 * kPi / 160.0, 19.0 * kPi / 240.0).asDiagonal());
}

TEST(PrimitiveMass, CapsuleMatchesSlices) {
  for (const auto& [r, h] : {std::pair{0.5, 1.0}, std::pair{0.1, 2.0}, std::pair{1.3, 0.2}}) {
    SCOPED_TRACE(testing::Message() << "r = " << r << ", h = " << h);
    const double density = 950.0;
    expectMatchesSlices(capsuleMassProperties(r, h, density),
                        integrateSlices(capsulePieces(r, h), density), density);
  }
}

TEST(PrimitiveMass, CapsuleWithoutCylinderIsASphere) {
  const MassProperties capsule = capsuleMassProperties(0.7, 0.0, 3.0);
  const MassProperties sphere = sphereMassProperties(0.7, 3.0);
  expectRelNear(capsule.mass, sphere.mass);
  expectInertiaNear(capsule.inertia, sphere.inertia);
}

TEST(PrimitiveMass, ShiftInertiaToCubeCorner) {
  // Cube of side s = 2 m, m = 8 kg, about a corner (offset (1, 1, 1) m):
  // diagonal m s²/6 + m (1² + 1²) = 2/3 m s², products −m · 1 · 1 = −m s²/4.
  const MassProperties cube = boxMassProperties(Vec3::Ones(), 1.0);
  const Mat3 aboutCorner = shiftInertia(cube.inertia, cube.mass, Vec3::Ones());
  Mat3 expected = Mat3::Constant(-8.0);
  expected.diagonal().setConstant(2.0 / 3.0 * 8.0 * 4.0);
  expectInertiaNear(aboutCorner, expected);
}

}  // namespace
}  // namespace rbsim
