#pragma once
// The whole collision pipeline for one world state: broad phase, then the
// narrow phase on every candidate pair's convex pieces, giving manifolds.
// Piece pairs are skipped when their boxes (grown by half the contact margin
// each) do not overlap; manifolds without points are dropped.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "physics/body/body.h"
#include "physics/collision/body_contact.h"
#include "physics/collision/broad_phase.h"
#include "physics/collision/contact_generation.h"
#include "physics/collision/triangle_mesh_contacts.h"
#include "physics/parallel/task_pool.h"

namespace rbsim {

// What the detector needs to know of the step its contacts are for.
struct DetectionStep {
  double dt = 0.0;  // s
  // Speculative contacts (the impulse model): a fast body's pairs reach as
  // far as it may move within dt, so its impact is seen in the step it
  // happens. Off, only the contact margin counts.
  bool speculative = false;
  // Bounds on every awake body's speeds, when the caller knows them (the
  // world does, from the step before): squared |v| (m²/s²) and squared |ω|
  // (1/s², a bound). When even the largest radius turns at the largest spin
  // and moves at the largest speed below what needs a reach, no body's reach
  // is computed. Negative: unknown, each body is checked.
  double maxSquaredSpeed = -1.0;
  double maxSquaredSpin = -1.0;
  // Pairs the broad phase leaves out (BroadPhase::update: serialPairKey
  // keys, ascending): their narrow phase is never run. The world's joined
  // and excluded pairs; groups and masks come with the bodies.
  std::span<const uint64_t> excludedPairs;
};

class CollisionDetector {
 public:
  // fatMargin (m): the broad phase's fat-box margin. The broad phase pairs
  // bodies within settings.margin of each other.
  explicit CollisionDetector(const ContactSettings& settings = {}, double fatMargin = 0.05);

  // Finds every contact of the bodies' current state; `bodies` in ascending
  // serial order, as a World keeps them (world/contact_detection.h passes
  // a world's). Deterministic: the contacts come sorted by (serial A,
  // serial B, piece A, piece B), bodies by their index in `bodies`. The
  // pairs' narrow phase is shared among the pool's threads; the contacts
  // are the same for every thread count.
  void detect(std::span<const Body> bodies, const DetectionStep& step, TaskPool& pool);

  const std::vector<BodyContact>& contacts() const { return m_contacts; }
  int contactPointCount() const;
  const BroadPhase& broadPhase() const { return m_broadPhase; }
  // Hull piece pairs of the last detect() that keep a separating direction
  // for the next (SeparationCache), and how many pairs the kept direction
  // alone proved apart in it (a measure of temporal coherence).
  std::size_t keptSeparationCount() const { return m_separations.size(); }

 private:
  struct PlacedPiece {
    PlacedConvex convex;
    Aabb box;  // world, grown by half the contact margin
  };

  struct BodyGeometry {
    std::shared_ptr<const BodyDescription> description;  // whose collider this is
    const Collider* collider = nullptr;                  // null: no collision geometry
    BroadPhaseShape shape;
    Transform pose;  // body -> world
    int32_t serial = 0;
    double radius = 0.0;  // m: the collider's farthest point from the body origin (bounded)
    // m: how far a point of the body may move in the coming step, at most
    // (dt (|v| + |ω| radius); 0 for bodies slower than half the margin per
    // step). Impulse
    // model only: pairs within the margin plus both reaches are contacts
    // (speculative ones while apart), so that a fast body's impact is seen in
    // the step it happens, not after it has sunk in.
    double reach = 0.0;
    // Same collider at bit for bit the same pose (and reach) as in the previous detect():
    // a pair of such bodies has the same manifolds as then (the narrow phase
    // is a pure function of the two placed colliders), so they are reused.
    // Resting and sleeping bodies stop costing narrow-phase time.
    bool unchanged = false;
  };

  // A hull pair's SeparationCache, kept from one detect() to the next.
  struct KeptSeparation {
    uint64_t key = 0;  // (serial A, serial B)
    int pieceA = 0;
    int pieceB = 0;
    SeparationCache cache;
  };

  // The narrow phase of a run of consecutive candidate pairs, done by one
  // thread into its own lists; the runs' lists are joined in pair order.
  // Each on its own cache lines: a run's thread writes its lists' ends and
  // cursors at every pair, and neighbouring runs go to different threads.
  struct alignas(64) PairRun {
    std::vector<BodyContact> contacts;
    std::vector<uint64_t> contactKeys;  // (serial A, serial B) of each contact
    std::vector<KeptSeparation> separations;  // in (key, piece A, piece B) order
    std::vector<PlacedPiece> placedB;   // scratch
    std::vector<TriangleManifold> triangleManifolds;  // scratch
    // Merge walks over the previous detect()'s lists: pairs come in key order.
    std::size_t previousContactCursor = 0;
    std::size_t previousPairCursor = 0;
    std::size_t previousSeparationCursor = 0;
  };

  void collideRun(PairRun& run, std::size_t firstPair, std::size_t endPair) const;
  void collidePair(PairRun& run, uint64_t key, int indexA, int indexB) const;
  void collidePair(PairRun& run, uint64_t key, int indexA, int indexB,
                   const ContactSettings& settings) const;
  // A pair with a trimesh: each convex piece of the other body against the
  // triangles near it, one manifold per (triangle, piece).
  void collideTriangleMeshPair(PairRun& run, int indexA, int indexB,
                               const ContactSettings& settings) const;
  // The previous detect()'s cache of the pieces' pair (zero if none); moves
  // the run's cursor, so pieces must be asked for in (key, A, B) order.
  SeparationCache previousSeparation(PairRun& run, uint64_t key, int pieceA, int pieceB) const;
  // Copies the previous detect()'s manifolds of the pair (serial order key);
  // false when the pair was not a candidate then.
  bool reusePair(PairRun& run, uint64_t key, int indexA, int indexB) const;

  ContactSettings m_settings;
  BroadPhase m_broadPhase;
  std::vector<BodyContact> m_contacts;
  std::vector<uint64_t> m_contactKeys;    // (serial A, serial B) of each of m_contacts
  std::vector<uint64_t> m_pairKeys;       // the candidate pairs of this detect()
  std::vector<BodyContact> m_previousContacts;
  std::vector<uint64_t> m_previousContactKeys;
  std::vector<uint64_t> m_previousPairKeys;
  std::vector<KeptSeparation> m_separations;  // of this detect(), in (key, A, B) order
  std::vector<KeptSeparation> m_previousSeparations;
  std::vector<PairRun> m_runs;
  std::vector<BroadPhaseBody> m_broadPhaseInputs;
  std::vector<BodyGeometry> m_geometry;  // by dense body index, for the current detect()
  double m_maxRadius = 0.0;  // m: of every collider seen (never shrinks: a bound)
};

}  // namespace rbsim
