#include "physics/solver/sweep_batches.h"

#include <algorithm>
#include <bit>
#include <numeric>

namespace rbsim {

namespace {

constexpr int kColours = 64;  // one bit each in a body's mask
constexpr int kOverflow = kColours;

}  // namespace

void SweepBatcher::build(std::span<const ConstraintBodies> constraints, std::span<const char> moves,
                         std::span<const int> stage, SweepBatches& out) {
  const std::size_t count = constraints.size();
  out.order.clear();
  out.batchStart.assign(1, 0);
  out.inOrder.clear();
  m_byStage.resize(count);
  std::iota(m_byStage.begin(), m_byStage.end(), 0);
  if (!stage.empty())  // stable: within a stage, the constraints' own order
    std::stable_sort(m_byStage.begin(), m_byStage.end(), [&](int x, int y) {
      return stage[static_cast<std::size_t>(x)] < stage[static_cast<std::size_t>(y)];
    });
  m_coloursTaken.assign(moves.size(), 0);
  m_colourOf.resize(count);

  const auto moving = [&](int body) { return moves[static_cast<std::size_t>(body)] != 0; };
  std::size_t first = 0;
  while (first < count) {
    // One stage: [first, end) of m_byStage.
    std::size_t end = first + 1;
    if (!stage.empty()) {
      const int s = stage[static_cast<std::size_t>(m_byStage[first])];
      while (end < count && stage[static_cast<std::size_t>(m_byStage[end])] == s) ++end;
    } else {
      end = count;
    }
    m_colourCount.assign(kColours + 1, 0);
    for (std::size_t k = first; k < end; ++k) {
      const ConstraintBodies& c = constraints[static_cast<std::size_t>(m_byStage[k])];
      uint64_t taken = 0;
      if (moving(c.bodyA)) taken |= m_coloursTaken[static_cast<std::size_t>(c.bodyA)];
      if (moving(c.bodyB)) taken |= m_coloursTaken[static_cast<std::size_t>(c.bodyB)];
      const int colour = taken == ~uint64_t{0} ? kOverflow : std::countr_one(taken);
      m_colourOf[k] = colour;
      ++m_colourCount[static_cast<std::size_t>(colour)];
      if (colour == kOverflow) continue;
      const uint64_t bit = uint64_t{1} << colour;
      if (moving(c.bodyA)) m_coloursTaken[static_cast<std::size_t>(c.bodyA)] |= bit;
      if (moving(c.bodyB)) m_coloursTaken[static_cast<std::size_t>(c.bodyB)] |= bit;
    }
    // The stage's batches: its colours in order, each in constraint order,
    // then its overflow (a counting sort by colour).
    const std::size_t base = out.order.size();
    out.order.resize(base + (end - first));
    m_colourStart.assign(kColours + 2, 0);
    for (int colour = 0; colour <= kOverflow; ++colour)
      m_colourStart[static_cast<std::size_t>(colour) + 1] =
          m_colourStart[static_cast<std::size_t>(colour)] + m_colourCount[static_cast<std::size_t>(colour)];
    for (std::size_t k = first; k < end; ++k)
      out.order[base + static_cast<std::size_t>(m_colourStart[static_cast<std::size_t>(m_colourOf[k])]++)] =
          m_byStage[k];
    int position = static_cast<int>(base);
    for (int colour = 0; colour <= kOverflow; ++colour) {
      const int size = m_colourCount[static_cast<std::size_t>(colour)];
      if (size == 0) continue;
      position += size;
      out.batchStart.push_back(position);
      out.inOrder.push_back(colour == kOverflow ? 1 : 0);
    }
    // The next stage starts with no colour taken.
    for (std::size_t k = first; k < end; ++k) {
      const ConstraintBodies& c = constraints[static_cast<std::size_t>(m_byStage[k])];
      m_coloursTaken[static_cast<std::size_t>(c.bodyA)] = 0;
      m_coloursTaken[static_cast<std::size_t>(c.bodyB)] = 0;
    }
    first = end;
  }
}

}  // namespace rbsim
