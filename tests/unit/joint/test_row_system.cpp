// The joint step's block factorisation of K = J M⁻¹ Jᵀ (joint/row_system.h)
// against a dense K built here from the same rows: trees, loops, limit rows
// that follow the rest, blocks of every size, a kept analysis giving the
// same bits as a fresh one, and a factor kept only for bit-identical inputs.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "physics/joint/row_system.h"

namespace rbsim {
namespace {

struct Bodies {
  std::vector<double> inverseMass;
  std::vector<Mat3> inverseInertia;
};

Bodies randomBodies(int count, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), mass(0.2, 5.0);
  Bodies bodies;
  for (int i = 0; i < count; ++i) {
    bodies.inverseMass.push_back(1.0 / mass(random));
    Mat3 a;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) a(r, c) = unit(random);
    bodies.inverseInertia.push_back(a * a.transpose() + 0.1 * Mat3::Identity());
  }
  return bodies;
}

Vec3 randomVec(std::mt19937& random) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return {unit(random), unit(random), unit(random)};
}

// `size` rows of one link between two bodies (-1: a fixed side).
void addLink(std::vector<JointSolverRow>& rows, int link, int bodyA, int bodyB, int size, std::mt19937& random) {
  for (int k = 0; k < size; ++k) {
    JointSolverRow row = JointSolverRow::of(bodyA, bodyB, link);
    row.jacobian = {randomVec(random), randomVec(random), randomVec(random), randomVec(random)};
    rows.push_back(row);
  }
}

// K as the system defines it, dense, with its relative regularisation.
Eigen::MatrixXd denseK(const std::vector<JointSolverRow>& rows, const Bodies& bodies) {
  const auto n = static_cast<Eigen::Index>(rows.size());
  const auto dof = static_cast<Eigen::Index>(6 * bodies.inverseMass.size());
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(n, dof);
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(dof, dof);
  for (std::size_t b = 0; b < bodies.inverseMass.size(); ++b) {
    const auto at = static_cast<Eigen::Index>(6 * b);
    w.block<3, 3>(at, at) = bodies.inverseMass[b] * Mat3::Identity();
    w.block<3, 3>(at + 3, at + 3) = bodies.inverseInertia[b];
  }
  for (Eigen::Index r = 0; r < n; ++r) {
    const JointSolverRow& row = rows[static_cast<std::size_t>(r)];
    if (row.bodyA >= 0) {
      j.block<1, 3>(r, 6 * row.bodyA) = row.jacobian.linearA.transpose();
      j.block<1, 3>(r, 6 * row.bodyA + 3) = row.jacobian.angularA.transpose();
    }
    if (row.bodyB >= 0) {
      j.block<1, 3>(r, 6 * row.bodyB) = row.jacobian.linearB.transpose();
      j.block<1, 3>(r, 6 * row.bodyB + 3) = row.jacobian.angularB.transpose();
    }
  }
  Eigen::MatrixXd k = j * w * j.transpose();
  k.diagonal() *= 1.0 + 1e-10;
  return k;
}

Eigen::VectorXd randomRhs(Eigen::Index n, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b[i] = unit(random);
  return b;
}

// The solve against the dense K: the residual relative to K's and x's size.
void expectSolves(const std::vector<JointSolverRow>& rows, const Bodies& bodies, std::mt19937& random) {
  RowSystem system;
  system.factor(rows, bodies.inverseMass, bodies.inverseInertia);
  ASSERT_TRUE(system.ok());
  ASSERT_EQ(system.size(), static_cast<Eigen::Index>(rows.size()));
  const Eigen::MatrixXd k = denseK(rows, bodies);
  const Eigen::VectorXd b = randomRhs(k.rows(), random);
  const Eigen::VectorXd x = system.solve(b);
  const Eigen::VectorXd expected = k.llt().solve(b);
  const double scale = k.cwiseAbs().maxCoeff() * x.cwiseAbs().maxCoeff();
  EXPECT_LT((k * x - b).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-8 * expected.cwiseAbs().maxCoeff());
}

