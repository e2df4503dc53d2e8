#include "physics/collision/broad_phase.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <iterator>

namespace rbsim {

namespace {

constexpr std::size_t at(int index) {
  return static_cast<std::size_t>(index);
}

// A moving proxy's fat box is stretched by this many steps' worth of its
// last displacement, so a steadily moving body is re-inserted less often.
constexpr double kPredictionSteps = 2.0;

constexpr auto byKey = [](const auto& a, const auto& b) { return a.key < b.key; };

}  // namespace

BroadPhase::BroadPhase(double fatMargin, double contactMargin)
    : m_fatMargin(fatMargin), m_contactMargin(contactMargin), m_tree(fatMargin) {
  assert(fatMargin >= 0.0 && contactMargin >= 0.0);
}

BroadPhaseShape BroadPhaseShape::of(const Body& body) {
  BroadPhaseShape shape;
  shape.isStatic = body.isStatic();
  shape.filter = body.description().collisionFilter;
  if (const Collider* collider = body.description().collider.get()) {
    if (!collider->pieces.empty() || collider->triangles) shape.bounds = collider->bounds;
    shape.plane = collider->plane;
  }
  return shape;
}

BroadPhaseBody BroadPhaseShape::placed(int32_t serial, int index, const Transform& pose) const {
  BroadPhaseBody body;
  body.serial = serial;
  body.index = index;
  body.isStatic = isStatic;
  body.filter = filter;
  if (bounds) body.box = transformedAabb(*bounds, pose);
  if (plane) body.plane = worldHalfSpace(*plane, pose);
  return body;
}

void BroadPhase::update(std::span<const Body> bodies, std::span<const uint64_t> excludedPairs) {
  m_inputs.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    const BroadPhaseShape shape = BroadPhaseShape::of(body);
    if (shape.hasGeometry() && !body.isFrozen())  // frozen: out of the simulation
      m_inputs.push_back(
          shape.placed(body.serial(), static_cast<int>(i), {body.rotation(), body.position()}));
  }
  update(m_inputs, excludedPairs);
}

void BroadPhase::update(std::span<const BroadPhaseBody> bodies, std::span<const uint64_t> excludedPairs) {
  assert(std::is_sorted(excludedPairs.begin(), excludedPairs.end()));
  m_movedCount = 0;
  if (!canFollow(bodies)) clear();
  const bool entriesShifted = syncEntries(bodies);
  updateCandidates(entriesShifted);
  collectPairs(excludedPairs);
}

void BroadPhase::clear() {
  m_tree = DynamicAabbTree(m_fatMargin);
  m_entries.clear();
  m_filters.clear();
  m_candidates.clear();
}

// Whether `bodies` can be reached from the current entries by removals and
// appends alone: serials ascending, and any serial not known yet larger
// than every known one.
bool BroadPhase::canFollow(std::span<const BroadPhaseBody> bodies) const {
  std::size_t known = 0;
  int32_t previous = 0;
  for (std::size_t j = 0; j < bodies.size(); ++j) {
    const int32_t serial = bodies[j].serial;
    if (j > 0 && serial <= previous) return false;
    previous = serial;
    while (known < m_entries.size() && m_entries[known].serial < serial) ++known;
    if (known == m_entries.size()) break;  // the rest are new and larger than all known
    if (m_entries[known].serial != serial) return false;
  }
  return true;
}

// Removes the entries of bodies that are gone (compacting in place, so the
// order stays by serial), updates the others and appends the new ones.
// Returns whether any entry changed index.
bool BroadPhase::syncEntries(std::span<const BroadPhaseBody> bodies) {
  m_planes.clear();
  const std::size_t oldCount = m_entries.size();
  m_filters.resize(oldCount);
  m_remap.assign(oldCount, -1);
  std::size_t next = 0;  // next input body
  int write = 0;
  for (std::size_t read = 0; read < oldCount; ++read) {
    Entry& entry = m_entries[read];
    if (next < bodies.size() && bodies[next].serial == entry.serial) {
      if (at(write) != read) {
        m_entries[at(write)] = entry;
        if (entry.proxy != DynamicAabbTree::kNull) m_tree.setUserData(entry.proxy, write);
      }
      m_remap[read] = write;
      syncEntry(write, bodies[next]);
      ++next;
      ++write;
    } else if (entry.proxy != DynamicAabbTree::kNull) {
      m_tree.destroyProxy(entry.proxy);
    }
  }
  const bool shifted = at(write) != oldCount;
  m_entries.resize(at(write));
  m_filters.resize(at(write));
  for (; next < bodies.size(); ++next) {
    const int index = static_cast<int>(m_entries.size());
    m_filters.emplace_back();
    Entry& entry = m_entries.emplace_back();
    entry.serial = bodies[next].serial;
    entry.isStatic = bodies[next].isStatic;
    syncEntry(index, bodies[next]);
  }
  return shifted;
}

void BroadPhase::syncEntry(int entryIndex, const BroadPhaseBody& body) {
  Entry& entry = m_entries[at(entryIndex)];
  entry.moved = entry.isStatic != body.isStatic;
  entry.isStatic = body.isStatic;
  entry.index = body.index;
  m_filters[at(entryIndex)] = body.filter;
  if (body.plane) m_planes.push_back({entryIndex, *body.plane});
  if (body.box) {
    const Aabb box = body.box->fattened(0.5 * m_contactMargin);
    if (entry.proxy == DynamicAabbTree::kNull) {
      entry.proxy = m_tree.createProxy(box, entryIndex);
      entry.moved = true;
    } else {
      const Vec3 displacement = kPredictionSteps * (box.center() - entry.box.center());
      if (m_tree.moveProxy(entry.proxy, box, displacement)) entry.moved = true;
    }
    entry.box = box;
  } else if (entry.proxy != DynamicAabbTree::kNull) {
    m_tree.destroyProxy(entry.proxy);
    entry.proxy = DynamicAabbTree::kNull;
    entry.moved = true;
  }
  if (entry.moved) ++m_movedCount;
}

