// Monte Carlo mass properties: an independent cross-check of the exact
// polyhedron integrals, with standard errors.
//
// Points X are drawn uniformly in the mesh's bounding box B (volume V_B) and
// I = 1 when X is inside the solid. For N samples, n of them inside:
//   volume   V = V_B p̂ with p̂ = n/N; Var(V) = V_B² p(1−p)/N.
//   centre   ĉ = mean of the inside points. Given n, that is the mean of n
//            points uniform in the solid, so SE(ĉ_k) = s_k/√n with s_k the
//            sample standard deviation of the inside points' k-th coordinate.
//   inertia  Î = ρ V_B (1/N) Σ_i I_i g(X_i − ĉ), with g(r) = |r|² 1 − r rᵀ.
//            Î depends on all N samples through the mass as well as through
//            ĉ, so its error is not that of the inside points alone. By the
//            delta method, the influence of sample i is
//              ψ_i = I_i g(X_i − c)
//            (the term from ĉ drops out: the inertia about a point is
//            stationary at the centre of mass, since E[I (X − c)] = 0), hence
//            SE(Î_jk) = ρ V_B s(ψ_jk)/√N with s the sample standard deviation
//            over ALL N samples, outside ones contributing ψ = 0. Those zeros
//            are what carry the mass uncertainty into the inertia's error.
#include "support/monte_carlo_mass.h"

#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

namespace rbsim {
namespace {

// splitmix64 (Steele, Lea and Flood 2014): tiny, passes BigCrush, and gives
// the same sequence on every platform, unlike the std:: distributions.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : m_state(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (m_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t m_state;
};

using Triangle = std::array<Vec3, 3>;

// Generalised winding number: the solid angle the closed surface subtends at
// p, over 4π. It is 1 inside and 0 outside for an outward-wound mesh, and
// unlike ray parity it has no special cases (rays through edges or
// vertices). Solid angle of a triangle by Van Oosterom and Strackee, "The
// Solid Angle of a Plane Triangle", IEEE Trans. Biomed. Eng. 30(2), 1983:
//   tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|).
double windingNumber(const std::vector<Triangle>& triangles, const Vec3& p) {
  double totalAngle = 0.0;
  for (const Triangle& t : triangles) {
    const Vec3 a = t[0] - p, b = t[1] - p, c = t[2] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    totalAngle += 2.0 * std::atan2(numerator, denominator);
  }
  return totalAngle / (4.0 * std::numbers::pi);
}

Vec3 sampleInBox(SplitMix64& rng, const Vec3& halfSize) {
  Vec3 r;
  for (int axis = 0; axis < 3; ++axis) r[axis] = (2.0 * rng.uniform() - 1.0) * halfSize[axis];
  return r;
}

// The six distinct entries of g(r) = |r|² 1 − r rᵀ, in the order
// xx, yy, zz, xy, yz, zx.
using Six = Eigen::Matrix<double, 6, 1>;
Six inertiaIntegrand(const Vec3& r) {
  Six g;
  g << r.y() * r.y() + r.z() * r.z(), r.z() * r.z() + r.x() * r.x(), r.x() * r.x() + r.y() * r.y(),
      -r.x() * r.y(), -r.y() * r.z(), -r.z() * r.x();
  return g;
}

Mat3 symmetricFromSix(const Six& s) {
  Mat3 m;
  m << s[0], s[3], s[5],  //
      s[3], s[1], s[4],   //
      s[5], s[4], s[2];
  return m;
}

}  // namespace

MonteCarloMassProperties monteCarloMassProperties(const TriangleMesh& mesh, double density,
                                                  int samples, unsigned long long seed) {
  assert(samples >= 2 && "a standard error needs at least two samples");
  MonteCarloMassProperties result;
  result.samples = samples;
  if (samples < 2 || mesh.triangles.empty()) return result;

  // Work about the bounding-box centre, for the same precision reason as the
  // exact integrals.
  Vec3 lower, upper;
  usedVertexBounds(mesh, lower, upper);
  const Vec3 reference = 0.5 * (lower + upper);
  const Vec3 halfSize = 0.5 * (upper - lower);
  const double boxVolume = (upper - lower).prod();
  std::vector<Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& triangle : mesh.triangles) {
    triangles.push_back({mesh.vertices[static_cast<size_t>(triangle[0])] - reference,
                         mesh.vertices[static_cast<size_t>(triangle[1])] - reference,
                         mesh.vertices[static_cast<size_t>(triangle[2])] - reference});
  }
  const double n = static_cast<double>(samples);

  // Pass 1: classify the points (the expensive part) and find ĉ. The flags
  // are kept so that pass 2 only has to regenerate the points.
  std::vector<bool> inside(static_cast<size_t>(samples));
  int insideCount = 0;
  Vec3 sum = Vec3::Zero();
  SplitMix64 rng(seed);
  for (int i = 0; i < samples; ++i) {
    const Vec3 r = sampleInBox(rng, halfSize);
    if (windingNumber(triangles, r) > 0.5) {
      inside[static_cast<size_t>(i)] = true;
      ++insideCount;
      sum += r;
    }
  }
  result.insideSamples = insideCount;

  const double p = insideCount / n;
  MassProperties& estimate = result.estimate;
  MassProperties& error = result.standardError;
  estimate.volume = boxVolume * p;
  estimate.mass = density * estimate.volume;
  error.volume = boxVolume * std::sqrt(p * (1.0 - p) / (n - 1.0));
  error.mass = density * error.volume;
  if (insideCount == 0) {
    estimate.centerOfMass = reference;
    error.centerOfMass = Vec3::Constant(std::numeric_limits<double>::infinity());
    return result;
  }
  const Vec3 center = sum / insideCount;  // from the reference point

  // Pass 2: deviations from ĉ, and the mean and variance of ψ over all N
  // samples (Welford's update, stable where the textbook formula cancels).
  Vec3 squaredDeviation = Vec3::Zero();
  Six psiMean = Six::Zero();
  Six psiSquares = Six::Zero();
  rng = SplitMix64(seed);
  for (int i = 0; i < samples; ++i) {
    const Vec3 r = sampleInBox(rng, halfSize);
    Six psi = Six::Zero();
    if (inside[static_cast<size_t>(i)]) {
      const Vec3 d = r - center;
      squaredDeviation += d.cwiseProduct(d);
      psi = inertiaIntegrand(d);
    }
    const Six delta = psi - psiMean;
    psiMean += delta / static_cast<double>(i + 1);
    psiSquares += delta.cwiseProduct(psi - psiMean);
  }

  estimate.centerOfMass = reference + center;
  error.centerOfMass =
      insideCount > 1 ? Vec3((squaredDeviation / (insideCount * (insideCount - 1.0))).cwiseSqrt())
                      : Vec3::Constant(std::numeric_limits<double>::infinity());
  const double scale = density * boxVolume;
  estimate.inertia = symmetricFromSix(scale * psiMean);
  error.inertia = symmetricFromSix(scale * (psiSquares / ((n - 1.0) * n)).cwiseSqrt());
  return result;
}

}  // namespace rbsim