bool sameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(RowSystem, SolvesAChainOfBallJointsHungFromTheWorld) {
  std::mt19937 random(1);
  const Bodies bodies = randomBodies(30, random);
  std::vector<JointSolverRow> rows;
  addLink(rows, 0, -1, 0, 3, random);
  for (int i = 1; i < 30; ++i) addLink(rows, i, i - 1, i, 3, random);
  expectSolves(rows, bodies, random);
}

TEST(RowSystem, SolvesATreeOfEveryBlockSizeWithLimitRowsAfterTheRest) {
  std::mt19937 random(2);
  const Bodies bodies = randomBodies(13, random);
  std::vector<JointSolverRow> rows;
  // A torso (0) with limbs of two links each, and one link welded to the
  // world; sizes 1 to 6 (a rod, ball, hinge, fixed).
  int link = 0;
  addLink(rows, link++, -1, 0, 5, random);
  for (int limb = 0; limb < 6; ++limb) {
    const int upper = 1 + 2 * limb, lower = upper + 1;
    addLink(rows, link++, 0, upper, limb == 5 ? 5 : 3 + limb % 3, random);
    addLink(rows, link++, upper, lower, limb == 5 ? 2 : 1 + limb, random);
  }
  // Limit rows, each its link's last, after every joint row (as the joint
  // step appends them): a hinge's 5 + 1 in link 0's and link 11's blocks.
  addLink(rows, 0, -1, 0, 1, random);
  addLink(rows, 4, 3, 4, 1, random);
  addLink(rows, 11, 0, 11, 1, random);
  expectSolves(rows, bodies, random);
}

TEST(RowSystem, SolvesLoopsThatFillIn) {
  std::mt19937 random(3);
  // A four-bar: ground (world), crank 0, coupler 1, rocker 2, back to the
  // ground; and a 6 × 6 grid of bodies joined to their neighbours, its top
  // row pinned.
  {
    const Bodies bodies = randomBodies(3, random);
    std::vector<JointSolverRow> rows;
    addLink(rows, 0, -1, 0, 5, random);
    addLink(rows, 1, 0, 1, 5, random);
    addLink(rows, 2, 1, 2, 5, random);
    addLink(rows, 3, 2, -1, 3, random);
    expectSolves(rows, bodies, random);
  }
  {
    constexpr int n = 6;
    const Bodies bodies = randomBodies(n * n, random);
    std::vector<JointSolverRow> rows;
    int link = 0;
    for (int i = 0; i < n; ++i) addLink(rows, link++, -1, i, 3, random);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        if (c + 1 < n) addLink(rows, link++, r * n + c, r * n + c + 1, 3, random);
        if (r + 1 < n) addLink(rows, link++, r * n + c, (r + 1) * n + c, 3, random);
      }
    expectSolves(rows, bodies, random);
  }
}

TEST(RowSystem, AKeptAnalysisGivesTheBitsOfAFreshOne) {
  std::mt19937 random(4);
  const Bodies bodies = randomBodies(20, random);
  // A tree with a loop; then the same joints with other rows (the next
  // step), with a limit row added (a block grows), and without it again.
  const auto makeRows = [&](bool withLimit) {
    std::vector<JointSolverRow> rows;
    for (int i = 0; i < 20; ++i) addLink(rows, i, i - 1, i, i % 2 ? 5 : 3, random);
    addLink(rows, 20, 3, 17, 3, random);
    if (withLimit) addLink(rows, 7, 6, 7, 1, random);
    return rows;
  };
  RowSystem kept;
  for (const bool withLimit : {false, false, true, false}) {
    const std::vector<JointSolverRow> rows = makeRows(withLimit);
    kept.factor(rows, bodies.inverseMass, bodies.inverseInertia);
    RowSystem fresh;
    fresh.factor(rows, bodies.inverseMass, bodies.inverseInertia);
    ASSERT_TRUE(kept.ok());
    ASSERT_TRUE(fresh.ok());
    const Eigen::VectorXd b = randomRhs(static_cast<Eigen::Index>(rows.size()), random);
    EXPECT_TRUE(sameBits(kept.solve(b), fresh.solve(b))) << "with limit: " << withLimit;
    expectSolves(rows, bodies, random);
  }
}

