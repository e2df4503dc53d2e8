#include <gtest/gtest.h>

#include <random>

#include "rbsim/physics/quaternion.h"
#include "physics/math/rotation_matrix.h"

namespace rbsim {
namespace {

TEST(GramSchmidt, RestoresOrthonormalityOfADriftedMatrix) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  const Mat3 exact = Quaternion::fromRollPitchYaw(0.3, -0.8, 2.0).toRotationMatrix();
  Mat3 drifted = exact;
  for (int i = 0; i < 9; ++i) drifted(i / 3, i % 3) += noise(rng);
  ASSERT_GT(orthonormalityError(drifted), 1e-5);  // the drift is real

  const Mat3 fixed = gramSchmidtOrthonormalize(drifted);
  EXPECT_LT(orthonormalityError(fixed), 1e-15);
  EXPECT_NEAR(fixed.determinant(), 1.0, 1e-15);
  // It stays the nearby rotation: within the size of the perturbation.
  EXPECT_LT((fixed - exact).cwiseAbs().maxCoeff(), 5e-3);
  // The first column keeps its direction.
  EXPECT_LT((fixed.col(0) - drifted.col(0).normalized()).norm(), 1e-15);
}

TEST(GramSchmidt, RepeatedMultiplicationDriftIsRemoved) {
  // Composing many small rotations as matrices accumulates round-off (why
  // Baraff's notes prefer quaternions); re-orthonormalising brings it back to machine precision.
  const Mat3 small = Quaternion::fromAxisAngle(Vec3(1, 2, 3), 1e-3).toRotationMatrix();
  Mat3 r = Mat3::Identity();
  for (int i = 0; i < 100000; ++i) r = small * r;
  EXPECT_GT(orthonormalityError(r), 1e-14);
  EXPECT_LT(orthonormalityError(gramSchmidtOrthonormalize(r)), 1e-15);
}

TEST(CrossMatrix, MultipliesAsTheCrossProduct) {
  const Vec3 a(1.5, -2.0, 0.25), b(-0.5, 4.0, 3.0);
  EXPECT_LT((crossMatrix(a) * b - a.cross(b)).norm(), 1e-15);
}

}  // namespace
}  // namespace rbsim
