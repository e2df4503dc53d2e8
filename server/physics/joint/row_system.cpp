#include "physics/joint/row_system.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

namespace rbsim {

namespace {

std::atomic<std::uint64_t> g_factorisations{0};
std::atomic<std::uint64_t> g_kept{0};
std::atomic<std::uint64_t> g_solves{0};

// Where row position `row` sits among column `column`'s off-diagonal blocks
// (as an index into `below`); the symbolic factorisation guarantees it is
// there.
int findBelow(const std::vector<int>& columnStart, const std::vector<int>& below, int column, int row) {
  const auto first = below.begin() + columnStart[static_cast<std::size_t>(column)];
  const auto last = below.begin() + columnStart[static_cast<std::size_t>(column) + 1];
  const auto at = std::lower_bound(first, last, row);
  return static_cast<int>(at - below.begin());
}

// In place, the lower Cholesky factor of the n × n column-major block d
// (only its lower triangle is read), its diagonal kept as reciprocals (the
// solves multiply by them: no division on their critical path). False if
// it is not positive definite.
bool choleskyInPlace(double* d, int n) {
  for (int k = 0; k < n; ++k) {
    double pivot = d[k + n * k];
    for (int m = 0; m < k; ++m) pivot -= d[k + n * m] * d[k + n * m];
    if (!(pivot > 0.0) || !std::isfinite(pivot)) return false;
    const double inverse = 1.0 / std::sqrt(pivot);
    d[k + n * k] = inverse;
    for (int i = k + 1; i < n; ++i) {
      double v = d[i + n * k];
      for (int m = 0; m < k; ++m) v -= d[i + n * m] * d[k + n * m];
      d[i + n * k] = v * inverse;
    }
  }
  return true;
}

// b := b L⁻ᵀ for the rows × n column-major block b and the n × n lower
// factor l (its diagonal as reciprocals).
void solveRightTransposed(const double* l, int n, double* b, int rows) {
  for (int i = 0; i < rows; ++i)
    for (int k = 0; k < n; ++k) {
      double v = b[i + rows * k];
      for (int m = 0; m < k; ++m) v -= l[k + n * m] * b[i + rows * m];
      b[i + rows * k] = v * l[k + n * k];
    }
}

// t −= a bᵀ: a is ra × S, b is rb × S, t is ra × rb (all column-major);
// only t's lower triangle when `lowerOnly` (a diagonal block, a == b).
// S, the eliminated column's size, is fixed so the inner loop unrolls;
// three rows everywhere (a grid of ball joints) has its own loop.
template <int S>
void subtractProduct(const double* a, int ra, const double* b, int rb, double* t, bool lowerOnly) {
  if (S == 3 && ra == 3 && rb == 3 && !lowerOnly) {
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) t[i + 3 * j] -= a[i] * b[j] + a[i + 3] * b[j + 3] + a[i + 6] * b[j + 6];
    return;
  }
  for (int j = 0; j < rb; ++j)
    for (int i = lowerOnly ? j : 0; i < ra; ++i) {
      double v = 0.0;
      for (int m = 0; m < S; ++m) v += a[i + ra * m] * b[j + rb * m];
      t[i + ra * j] -= v;
    }
}

// Column p's updates of the blocks its off-diagonal blocks reach, S its
// size: for each block b, the diagonal block of b's row, then the blocks
// below it in b's row's column (`targets`, in that order).
template <int S>
void updateFromColumn(double* values, const int* belowAt, const int* belowRow, int first, int last,
                      const int* sizeAt, const int* diagonalAt, const int*& targets) {
  for (int b = first; b < last; ++b) {
    const int rowB = belowRow[b];
    const int rb = sizeAt[rowB];
    const double* lb = values + belowAt[b];
    subtractProduct<S>(lb, rb, lb, rb, values + diagonalAt[rowB], true);
    for (int a = b + 1; a < last; ++a)
      subtractProduct<S>(values + belowAt[a], sizeAt[belowRow[a]], lb, rb, values + belowAt[*targets++], false);
  }
}

// Bit-for-bit equality (a -0 is not a 0 here, a NaN is its own bits): a
// kept factor must give the bits a fresh one would.
bool sameBits(const double* a, const double* b, std::size_t count) {
  return std::memcmp(a, b, count * sizeof(double)) == 0;
}
bool sameBits(const Vec3& a, const Vec3& b) { return sameBits(a.data(), b.data(), 3); }
bool sameBits(const JointRow& a, const JointRow& b) {
  return sameBits(a.linearA, b.linearA) && sameBits(a.angularA, b.angularA) && sameBits(a.linearB, b.linearB) &&
         sameBits(a.angularB, b.angularB);
}
bool sameBits(const JointSolverRow& a, const JointSolverRow& b) {
  return a.bodyA == b.bodyA && a.bodyB == b.bodyB && a.bodyC == b.bodyC && a.bodyD == b.bodyD && a.link == b.link &&
         sameBits(a.jacobian, b.jacobian) && sameBits(a.second, b.second);
}

}  // namespace

