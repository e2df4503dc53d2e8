#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "rbsim/physics/quaternion.h"
#include "physics/math/rotation_matrix.h"

namespace rbsim {
namespace {

constexpr double kPi = std::numbers::pi;

Quaternion randomUnitQuaternion(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  return Quaternion{normal(rng), normal(rng), normal(rng), normal(rng)}.normalized();
}

// Rotation about a coordinate axis, written out by hand (independent of the
// quaternion code).
Mat3 axisRotation(int axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 r;
  if (axis == 0) r << 1, 0, 0, 0, c, -s, 0, s, c;
  if (axis == 1) r << c, 0, s, 0, 1, 0, -s, 0, c;
  if (axis == 2) r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

TEST(Quaternion, AxisAngleMatchesHandWrittenRotationMatrices) {
  for (int axis = 0; axis < 3; ++axis) {
    for (double angle : {0.3, -1.2, 2.9, kPi}) {
      const Quaternion q = Quaternion::fromAxisAngle(Vec3::Unit(axis), angle);
      EXPECT_LT((q.toRotationMatrix() - axisRotation(axis, angle)).cwiseAbs().maxCoeff(), 1e-15);
    }
  }
}

TEST(Quaternion, YawOfQuarterTurnMapsXToY) {
  const Quaternion q = Quaternion::fromRollPitchYaw(0.0, 0.0, kPi / 2);
  EXPECT_LT((q.rotate(Vec3::UnitX()) - Vec3::UnitY()).norm(), 1e-15);
  // Columns of R are the body axes in world coordinates.
  EXPECT_LT((q.toRotationMatrix().col(0) - Vec3::UnitY()).norm(), 1e-15);
}

TEST(Quaternion, ProductComposesRotationsRightToLeft) {
  std::mt19937_64 rng(1);
  for (int i = 0; i < 100; ++i) {
    const Quaternion a = randomUnitQuaternion(rng), b = randomUnitQuaternion(rng);
    const Mat3 expected = a.toRotationMatrix() * b.toRotationMatrix();
    EXPECT_LT(((a * b).toRotationMatrix() - expected).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(Quaternion, RotateAgreesWithMatrixAndInverseRotateUndoesIt) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> uniform(-10.0, 10.0);
  for (int i = 0; i < 100; ++i) {
    const Quaternion q = randomUnitQuaternion(rng);
    const Vec3 v(uniform(rng), uniform(rng), uniform(rng));
    EXPECT_LT((q.rotate(v) - q.toRotationMatrix() * v).norm(), 1e-13);
    EXPECT_LT((q.inverseRotate(q.rotate(v)) - v).norm(), 1e-13);
  }
}

TEST(Quaternion, MatrixRoundTripIncludingHalfTurns) {
  std::mt19937_64 rng(3);
  std::vector<Quaternion> cases;
  for (int i = 0; i < 200; ++i) cases.push_back(randomUnitQuaternion(rng));
  // Half turns make the trace -1: the branch where the naive formula divides by ~0.
  for (int axis = 0; axis < 3; ++axis) cases.push_back(Quaternion::fromAxisAngle(Vec3::Unit(axis), kPi));
  cases.push_back(Quaternion::fromAxisAngle(Vec3(1, 1, 0), kPi));
  for (const Quaternion& q : cases) {
    const Quaternion back = Quaternion::fromRotationMatrix(q.toRotationMatrix());
    // q and -q are the same rotation.
    const double sign = (back.w * q.w + back.x * q.x + back.y * q.y + back.z * q.z) < 0 ? -1.0 : 1.0;
    EXPECT_NEAR(back.w, sign * q.w, 1e-14);
    EXPECT_NEAR(back.x, sign * q.x, 1e-14);
    EXPECT_NEAR(back.y, sign * q.y, 1e-14);
    EXPECT_NEAR(back.z, sign * q.z, 1e-14);
  }
}

TEST(Quaternion, RollPitchYawMatchesFixedAxisComposition) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> angle(-1.5, 1.5);
  for (int i = 0; i < 100; ++i) {
    const double roll = 2 * angle(rng), pitch = angle(rng), yaw = 2 * angle(rng);
    const Quaternion q = Quaternion::fromRollPitchYaw(roll, pitch, yaw);
    const Mat3 expected = axisRotation(2, yaw) * axisRotation(1, pitch) * axisRotation(0, roll);
    EXPECT_LT((q.toRotationMatrix() - expected).cwiseAbs().maxCoeff(), 1e-14);
    const Vec3 rpy = q.toRollPitchYaw();
    EXPECT_NEAR(rpy.x(), roll, 1e-12);
    EXPECT_NEAR(rpy.y(), pitch, 1e-12);
    EXPECT_NEAR(rpy.z(), yaw, 1e-12);
  }
}

TEST(Quaternion, RollPitchYawAtGimbalLockStillReproducesTheRotation) {
  const Quaternion q = Quaternion::fromRollPitchYaw(0.4, kPi / 2, -0.7);
  const Vec3 rpy = q.toRollPitchYaw();
  const Quaternion back = Quaternion::fromRollPitchYaw(rpy.x(), rpy.y(), rpy.z());
  EXPECT_LT((back.toRotationMatrix() - q.toRotationMatrix()).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(Quaternion, NormalizedHasUnitNorm) {
  const Quaternion q = Quaternion{3.0, -4.0, 12.0, 0.0}.normalized();
  EXPECT_NEAR(q.norm(), 1.0, 1e-16);
  EXPECT_DOUBLE_EQ(q.w, 3.0 / 13.0);
  EXPECT_DOUBLE_EQ(q.z, 0.0);
}

}  // namespace
}  // namespace rbsim
