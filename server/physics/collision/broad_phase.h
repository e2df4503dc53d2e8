#pragma once
// Broad phase: which pairs of bodies might touch. One tree proxy per body
// that has convex pieces (planes are infinite and are paired separately with
// every dynamic body whose box reaches them); static bodies never pair with
// each other. Incremental from step to step: proxies move only when a body
// leaves its fattened box, and only moved proxies query the tree. An update
// costs O(N) to follow the bodies and re-check the candidate pairs, plus
// O(M log N) tree work for the M proxies that moved and O(K log K) to sort
// the K pairs they found; and O(N) per plane.
//
// What is reported is a pure function of the current poses and collision
// filters (not of the tree's history): two bodies pair when their tight
// boxes, each grown by half the contact margin, overlap; a body pairs with a
// plane when its grown box reaches the plane's half-space grown by half the
// margin; and, either way, only when their collision groups and masks allow
// it (rbsim/physics/collision_filter.h) and their pair is not among the
// excluded ones given to update() (bodies a joint joins, pairs a robot or
// the user left out). The fat boxes of the tree only make finding those
// pairs cheap, and the filters are applied to the pairs found, not to the
// tree's candidates, so a change of filters takes effect at the next update.
// So a broad phase rebuilt from scratch (after a restore, say) gives exactly
// the same pairs.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "physics/body/body.h"
#include "physics/collision/collider.h"
#include "physics/collision/dynamic_aabb_tree.h"
#include "rbsim/physics/collision_filter.h"
#include "rbsim/physics/transform.h"

namespace rbsim {

// Two bodies by dense index into the bodies given to update(), ordered so that
// serial(a) < serial(b).
struct BodyPair {
  int a = 0;
  int b = 0;
  friend bool operator==(const BodyPair&, const BodyPair&) = default;
};

// The key of the pair of bodies with these serials, whichever order they
// come in: (lower serial << 32) | higher serial. Sorting keys sorts pairs
// by (serial A, serial B), the order in which the broad phase reports them.
inline uint64_t serialPairKey(int32_t serialA, int32_t serialB) {
  const auto low = static_cast<uint64_t>(static_cast<uint32_t>(serialA < serialB ? serialA : serialB));
  const auto high = static_cast<uint64_t>(static_cast<uint32_t>(serialA < serialB ? serialB : serialA));
  return (low << 32) | high;
}

// A half-space in the world frame: normal · p <= offset is solid.
struct HalfSpace {
  Vec3 normal = Vec3::UnitZ();  // unit, out of the solid
  double offset = 0.0;          // m
};

// The world half-space of a body's plane (given in its body frame).
inline HalfSpace worldHalfSpace(const PlaneShape& plane, const Transform& bodyPose) {
  const Vec3 normal = bodyPose.rotate(plane.normal);
  return {normal, plane.offset + normal.dot(bodyPose.translation)};
}

// Lowest value of normal · p over the box: how deep it reaches into a half-space.
inline double lowestAlong(const Aabb& box, const Vec3& normal) {
  double lowest = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    lowest += normal[axis] * (normal[axis] >= 0.0 ? box.min[axis] : box.max[axis]);
  return lowest;
}

// One body as the broad phase sees it: what update(bodies) extracts from each
// body with collision geometry, or what a test or benchmark gives directly.
struct BroadPhaseBody {
  int32_t serial = 0;  // identity: strictly ascending along the input, never reused
  int index = 0;       // what BodyPair reports (the body's dense index)
  bool isStatic = false;
  std::optional<Aabb> box;         // world box of the convex pieces; none: no pieces
  std::optional<HalfSpace> plane;  // the body's half-space, if it is a plane
  CollisionFilter filter;          // its collision group and mask
};

// What the broad phase needs of a body's geometry, fixed when the body is
// created. Callers that update every step may keep it per body: reaching it
// through the body's description and collider costs two cache misses a body.
struct BroadPhaseShape {
  bool isStatic = false;
  std::optional<Aabb> bounds;       // body frame, of the convex pieces; none without pieces
  std::optional<PlaneShape> plane;  // body frame
  CollisionFilter filter;           // the body's collision group and mask