bool RowSystem::madeFrom(const std::vector<JointSolverRow>& rows, const std::vector<double>& inverseMass,
                         const std::vector<Mat3>& inverseInertia) const {
  if (!m_made || rows.size() != m_madeRows.size() || inverseMass.size() != m_madeInverseMass.size() ||
      inverseInertia.size() != m_madeInverseInertia.size())
    return false;
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (!sameBits(rows[r], m_madeRows[r])) return false;
  if (!inverseMass.empty() && !sameBits(inverseMass.data(), m_madeInverseMass.data(), inverseMass.size())) return false;
  for (std::size_t i = 0; i < inverseInertia.size(); ++i)
    if (!sameBits(inverseInertia[i].data(), m_madeInverseInertia[i].data(), 9)) return false;
  return true;
}

bool RowSystem::madeFor(const std::vector<JointSolverRow>& rows) const {
  if (!m_made || rows.size() != m_madeRows.size()) return false;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const JointSolverRow& a = rows[r];
    const JointSolverRow& b = m_madeRows[r];
    if (a.link != b.link || a.bodyA != b.bodyA || a.bodyB != b.bodyB || a.bodyC != b.bodyC || a.bodyD != b.bodyD)
      return false;
  }
  return true;
}

RowSystemCounts RowSystem::counts() {
  return {g_factorisations.load(std::memory_order_relaxed), g_kept.load(std::memory_order_relaxed),
          g_solves.load(std::memory_order_relaxed)};
}

