#pragma once
// Mass properties of a solid of uniform density.

#include <optional>
#include <span>
#include <string>

#include "rbsim/physics/expected.h"
#include "rbsim/physics/triangle_mesh.h"
#include "rbsim/physics/transform.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct MassProperties {
  double mass = 0.0;                    // kg
  double volume = 0.0;                  // m³
  Vec3 centerOfMass = Vec3::Zero();     // m, in the frame the shape was given in
  Mat3 inertia = Mat3::Zero();          // kg·m², about the centre of mass, same frame
};

// The inertia tensor diagonalised: inertia = axes * diag(moments) * axesᵀ.
struct PrincipalAxes {
  Vec3 moments = Vec3::Zero();   // kg·m², ascending
  Mat3 axes = Mat3::Identity();  // columns are the principal axes; a proper rotation (det = +1)
};

// Closed forms for primitives centred at the origin of their frame; the
// cylinder and the capsule have their axis along z. `halfLength` is half the
// length of the cylindrical part (the capsule's caps come on top).
MassProperties sphereMassProperties(double radius, double density);
MassProperties boxMassProperties(const Vec3& halfExtents, double density);
MassProperties cylinderMassProperties(double radius, double halfLength, double density);
MassProperties capsuleMassProperties(double radius, double halfLength, double density);

// Exact mass properties of the solid bounded by a closed, outward-wound
// triangle mesh, by the divergence theorem (Mirtich 1996, "Fast and Accurate
// Computation of Polyhedral Mass Properties"). The mesh is shifted to a
// reference point inside its bounding box before integrating so that a mesh
// far from the origin loses no precision. The mesh must have passed
// validateClosedMesh.
MassProperties polyhedronMassProperties(const TriangleMesh& mesh, double density);

// One solid of a union: its mass properties in its own frame, and where
// that frame sits (part frame -> the union's frame).
struct PlacedMassProperties {
  MassProperties properties;
  Transform placement;
};

// The exact mass properties of a union of solids that do not overlap, in the
// union's frame: masses and volumes add, the centre of mass is the
// mass-weighted mean, and each inertia is rotated into the union's frame
// (R I Rᵀ) and moved to the common centre of mass (parallel-axis theorem).
// `parts` must not be empty.
MassProperties combinedMassProperties(std::span<const PlacedMassProperties> parts);

// Eigen-decomposition of a symmetric inertia tensor. When the tensor is
// already diagonal (off-diagonal terms below 1e-12 of its trace) the axes
// stay the identity, so primitives keep their natural axes even when two
// moments are equal; the moments are then the diagonal in x, y, z order,
// which need not be ascending. Otherwise they are ascending.
PrincipalAxes principalAxes(const Mat3& inertia);

// Why an inertia tensor given as data (URDF <inertial>, CAD) cannot be a
// rigid body's, or nothing when it can: it must be finite, symmetric,
// positive definite, and each principal moment at most the sum of the other
// two (I1 + I2 − I3 = 2 ∫ z² dm ≥ 0 in principal axes; equality is a body
// flat in a plane). Symmetry and the inequality allow round-off of
// kInertiaTolerance times the largest |entry| or the trace: text written by
// CAD tools repeats products of inertia to ~16 digits, and the principal
// moments of a rotated tensor carry the eigensolver's rounding.
std::optional<std::string> inertiaTensorProblem(const Mat3& inertia);
inline constexpr double kInertiaTolerance = 1e-12;

// Inertia of the same body about a point displaced by `offset` from the
// centre of mass (parallel-axis theorem): I + m (|d|² 1 − d dᵀ).
Mat3 shiftInertia(const Mat3& inertiaAboutCenter, double mass, const Vec3& offset);

}  // namespace rbsim