TEST(RowSystem, AFactorAskedForWithTheSameBitsIsKeptAndAnyOtherBitRefactors) {
  std::mt19937 random(6);
  Bodies bodies = randomBodies(12, random);
  std::vector<JointSolverRow> rows;
  for (int i = 0; i < 12; ++i) addLink(rows, i, i - 1, i, i % 2 ? 5 : 3, random);
  RowSystem system;
  system.factor(rows, bodies.inverseMass, bodies.inverseInertia);
  ASSERT_TRUE(system.ok());
  EXPECT_TRUE(system.madeFrom(rows, bodies.inverseMass, bodies.inverseInertia));
  const Eigen::VectorXd b = randomRhs(static_cast<Eigen::Index>(rows.size()), random);
  const Eigen::VectorXd first = system.solve(b);

  // The same inputs (copies): kept, nothing factorised.
  const RowSystemCounts before = RowSystem::counts();
  const std::vector<JointSolverRow> sameRows = rows;
  const Bodies sameBodies = bodies;
  system.factor(sameRows, sameBodies.inverseMass, sameBodies.inverseInertia);
  const RowSystemCounts after = RowSystem::counts();
  EXPECT_EQ(after.factorisations, before.factorisations);
  EXPECT_EQ(after.kept, before.kept + 1);
  EXPECT_TRUE(sameBits(system.solve(b), first));

  // One bit anywhere in the inputs (a row's number, a body index, a mass,
  // an inertia, even a zero's sign) is another factor, and it is made.
  const auto expectRefactors = [&](const std::vector<JointSolverRow>& otherRows, const Bodies& otherBodies,
                                   const char* what) {
    RowSystem copy = system;
    EXPECT_FALSE(copy.madeFrom(otherRows, otherBodies.inverseMass, otherBodies.inverseInertia)) << what;
    const std::uint64_t made = RowSystem::counts().factorisations;
    copy.factor(otherRows, otherBodies.inverseMass, otherBodies.inverseInertia);
    EXPECT_EQ(RowSystem::counts().factorisations, made + 1) << what;
    RowSystem fresh;
    fresh.factor(otherRows, otherBodies.inverseMass, otherBodies.inverseInertia);
    if (copy.ok() && fresh.ok()) {
      EXPECT_TRUE(sameBits(copy.solve(b), fresh.solve(b))) << what;
    }
  };
  {
    std::vector<JointSolverRow> other = rows;
    other[7].jacobian.angularB.y() = std::nextafter(other[7].jacobian.angularB.y(), 2.0);
    expectRefactors(other, bodies, "a row's number");
  }
  {
    std::vector<JointSolverRow> other = rows;
    other[0].bodyA = 11;  // the first link to the last body instead of the world
    expectRefactors(other, bodies, "a row's side");
  }
  {
    Bodies other = bodies;
    other.inverseMass[3] = std::nextafter(other.inverseMass[3], 0.0);
    expectRefactors(rows, other, "a mass");
  }
  {
    Bodies other = bodies;
    other.inverseInertia[5](1, 2) = std::nextafter(other.inverseInertia[5](1, 2), 10.0);
    expectRefactors(rows, other, "an inertia");
  }
  {
    std::vector<JointSolverRow> zero = rows, negativeZero = rows;
    zero[2].jacobian.linearA.x() = 0.0;
    negativeZero[2].jacobian.linearA.x() = -0.0;
    system.factor(zero, bodies.inverseMass, bodies.inverseInertia);
    expectRefactors(negativeZero, bodies, "a zero's sign");
  }
}

TEST(RowSystem, NoRowsOrRowsThatMoveNothingAreNoSystem) {
  std::mt19937 random(5);
  const Bodies bodies = randomBodies(2, random);
  RowSystem system;
  system.factor({}, bodies.inverseMass, bodies.inverseInertia);
  EXPECT_FALSE(system.ok());
  // A row between two fixed sides: K has a zero diagonal.
  std::vector<JointSolverRow> rows;
  addLink(rows, 0, 0, 1, 3, random);
  addLink(rows, 1, -1, -1, 1, random);
  system.factor(rows, bodies.inverseMass, bodies.inverseInertia);
  EXPECT_FALSE(system.ok());
}

}  // namespace
}  // namespace rbsim
