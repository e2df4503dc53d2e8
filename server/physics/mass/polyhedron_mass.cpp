// Exact mass properties of a closed triangle mesh, after B. Mirtich, "Fast
// and Accurate Computation of Polyhedral Mass Properties", Journal of
// Graphics Tools 1(2), 1996 (the reference code is volInt.c).
//
// The volume integrals T0 = ∫1, T1 = ∫(x, y, z), T2 = ∫(x², y², z²) and
// TP = ∫(xy, yz, zx) are turned into sums of surface integrals over the faces
// by the divergence theorem. Each face integral is then written in terms of
// its projection onto the coordinate plane where it is largest (α, β are the
// projected axes, γ the dropped one), and each projection integral into line
// integrals around the edges by Green's theorem. Every step is exact, so the
// only error is floating-point round-off.
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include "rbsim/physics/mass_properties.h"

namespace rbsim {
namespace {

// Integrals over the projection of a face onto the (α, β) plane, e.g.
// pab = ∫∫ α β dα dβ (Mirtich section 4.2, eq. (38)-(39) summed per edge).
struct ProjectionIntegrals {
  double p1 = 0.0, pa = 0.0, pb = 0.0, paa = 0.0, pab = 0.0, pbb = 0.0;
  double paaa = 0.0, paab = 0.0, pabb = 0.0, pbbb = 0.0;
};

// Integrals over the face itself: fa = ∫ α dA etc., divided by |n_γ|
// (Mirtich section 4.3).
struct FaceIntegrals {
  double fa = 0.0, fb = 0.0, fc = 0.0;
  double faa = 0.0, fbb = 0.0, fcc = 0.0;
  double faaa = 0.0, fbbb = 0.0, fccc = 0.0;
  double faab = 0.0, fbbc = 0.0, fcca = 0.0;
};

ProjectionIntegrals projectionIntegrals(const std::array<Vec3, 3>& v, int a, int b) {
  ProjectionIntegrals p;
  for (int i = 0; i < 3; ++i) {
    const Vec3& from = v[static_cast<size_t>(i)];
    const Vec3& to = v[static_cast<size_t>((i + 1) % 3)];
    const double a0 = from[a], b0 = from[b];
    const double a1 = to[a], b1 = to[b];
    const double da = a1 - a0, db = b1 - b0;
    const double a0_2 = a0 * a0, a0_3 = a0_2 * a0, a0_4 = a0_3 * a0;
    const double b0_2 = b0 * b0, b0_3 = b0_2 * b0, b0_4 = b0_3 * b0;
    const double a1_2 = a1 * a1, a1_3 = a1_2 * a1;
    const double b1_2 = b1 * b1, b1_3 = b1_2 * b1;

    const double c1 = a1 + a0;
    const double ca = a1 * c1 + a0_2;
    const double caa = a1 * ca + a0_3;
    const double caaa = a1 * caa + a0_4;
    const double cb = b1 * (b1 + b0) + b0_2;
    const double cbb = b1 * cb + b0_3;
    const double cbbb = b1 * cbb + b0_4;
    const double cab = 3.0 * a1_2 + 2.0 * a1 * a0 + a0_2;
    const double kab = a1_2 + 2.0 * a1 * a0 + 3.0 * a0_2;
    const double caab = a0 * cab + 4.0 * a1_3;
    const double kaab = a1 * kab + 4.0 * a0_3;
    const double cabb = 4.0 * b1_3 + 3.0 * b1_2 * b0 + 2.0 * b1 * b0_2 + b0_3;
    const double kabb = b1_3 + 2.0 * b1_2 * b0 + 3.0 * b1 * b0_2 + 4.0 * b0_3;

    p.p1 += db * c1;
    p.pa += db * ca;
    p.paa += db * caa;
    p.paaa += db * caaa;
    p.pb += da * cb;
    p.pbb += da * cbb;
    p.pbbb += da * cbbb;
    p.pab += db * (b1 * cab + b0 * kab);
    p.paab += db * (b1 * caab + b0 * kaab);
    p.pabb += da * (a1 * cabb + a0 * kabb);
  }
  p.p1 /= 2.0;
  p.pa /= 6.0;
  p.paa /= 12.0;
  p.paaa /= 20.0;
  p.pb /= -6.0;
  p.pbb /= -12.0;
  p.pbbb /= -20.0;
  p.pab /= 24.0;
  p.paab /= 60.0;
  p.pabb /= -60.0;
  return p;
}

// The face lies in the plane n·x + w = 0 with n the unit outward normal, so
// on it γ = −(n_α α + n_β β + w)/n_γ; substituting turns every face integral
// into projection integrals.
FaceIntegrals faceIntegrals(const std::array<Vec3, 3>& v, const Vec3& n, int a, int b, int c) {
  const ProjectionIntegrals p = projectionIntegrals(v, a, b);
  const double w = -n.dot(v[0]);
  const double na = n[a], nb = n[b];
  const double k1 = 1.0 / n[c], k2 = k1 * k1, k3 = k2 * k1, k4 = k3 * k1;

  FaceIntegrals f;
  f.fa = k1 * p.pa;
  f.fb = k1 * p.pb;
  f.fc = -k2 * (na * p.pa + nb * p.pb + w * p.p1);

  f.faa = k1 * p.paa;
  f.fbb = k1 * p.pbb;
  f.fcc = k3 * (na * na * p.paa + 2.0 * na * nb * p.pab + nb * nb * p.pbb +
                w * (2.0 * (na * p.pa + nb * p.pb) + w * p.p1));

  f.faaa = k1 * p.paaa;
  f.fbbb = k1 * p.pbbb;
  f.fccc = -k4 * (na * na * na * p.paaa + 3.0 * na * na * nb * p.paab +
                  3.0 * na * nb * nb * p.pabb + nb * nb * nb * p.pbbb +
                  3.0 * w * (na * na * p.paa + 2.0 * na * nb * p.pab + nb * nb * p.pbb) +
                  w * w * (3.0 * (na * p.pa + nb * p.pb) + w * p.p1));

  f.faab = k1 * p.paab;
  f.fbbc = -k2 * (na * p.pabb + nb * p.pbbb + w * p.pbb);
  f.fcca = k3 * (na * na * p.paaa + 2.0 * na * nb * p.paab + nb * nb * p.pabb +
                 w * (2.0 * (na * p.paa + nb * p.pab) + w * p.pa));
  return f;
}

}  // namespace

MassProperties polyhedronMassProperties(const TriangleMesh& mesh, double density) {
  // The integrands grow like |x|³, so a unit cube placed 1e6 m from the
  // origin would have its ~1 m⁵ inertia computed as the difference of terms
  // of order 1e18: all digits lost. Integrating about the bounding-box centre
  // keeps every term at the mesh's own scale; T1 and the parallel-axis step
  // below bring the results back to the mesh's frame.
  Vec3 lower, upper;
  usedVertexBounds(mesh, lower, upper);
  const Vec3 reference = 0.5 * (lower + upper);

  double t0 = 0.0;
  Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero(), tp = Vec3::Zero();
  for (const auto& triangle : mesh.triangles) {
    const std::array<Vec3, 3> v = {mesh.vertices[static_cast<size_t>(triangle[0])] - reference,
                                   mesh.vertices[static_cast<size_t>(triangle[1])] - reference,
                                   mesh.vertices[static_cast<size_t>(triangle[2])] - reference};
    const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
    // Project onto the plane of the largest normal component, so that the
    // divisions by n_γ are well conditioned (|n_γ| >= 1/√3).
    const Vec3 absN = n.cwiseAbs();
    const int c = (absN.x() > absN.y() && absN.x() > absN.z()) ? 0 : (absN.y() > absN.z() ? 1 : 2);
    const int a = (c + 1) % 3;
    const int b = (a + 1) % 3;
    const FaceIntegrals f = faceIntegrals(v, n, a, b, c);

    // Divergence theorem with the fields (x, 0, 0), (x²/2, ...), (x³/3, ...)
    // and (x²y/2, ...): Mirtich eq. (13)-(16).
    t0 += n.x() * (a == 0 ? f.fa : (b == 0 ? f.fb : f.fc));
    t1[a] += n[a] * f.faa;
    t1[b] += n[b] * f.fbb;
    t1[c] += n[c] * f.fcc;
    t2[a] += n[a] * f.faaa;
    t2[b] += n[b] * f.fbbb;
    t2[c] += n[c] * f.fccc;
    tp[a] += n[a] * f.faab;
    tp[b] += n[b] * f.fbbc;
    tp[c] += n[c] * f.fcca;
  }
  t1 /= 2.0;
  t2 /= 3.0;
  tp /= 2.0;
  assert(t0 > 0.0 && "polyhedronMassProperties needs a closed, outward-wound mesh");

  MassProperties props;
  props.volume = t0;
  props.mass = density * t0;
  const Vec3 centerOffset = t1 / t0;  // from the reference point
  props.centerOfMass = reference + centerOffset;

  // tp holds (∫xy, ∫yz, ∫zx).
  Mat3 aboutReference;
  aboutReference(0, 0) = t2.y() + t2.z();
  aboutReference(1, 1) = t2.z() + t2.x();
  aboutReference(2, 2) = t2.x() + t2.y();
  aboutReference(0, 1) = aboutReference(1, 0) = -tp.x();
  aboutReference(1, 2) = aboutReference(2, 1) = -tp.y();
  aboutReference(2, 0) = aboutReference(0, 2) = -tp.z();
  aboutReference *= density;
  // Parallel-axis theorem backwards: I_ref = I_com + m (|d|² 1 − d dᵀ).
  props.inertia = shiftInertia(aboutReference, -props.mass, centerOffset);
  return props;
}

}  // namespace rbsim
