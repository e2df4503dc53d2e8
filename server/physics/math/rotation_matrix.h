#pragma once
// Rotation-matrix utilities.

#include "rbsim/physics/math_types.h"

namespace rbsim {

// Restores orthonormality of a rotation matrix that has drifted (the usual
// fix for accumulated round-off, which Baraff's rigid-body notes discuss) by
// Gram–Schmidt on its columns: the first column keeps its direction, the
// second is made orthogonal to it, the third is their cross product so the
// result is a proper rotation (det = +1).
Mat3 gramSchmidtOrthonormalize(const Mat3& drifted);

// Largest absolute entry of RᵀR − 1: 0 for an exact rotation.
double orthonormalityError(const Mat3& rotation);

// R diag(d) Rᵀ: a tensor given in principal axes, in the frame R maps them
// to (the world inertia and its inverse). Exactly symmetric: each entry
// below the diagonal is the one above it (a general product rounds (i, j)
// and (j, i) differently), and it takes about half the arithmetic.
inline Mat3 rotatedDiagonal(const Mat3& rotation, const Vec3& diagonal) {
  const Mat3 scaled = rotation * diagonal.asDiagonal();  // column k times d_k
  const auto entry = [&](int i, int j) {
    return scaled(i, 0) * rotation(j, 0) + scaled(i, 1) * rotation(j, 1) + scaled(i, 2) * rotation(j, 2);
  };
  const double xx = entry(0, 0), xy = entry(0, 1), xz = entry(0, 2);
  const double yy = entry(1, 1), yz = entry(1, 2), zz = entry(2, 2);
  Mat3 out;
  out << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  return out;
}

// The matrix [a]× with [a]× b = a × b.
Mat3 crossMatrix(const Vec3& a);

}  // namespace rbsim
