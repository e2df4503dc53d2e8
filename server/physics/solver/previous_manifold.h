#pragma once
// Last step's solved manifold of a contact, for warm starting.

#include <cstddef>
#include <cstdint>
#include <tuple>
#include <vector>

#include "rbsim/physics/contacts.h"

namespace rbsim {

// Bodies' serials and pieces: what identifies a contact from step to step.
using ManifoldKey = std::tuple<int32_t, int32_t, int, int>;

// Last step's manifold with this key (same bodies and pieces), or null.
// `previous` is sorted by key and so are the calls: `cursor` only moves on.
inline const SolvedManifold* previousManifold(const std::vector<SolvedManifold>& previous,
                                              const ManifoldKey& key, std::size_t& cursor) {
  const auto keyOf = [](const SolvedManifold& s) {
    return ManifoldKey{s.serialA, s.serialB, s.pieceA, s.pieceB};
  };
  while (cursor < previous.size() && keyOf(previous[cursor]) < key) ++cursor;
  return cursor < previous.size() && keyOf(previous[cursor]) == key ? &previous[cursor] : nullptr;
}

}  // namespace rbsim