void RowSystem::analyse() {
  const int blocks = static_cast<int>(m_keys.size());
  // The blocks touching each body.
  int bodies = 0;
  for (const BlockKey& key : m_keys)
    for (const int body : key.bodies) bodies = std::max(bodies, body + 1);
  std::vector<std::vector<Touch>> touching(static_cast<std::size_t>(bodies));
  for (int b = 0; b < blocks; ++b) {
    const BlockKey& key = m_keys[static_cast<std::size_t>(b)];
    for (int side = 0; side < JointSolverRow::kMaxSides; ++side)
      if (key.bodies[static_cast<std::size_t>(side)] >= 0)
        touching[static_cast<std::size_t>(key.bodies[static_cast<std::size_t>(side)])].push_back({b, side});
  }

  // The elimination order: approximate minimum degree on the block graph.
  std::vector<Eigen::Triplet<double, int>> pattern;
  for (int b = 0; b < blocks; ++b) pattern.emplace_back(b, b, 1.0);
  for (const auto& list : touching)
    for (const Touch& i : list)
      for (const Touch& j : list)
        if (i.block != j.block) pattern.emplace_back(i.block, j.block, 1.0);
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> graph(blocks, blocks);
  graph.setFromTriplets(pattern.begin(), pattern.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(graph, order);  // order.indices()[position] = block
  m_blockAt.assign(order.indices().data(), order.indices().data() + blocks);
  m_positionOf.assign(static_cast<std::size_t>(blocks), 0);
  for (int p = 0; p < blocks; ++p) m_positionOf[static_cast<std::size_t>(m_blockAt[static_cast<std::size_t>(p)])] = p;

  // The symbolic factorisation: column p's blocks below the diagonal are
  // its neighbours later in the order and its children's, less itself; its
  // parent in the elimination tree is the first of them.
  std::vector<std::vector<int>> later(static_cast<std::size_t>(blocks));
  for (const auto& list : touching)
    for (const Touch& i : list)
      for (const Touch& j : list) {
        const int pi = m_positionOf[static_cast<std::size_t>(i.block)];
        const int pj = m_positionOf[static_cast<std::size_t>(j.block)];
        if (pi > pj) later[static_cast<std::size_t>(pj)].push_back(pi);
      }
  std::vector<std::vector<int>> structure(static_cast<std::size_t>(blocks));
  std::vector<std::vector<int>> children(static_cast<std::size_t>(blocks));
  for (int p = 0; p < blocks; ++p) {
    std::vector<int>& rows = structure[static_cast<std::size_t>(p)];
    rows = std::move(later[static_cast<std::size_t>(p)]);
    for (const int child : children[static_cast<std::size_t>(p)])
      for (const int r : structure[static_cast<std::size_t>(child)])
        if (r != p) rows.push_back(r);
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    if (!rows.empty()) children[static_cast<std::size_t>(rows.front())].push_back(p);
  }
  m_columnStart.assign(1, 0);
  m_below.clear();
  for (const auto& rows : structure) {
    m_below.insert(m_below.end(), rows.begin(), rows.end());
    m_columnStart.push_back(static_cast<int>(m_below.size()));
  }

  // Where each column's updates of blocks off the diagonal go (in the
  // order updateFromColumn makes them).
  m_updateTarget.clear();
  for (int p = 0; p < blocks; ++p) {
    const int first = m_columnStart[static_cast<std::size_t>(p)];
    const int last = m_columnStart[static_cast<std::size_t>(p) + 1];
    for (int b = first; b < last; ++b)
      for (int a = b + 1; a < last; ++a)
        m_updateTarget.push_back(findBelow(m_columnStart, m_below, m_below[static_cast<std::size_t>(b)],
                                           m_below[static_cast<std::size_t>(a)]));
  }

  // Where K's contributions go: per body, its touches in elimination order.
  m_touchStart.assign(1, 0);
  m_touches.clear();
  m_assemblyTarget.clear();
  for (auto& list : touching) {
    std::sort(list.begin(), list.end(), [&](const Touch& x, const Touch& y) {
      return m_positionOf[static_cast<std::size_t>(x.block)] < m_positionOf[static_cast<std::size_t>(y.block)];
    });
    for (std::size_t i = 0; i < list.size(); ++i)
      for (std::size_t j = 0; j <= i; ++j) {
        const int pi = m_positionOf[static_cast<std::size_t>(list[i].block)];
        const int pj = m_positionOf[static_cast<std::size_t>(list[j].block)];
        m_assemblyTarget.push_back(i == j ? -1 - pi : findBelow(m_columnStart, m_below, pj, pi));
      }
    m_touches.insert(m_touches.end(), list.begin(), list.end());
    m_touchStart.push_back(static_cast<int>(m_touches.size()));
  }
}

void RowSystem::factor(const std::vector<JointSolverRow>& rows, const std::vector<double>& inverseMass,
                       const std::vector<Mat3>& inverseInertia) {
  if (madeFrom(rows, inverseMass, inverseInertia)) {
    g_kept.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  m_madeRows = rows;
  m_madeInverseMass = inverseMass;
  m_madeInverseInertia = inverseInertia;
  m_made = true;
  m_ok = false;
  m_rowCount = static_cast<Eigen::Index>(rows.size());
  if (rows.empty()) return;  // nothing to hold (ropes, all slack): no system

  // The blocks, in link order, and their rows.
  int links = 0;
  for (const JointSolverRow& row : rows) links = std::max(links, row.link + 1);
  // (Into kept storage, as all of a factor's numbers: a steady joint step
  // allocates nothing.)
  std::vector<int>& blockOfLink = m_blockOfLink;
  blockOfLink.assign(static_cast<std::size_t>(links), -1);
  for (const JointSolverRow& row : rows) blockOfLink[static_cast<std::size_t>(row.link)] = 0;
  std::vector<BlockKey>& keys = m_newKeys;
  keys.clear();
  for (int l = 0; l < links; ++l) {
    if (blockOfLink[static_cast<std::size_t>(l)] < 0) continue;
    blockOfLink[static_cast<std::size_t>(l)] = static_cast<int>(keys.size());
    keys.push_back({l, {-1, -1, -1, -1}});
  }
  m_sizeOf.assign(keys.size(), 0);
  m_rowsOf.resize(keys.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto block = static_cast<std::size_t>(blockOfLink[static_cast<std::size_t>(rows[r].link)]);
    int& size = m_sizeOf[block];
    if (size == kMaxBlock) return;  // more rows than a joint has: not a joint step's system
    m_rowsOf[block][static_cast<std::size_t>(size++)] = static_cast<int>(r);
    keys[block].bodies = {rows[r].bodyA, rows[r].bodyB, rows[r].bodyC, rows[r].bodyD};
  }
  if (keys != m_keys) {
    std::swap(m_keys, keys);
    analyse();
  }

  // Where each block's numbers go.
  const int blocks = static_cast<int>(m_keys.size());
  m_diagonalAt.resize(static_cast<std::size_t>(blocks));
  m_segmentAt.resize(static_cast<std::size_t>(blocks));
  m_belowAt.resize(m_below.size());
  m_sizeAt.resize(static_cast<std::size_t>(blocks));
  m_rowAtSlot.clear();
  for (int p = 0; p < blocks; ++p) {
    const auto block = static_cast<std::size_t>(m_blockAt[static_cast<std::size_t>(p)]);
    m_sizeAt[static_cast<std::size_t>(p)] = m_sizeOf[block];
    m_rowAtSlot.insert(m_rowAtSlot.end(), m_rowsOf[block].begin(), m_rowsOf[block].begin() + m_sizeOf[block]);
  }
  const auto sizeAt = [&](int position) { return m_sizeAt[static_cast<std::size_t>(position)]; };
  int offset = 0, segment = 0;
  for (int p = 0; p < blocks; ++p) {
    const int s = sizeAt(p);
    m_diagonalAt[static_cast<std::size_t>(p)] = offset;
    m_segmentAt[static_cast<std::size_t>(p)] = segment;
    offset += s * s;
    segment += s;
    for (int e = m_columnStart[static_cast<std::size_t>(p)]; e < m_columnStart[static_cast<std::size_t>(p) + 1]; ++e) {
      m_belowAt[static_cast<std::size_t>(e)] = offset;
      offset += sizeAt(m_below[static_cast<std::size_t>(e)]) * s;
    }
  }
  m_values.assign(static_cast<std::size_t>(offset), 0.0);
  // The solve's plan: each column's and block's place and size in one
  // record.
  m_columnPlan.resize(static_cast<std::size_t>(blocks));
  m_belowPlan.resize(m_below.size());
  for (int p = 0; p < blocks; ++p) {
    const auto position = static_cast<std::size_t>(p);
    m_columnPlan[position] = {m_diagonalAt[position], m_segmentAt[position], sizeAt(p), m_columnStart[position],
                              m_columnStart[position + 1]};
  }
  for (std::size_t e = 0; e < m_below.size(); ++e) {
    const auto row = static_cast<std::size_t>(m_below[e]);
    m_belowPlan[e] = {m_belowAt[e], m_segmentAt[row], m_sizeAt[row]};
  }
  // A target as an offset, and its row count (its leading dimension).
  const auto targetAt = [&](int target, int& leading) {
    if (target < 0) {
      const int p = -1 - target;
      leading = sizeAt(p);
      return m_diagonalAt[static_cast<std::size_t>(p)];
    }
    leading = sizeAt(m_below[static_cast<std::size_t>(target)]);
    return m_belowAt[static_cast<std::size_t>(target)];
  };

  // K = Σ over bodies of J_body M_body⁻¹ J_bodyᵀ, block by block.
  const auto side = [&](int row, int which, Vec3& linear, Vec3& angular) {
    const JointSolverRow& r = rows[static_cast<std::size_t>(row)];
    linear = r.linear(which);
    angular = r.angular(which);
  };
  std::size_t target = 0;
  for (std::size_t body = 0; body + 1 < m_touchStart.size(); ++body) {
    const double m = inverseMass[body];
    const Mat3& inverseI = inverseInertia[body];
    const int first = m_touchStart[body], last = m_touchStart[body + 1];
    for (int i = first; i < last; ++i) {
      const Touch& ti = m_touches[static_cast<std::size_t>(i)];
      const auto bi = static_cast<std::size_t>(ti.block);
      // This side's rows of block i, the angular parts through I⁻¹.
      Vec3 linearI[kMaxBlock], responseI[kMaxBlock];
      for (int r = 0; r < m_sizeOf[bi]; ++r) {
        Vec3 angular;
        side(m_rowsOf[bi][static_cast<std::size_t>(r)], ti.side, linearI[r], angular);
        responseI[r] = inverseI * angular;
      }
      for (int j = first; j <= i; ++j) {
        const Touch& tj = m_touches[static_cast<std::size_t>(j)];
        const auto bj = static_cast<std::size_t>(tj.block);
        int leading = 0;
        double* out = m_values.data() + targetAt(m_assemblyTarget[target++], leading);
        for (int c = 0; c < m_sizeOf[bj]; ++c) {
          Vec3 linearJ, angularJ;
          side(m_rowsOf[bj][static_cast<std::size_t>(c)], tj.side, linearJ, angularJ);
          for (int r = i == j ? c : 0; r < m_sizeOf[bi]; ++r)
            out[r + leading * c] += m * linearI[r].dot(linearJ) + angularJ.dot(responseI[r]);
        }
      }
    }
  }
  // A tiny relative regularisation keeps K definite when joints are
  // redundant (a four-bar's hinges constrain one motion twice). It only
  // changes how fast the iteration converges, not what it converges to:
  // the iteration stops on the constraint errors themselves.
  for (int p = 0; p < blocks; ++p) {
    const int s = sizeAt(p);
    double* d = m_values.data() + m_diagonalAt[static_cast<std::size_t>(p)];
    for (int k = 0; k < s; ++k) d[k + s * k] *= 1.0 + 1e-10;
  }

  g_factorisations.fetch_add(1, std::memory_order_relaxed);
  // L Lᵀ, column by column (right-looking): factor the diagonal block,
  // scale the column's blocks below it, update the blocks they reach.
  const int* targets = m_updateTarget.data();
  for (int p = 0; p < blocks; ++p) {
    const int s = sizeAt(p);
    double* d = m_values.data() + m_diagonalAt[static_cast<std::size_t>(p)];
    if (!choleskyInPlace(d, s)) return;
    const int first = m_columnStart[static_cast<std::size_t>(p)];
    const int last = m_columnStart[static_cast<std::size_t>(p) + 1];
    for (int e = first; e < last; ++e)
      solveRightTransposed(d, s, m_values.data() + m_belowAt[static_cast<std::size_t>(e)],
                           sizeAt(m_below[static_cast<std::size_t>(e)]));
    switch (s) {
#define RBSIM_UPDATE(S)                                                                                      \
  case S:                                                                                                    \
    updateFromColumn<S>(m_values.data(), m_belowAt.data(), m_below.data(), first, last, m_sizeAt.data(),   \
                        m_diagonalAt.data(), targets);                                                       \
    break;
      RBSIM_UPDATE(1) RBSIM_UPDATE(2) RBSIM_UPDATE(3) RBSIM_UPDATE(4)
      RBSIM_UPDATE(5) RBSIM_UPDATE(6) RBSIM_UPDATE(7)
#undef RBSIM_UPDATE
    }
  }
  m_ok = true;
}

namespace {

// One column of L y = z (a diagonal block of S rows, then the blocks below
// it), and of Lᵀ x = y, S fixed so the small loops unroll.
template <int S>
void forwardColumn(const double* values, const RowSystem::ColumnPlan& column, const RowSystem::BlockPlan* below,
                   double* z) {
  const double* l = values + column.diagonal;
  double* zp = z + column.segment;
  for (int k = 0; k < S; ++k) {
    double v = zp[k];
    for (int m = 0; m < k; ++m) v -= l[k + S * m] * zp[m];
    zp[k] = v * l[k + S * k];
  }
  for (int e = column.first; e < column.last; ++e) {
    const RowSystem::BlockPlan& block = below[e];
    const double* b = values + block.values;
    double* zr = z + block.segment;
    for (int i = 0; i < block.rows; ++i) {
      double v = 0.0;
      for (int k = 0; k < S; ++k) v += b[i + block.rows * k] * zp[k];
      zr[i] -= v;
    }
  }
}

template <int S>
void backwardColumn(const double* values, const RowSystem::ColumnPlan& column, const RowSystem::BlockPlan* below,
                    double* z) {
  double* zp = z + column.segment;
  for (int e = column.first; e < column.last; ++e) {
    const RowSystem::BlockPlan& block = below[e];
    const double* b = values + block.values;
    const double* zr = z + block.segment;
    for (int k = 0; k < S; ++k) {
      double v = 0.0;
      for (int i = 0; i < block.rows; ++i) v += b[i + block.rows * k] * zr[i];
      zp[k] -= v;
    }
  }
  const double* l = values + column.diagonal;
  for (int k = S - 1; k >= 0; --k) {
    double v = zp[k];
    for (int m = k + 1; m < S; ++m) v -= l[m + S * k] * zp[m];
    zp[k] = v * l[k + S * k];
  }
}

}  // namespace

Eigen::VectorXd RowSystem::solve(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd x = rhs;
  solveInPlace(x);
  return x;
}

void RowSystem::solveInPlace(Eigen::VectorXd& x) const {
  g_solves.fetch_add(1, std::memory_order_relaxed);
  // Into elimination order.
  m_scratch.z.resize(m_rowCount);
  double* z = m_scratch.z.data();
  for (Eigen::Index slot = 0; slot < m_rowCount; ++slot) z[slot] = x[m_rowAtSlot[static_cast<std::size_t>(slot)]];
  const double* values = m_values.data();
  const BlockPlan* below = m_belowPlan.data();
  // L y = z.
  for (const ColumnPlan& column : m_columnPlan) {
    switch (column.size) {
#define RBSIM_FORWARD(S) \
  case S: forwardColumn<S>(values, column, below, z); break;
      RBSIM_FORWARD(1) RBSIM_FORWARD(2) RBSIM_FORWARD(3) RBSIM_FORWARD(4)
      RBSIM_FORWARD(5) RBSIM_FORWARD(6) RBSIM_FORWARD(7)
#undef RBSIM_FORWARD
    }
  }
  // Lᵀ x = y.
  for (auto column = m_columnPlan.rbegin(); column != m_columnPlan.rend(); ++column) {
    switch (column->size) {
#define RBSIM_BACKWARD(S) \
  case S: backwardColumn<S>(values, *column, below, z); break;
      RBSIM_BACKWARD(1) RBSIM_BACKWARD(2) RBSIM_BACKWARD(3) RBSIM_BACKWARD(4)
      RBSIM_BACKWARD(5) RBSIM_BACKWARD(6) RBSIM_BACKWARD(7)
#undef RBSIM_BACKWARD
    }
  }
  // Back into the rows' order.
  for (Eigen::Index slot = 0; slot < m_rowCount; ++slot) x[m_rowAtSlot[static_cast<std::size_t>(slot)]] = z[slot];
}

}  // namespace rbsim