  static BroadPhaseShape of(const Body& body);  // no geometry when the collider is null
  bool hasGeometry() const { return bounds || plane; }
  // The body at `pose` (body -> world), reported by BodyPair as `index`.
  BroadPhaseBody placed(int32_t serial, int index, const Transform& pose) const;
};

class BroadPhase {
 public:
  // fatMargin (m): how far a body may move before its proxy moves in the
  // tree. contactMargin (m): bodies whose boxes come this close pair up
  // (the narrow phase's contact margin, so that no near contact is missed).
  explicit BroadPhase(double fatMargin = 0.05, double contactMargin = 0.0);

  // Brings the proxies in line with the bodies (added, removed, moved since
  // the last update) and recomputes the candidate pairs; `bodies` in
  // ascending serial order, as a World keeps them. Bodies without a
  // collider (a null description().collider) and frozen ones take no part.
  // `excludedPairs`: keys (serialPairKey) of pairs never to report, sorted
  // ascending; keys of bodies not given are ignored.
  void update(std::span<const Body> bodies, std::span<const uint64_t> excludedPairs = {});
  // The same from explicit inputs, in ascending serial order. A serial seen
  // before must keep its isStatic; a new serial must exceed every serial
  // seen before (as World's do), otherwise everything is rebuilt.
  void update(std::span<const BroadPhaseBody> bodies, std::span<const uint64_t> excludedPairs = {});

  // Candidate pairs, sorted by (serial(a), serial(b)): deterministic
  // whatever the tree's shape. Filtered: no pair the bodies' groups and
  // masks, or the excluded pairs, rule out.
  const std::vector<BodyPair>& pairs() const { return m_pairs; }
  const DynamicAabbTree& tree() const { return m_tree; }
  double contactMargin() const { return m_contactMargin; }
  // Proxies created or re-inserted by the last update (a cost measure).
  int movedProxyCount() const { return m_movedCount; }

 private:
  // Per body with geometry, in ascending serial order; the tree's user data
  // is the index in m_entries. One cache line: the pair loops touch
  // entries in no particular order.
  struct alignas(64) Entry {
    Aabb box;  // the tight box grown by half the contact margin
    int32_t serial = 0;
    int index = 0;
    int proxy = DynamicAabbTree::kNull;
    bool isStatic = false;
    bool moved = false;  // its candidate pairs must be found again
  };
  struct PlaneEntry {
    int entry = 0;
    HalfSpace halfSpace;
  };
  // A pair of entries whose fat boxes overlap, keyed by (serial, serial).
  struct Candidate {
    uint64_t key = 0;
    int entryA = 0;
    int entryB = 0;
  };

  void clear();
  bool canFollow(std::span<const BroadPhaseBody> bodies) const;
  bool syncEntries(std::span<const BroadPhaseBody> bodies);
  void syncEntry(int entryIndex, const BroadPhaseBody& body);
  void updateCandidates(bool entriesMoved);
  void collectPairs(std::span<const uint64_t> excludedPairs);
  // Whether the filters let the two entries' bodies collide (`key` their pair's).
  bool filtersAllow(const Candidate& candidate, std::span<const uint64_t> excludedPairs,
                    std::size_t& excludedCursor) const;
  Candidate makeCandidate(int entryA, int entryB) const;

  double m_fatMargin;
  double m_contactMargin;
  DynamicAabbTree m_tree;
  std::vector<Entry> m_entries;
  // Parallel to m_entries (kept out of Entry, which fills its cache line).
  std::vector<CollisionFilter> m_filters;
  std::vector<PlaneEntry> m_planes;     // the entries with a plane, in entry order
  std::vector<int> m_remap;             // old entry index -> new one (-1: removed), during update
  std::vector<Candidate> m_candidates;  // sorted by key
  // Scratch, kept to reuse their memory.
  std::vector<Candidate> m_found;
  std::vector<Candidate> m_merged;
  std::vector<Candidate> m_touching;
  std::vector<BroadPhaseBody> m_inputs;  // scratch for update(bodies)
  std::vector<BodyPair> m_pairs;
  int m_movedCount = 0;
};

}  // namespace rbsim