BroadPhase::Candidate BroadPhase::makeCandidate(int entryA, int entryB) const {
  // Entries are in serial order, so the lower index has the lower serial.
  if (entryB < entryA) std::swap(entryA, entryB);
  const auto serialA = static_cast<uint64_t>(static_cast<uint32_t>(m_entries[at(entryA)].serial));
  const auto serialB = static_cast<uint64_t>(static_cast<uint32_t>(m_entries[at(entryB)].serial));
  return {(serialA << 32) | serialB, entryA, entryB};
}

// The candidates are the pairs whose fat boxes overlap. A pair of proxies
// that both kept their fat boxes keeps its status, so only the pairs of
// moved proxies are dropped and found again by querying the tree.
void BroadPhase::updateCandidates(bool entriesShifted) {
  std::size_t kept = 0;
  for (Candidate candidate : m_candidates) {
    if (entriesShifted) {
      candidate.entryA = m_remap[at(candidate.entryA)];
      candidate.entryB = m_remap[at(candidate.entryB)];
      if (candidate.entryA < 0 || candidate.entryB < 0) continue;
    }
    if (m_entries[at(candidate.entryA)].moved || m_entries[at(candidate.entryB)].moved) continue;
    m_candidates[kept++] = candidate;
  }
  m_candidates.resize(kept);

  m_found.clear();
  for (int i = 0; i < static_cast<int>(m_entries.size()); ++i) {
    const Entry& entry = m_entries[at(i)];
    if (!entry.moved || entry.proxy == DynamicAabbTree::kNull) continue;
    m_tree.query(m_tree.fatAabb(entry.proxy), [&](int proxy) {
      const int other = m_tree.userData(proxy);
      const Entry& otherEntry = m_entries[at(other)];
      // Two moved proxies find each other: keep the pair from the lower index only.
      const bool foundFromOtherSide = otherEntry.moved && other < i;
      if (other != i && !(entry.isStatic && otherEntry.isStatic) && !foundFromOtherSide)
        m_found.push_back(makeCandidate(i, other));
      return true;
    });
  }
  if (m_found.empty()) return;
  std::sort(m_found.begin(), m_found.end(), byKey);
  m_merged.clear();
  std::merge(m_candidates.begin(), m_candidates.end(), m_found.begin(), m_found.end(),
             std::back_inserter(m_merged), byKey);
  m_candidates.swap(m_merged);
}

bool BroadPhase::filtersAllow(const Candidate& candidate, std::span<const uint64_t> excludedPairs,
                              std::size_t& excludedCursor) const {
  if (!m_filters[at(candidate.entryA)].allows(m_filters[at(candidate.entryB)])) return false;
  // Candidates come in ascending key order: the cursor only moves forward.
  while (excludedCursor < excludedPairs.size() && excludedPairs[excludedCursor] < candidate.key) ++excludedCursor;
  return excludedCursor == excludedPairs.size() || excludedPairs[excludedCursor] != candidate.key;
}

void BroadPhase::collectPairs(std::span<const uint64_t> excludedPairs) {
  // Candidates whose grown tight boxes overlap and whose filters allow
  // them, still sorted by key.
  m_touching.clear();
  std::size_t excludedCursor = 0;
  for (const Candidate& candidate : m_candidates) {
    if (m_entries[at(candidate.entryA)].box.overlaps(m_entries[at(candidate.entryB)].box) &&
        filtersAllow(candidate, excludedPairs, excludedCursor))
      m_touching.push_back(candidate);
  }

  // Plane pairs: a plane against every proxy that reaches its half-space
  // (the box is already grown by half the margin; grow the plane by the other half).
  m_found.clear();
  for (const PlaneEntry& planeOwner : m_planes) {
    const int p = planeOwner.entry;
    const Entry& planeEntry = m_entries[at(p)];
    const HalfSpace& plane = planeOwner.halfSpace;
    const double reach = plane.offset + 0.5 * m_contactMargin;
    for (int i = 0; i < static_cast<int>(m_entries.size()); ++i) {
      const Entry& entry = m_entries[at(i)];
      if (i == p || entry.proxy == DynamicAabbTree::kNull) continue;
      if (planeEntry.isStatic && entry.isStatic) continue;
      if (lowestAlong(entry.box, plane.normal) <= reach) m_found.push_back(makeCandidate(p, i));
    }
  }

  const std::vector<Candidate>* sorted = &m_touching;
  if (!m_found.empty()) {
    std::sort(m_found.begin(), m_found.end(), byKey);
    excludedCursor = 0;
    std::size_t kept = 0;
    for (const Candidate& candidate : m_found)
      if (filtersAllow(candidate, excludedPairs, excludedCursor)) m_found[kept++] = candidate;
    m_found.resize(kept);
  }
  if (!m_found.empty()) {
    m_merged.clear();
    std::merge(m_touching.begin(), m_touching.end(), m_found.begin(), m_found.end(),
               std::back_inserter(m_merged), byKey);
    // A body with both a plane and pieces can be paired twice.
    const auto sameKey = [](const Candidate& a, const Candidate& b) { return a.key == b.key; };
    m_merged.erase(std::unique(m_merged.begin(), m_merged.end(), sameKey), m_merged.end());
    sorted = &m_merged;
  }
  m_pairs.clear();
  m_pairs.reserve(sorted->size());
  for (const Candidate& candidate : *sorted)
    m_pairs.push_back(
        {m_entries[at(candidate.entryA)].index, m_entries[at(candidate.entryB)].index});
}

}  // namespace rbsim
