#pragma once
// K = J M⁻¹ Jᵀ over the joints' rows, factorised K = L Lᵀ by blocks: one
// block per joint, holding all of its rows (and its limit's row, when the
// step holds one). Two blocks couple only through a body they share, so the
// block pattern is the joint graph's: for a tree of joints (a chain, an arm,
// a ragdoll) an elimination from the leaves makes no fill, and the factor
// and each solve cost O(joints) (Baraff, "Linear-Time Dynamics using
// Lagrange Multipliers", SIGGRAPH 1996); a loop (a four-bar, a grid of
// joints) fills in what its ordering makes it fill.
//
// The elimination order (approximate minimum degree on the block pattern:
// Amestoy, Davis and Duff, SIAM J. Matrix Anal. Appl. 17, 1996) and the
// symbolic factorisation (which blocks L has, which updates each column
// makes) depend only on which joints there are and which bodies they join,
// not on their rows' values or on how many rows a block has. They are kept
// while that graph stays (step after step, and while limits come and go)
// and are a pure function of it, so a kept analysis and a fresh one give
// the same bits.
//
// The numeric factor is a pure function of the rows, the inverse masses and
// the inverse inertias. RowSystem keeps a copy of those it was made from,
// and a factor asked for with inputs bit-identical to them is kept rather
// than made again: the joint step factors K at the step's end poses for
// the velocity projection, and the next step, starting there, finds its K₀
// already made (joint/joint_solver.h). Kept or made afresh, the bits are the
// same, so replay, checkpoints (which store no factor) and copies of a
// world stay bit-exact.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "physics/joint/joint_constraint.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

// One scalar row of the joint step's system: the link (joint) it belongs to
// and its sides. A joint's rows have two sides (A and B); a mimic
// coupling's row (joint_solver.h) spans the bodies of two joints, up to
// four, each at most once: its third and fourth sides are C and D, whose
// parts are `second`'s A and B parts.
struct JointSolverRow {
  int bodyA = -1, bodyB = -1;  // body indices, -1: a fixed side
  int link = 0;
  JointRow jacobian;
  int bodyC = -1, bodyD = -1;  // a coupling's further sides, -1: none
  JointRow second;

  static constexpr int kMaxSides = 4;
  // A joint's row: two sides, no coupling's further sides.
  static JointSolverRow of(int bodyA, int bodyB, int link, const JointRow& jacobian = {}) {
    JointSolverRow row;
    row.bodyA = bodyA;
    row.bodyB = bodyB;
    row.link = link;
    row.jacobian = jacobian;
    return row;
  }
  // The sides this row may have: 2 for a joint's row, 4 for a coupling's.
  int sideCount() const { return bodyC < 0 && bodyD < 0 ? 2 : 4; }
  int body(int side) const { return side == 0 ? bodyA : side == 1 ? bodyB : side == 2 ? bodyC : bodyD; }
  const Vec3& linear(int side) const {
    return side == 0 ? jacobian.linearA : side == 1 ? jacobian.linearB : side == 2 ? second.linearA : second.linearB;
  }
  const Vec3& angular(int side) const {
    return side == 0 ? jacobian.angularA : side == 1 ? jacobian.angularB : side == 2 ? second.angularA : second.angularB;
  }
};

// How much work the joint systems of this process have done: numeric
// factorisations of K, factorisations found already made (the inputs
// bit-identical to the kept factor's, RowSystem::factor), and solves with a
// factor. Always counted (a relaxed atomic add per factor or solve, far
// below either's cost), for the benchmarks (bench/joints) and the tests
// that check a factor is kept.
struct RowSystemCounts {
  std::uint64_t factorisations = 0;
  std::uint64_t kept = 0;
  std::uint64_t solves = 0;
};

class RowSystem {
 public:
  // Since the process started, over every RowSystem of every thread.
  static RowSystemCounts counts();

  // K of the rows for bodies of these inverse masses and (world) inverse
  // inertias, factorised. The rows of one link share a block; a link's rows
  // need not be next to each other (its limit's row may follow the rest).
  // Nothing is done when the inputs are bit-identical to the last factor's.
  void factor(const std::vector<JointSolverRow>& rows, const std::vector<double>& inverseMass,
              const std::vector<Mat3>& inverseInertia);
  // Whether the last factor was made from exactly these inputs (every bit).
  bool madeFrom(const std::vector<JointSolverRow>& rows, const std::vector<double>& inverseMass,
                const std::vector<Mat3>& inverseInertia) const;
  // Whether the last factor was made from rows of these links and bodies,
  // in this order (its numbers may differ): it is then a K of the same
  // pattern, which the joint step may keep as its quasi-Newton matrix
  // while it converges (JointSolverSettings::keepRatio).
  bool madeFor(const std::vector<JointSolverRow>& rows) const;

