#pragma once
// Rotation-matrix utilities.

#include "physics/math/types.h"

namespace rbsim {

// Restores orthonormality of a rotation matrix that has drifted (the usual
// fix for accumulated round-off, which Baraff's rigid-body notes discuss) by
// Gram–Schmidt on its columns: the first column keeps its direction, the
// second is made orthogonal to it, the third is their cross product so the
// result is a proper rotation (det = +1).
Mat3 gramSchmidtOrthonormalize(const Mat3& drifted);

// Largest absolute entry of RᵀR − 1: 0 for an exact rotation.
double orthonormalityError(const Mat3& rotation);

// The matrix [a]× with [a]× b = a × b.
Mat3 crossMatrix(const Vec3& a);

}  // namespace rbsim
