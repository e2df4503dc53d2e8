#include "physics/math/rotation_matrix.h"

namespace rbsim {

Mat3 gramSchmidtOrthonormalize(const Mat3& drifted) {
  const Vec3 e0 = drifted.col(0).normalized();
  const Vec3 c1 = drifted.col(1);
  const Vec3 e1 = (c1 - e0.dot(c1) * e0).normalized();
  Mat3 result;
  result.col(0) = e0;
  result.col(1) = e1;
  result.col(2) = e0.cross(e1);
  return result;
}

double orthonormalityError(const Mat3& rotation) {
  return (rotation.transpose() * rotation - Mat3::Identity()).cwiseAbs().maxCoeff();
}

Mat3 crossMatrix(const Vec3& a) {
  Mat3 m;
  m << 0.0, -a.z(), a.y(),  //
      a.z(), 0.0, -a.x(),   //
      -a.y(), a.x(), 0.0;
  return m;
}

}  // namespace rbsim