  // What a factor is made from; `made` false: no factor yet.
  struct Inputs {
    bool made = false;
    std::vector<JointSolverRow> rows;
    std::vector<double> inverseMass;
    std::vector<Mat3> inverseInertia;
  };
  Inputs inputs() const { return {m_made, m_madeRows, m_madeInverseMass, m_madeInverseInertia}; }
  // False when there are no rows or K was not positive definite.
  bool ok() const { return m_ok; }
  Eigen::Index size() const { return m_rowCount; }
  // K⁻¹ rhs, rhs in the rows' order.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  void solveInPlace(Eigen::VectorXd& x) const;

  // The solve's view of a column (elimination position) and of a block
  // below a diagonal: where its numbers and its rows' segment are, its
  // size; a column's blocks are [first, last) of the blocks' plan.
  struct ColumnPlan {
    int diagonal, segment, size, first, last;
  };
  struct BlockPlan {
    int values, segment, rows;
  };

 private:
  static constexpr int kMaxBlock = kMaxJointRows + 1;  // a joint's rows and its limit's

  // The block graph the analysis is of: per block, its link and bodies.
  struct BlockKey {
    int link;
    std::array<int, JointSolverRow::kMaxSides> bodies;
    bool operator==(const BlockKey& o) const { return link == o.link && bodies == o.bodies; }
  };
  void analyse();

  // --- the analysis (a function of m_keys only) ---
  std::vector<BlockKey> m_keys;  // by block, in link order
  std::vector<int> m_blockAt;    // elimination position -> block
  std::vector<int> m_positionOf; // block -> elimination position
  // L's off-diagonal blocks by column (elimination position): column c's
  // are m_below[m_columnStart[c] .. m_columnStart[c + 1]), their row
  // positions ascending.
  std::vector<int> m_columnStart;
  std::vector<int> m_below;
  // Column c's updates: for each pair (a, b), a > b, of its off-diagonal
  // blocks, the off-diagonal block L_a L_bᵀ goes to (by b, then a).
  std::vector<int> m_updateTarget;
  // K's contributions: per body, the blocks touching it (block, and which
  // side of its rows the body is: 0 A, 1 B, 2 C, 3 D).
  struct Touch {
    int block;
    int side;
  };
  std::vector<int> m_touchStart;
  std::vector<Touch> m_touches;
  // Per pair of touches of one body (first >= second in elimination
  // order), where their K block goes (as m_updateTarget).
  std::vector<int> m_assemblyTarget;

  // factor's scratch: each link's block, and the block keys of the rows
  // asked for (compared with m_keys).
  std::vector<int> m_blockOfLink;
  std::vector<BlockKey> m_newKeys;

  // --- the inputs of the last factor (madeFrom) ---
  std::vector<JointSolverRow> m_madeRows;
  std::vector<double> m_madeInverseMass;
  std::vector<Mat3> m_madeInverseInertia;
  bool m_made = false;

  // --- the numbers, per factor ---
  std::vector<std::array<int, kMaxBlock>> m_rowsOf;  // by block: its rows' indices
  std::vector<int> m_sizeOf;                          // by block
  std::vector<int> m_sizeAt;                          // by position
  std::vector<int> m_rowAtSlot;  // the rows in elimination order
  // The solve's scratch: not copied with the system (a copy of a kept
  // factor, joint_velocity_projection.cpp, keeps its own storage).
  struct Scratch {
    Eigen::VectorXd z;
    Scratch() = default;
    Scratch(const Scratch&) {}
    Scratch& operator=(const Scratch&) { return *this; }
  };
  mutable Scratch m_scratch;
  std::vector<ColumnPlan> m_columnPlan;  // by position
  std::vector<BlockPlan> m_belowPlan;    // by off-diagonal block
  std::vector<int> m_diagonalAt;  // by position: offset of the diagonal block in m_values
  std::vector<int> m_belowAt;     // by off-diagonal block: offset in m_values
  std::vector<int> m_segmentAt;   // by position: offset of its rows in the solve's vector
  std::vector<double> m_values;
  Eigen::Index m_rowCount = 0;
  bool m_ok = false;
};

}  // namespace rbsim
