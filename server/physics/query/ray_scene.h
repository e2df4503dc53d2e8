#pragma once
// The bodies as ray casts see them: one proxy per body with convex pieces
// (or a trimesh's triangles, walked through the mesh's own BVH)
// in a dynamic AABB tree (the broad phase's kind, collision/
// dynamic_aabb_tree.h), each piece placed in the world, and the planes
// aside (infinite, they are tested on every ray). The tree is kept as the
// broad phase keeps its own (a proxy moves only when its body leaves its
// fat box), built anew top down when the bodies change or many of them
// left their fat boxes, and copied after each change into a layout made
// for rays (query/ray_tree.h). The three queries
// walk that copy with the slab test, nearest boxes first, and test the
// pieces of the bodies whose boxes the ray crosses.
//
// Why a tree of its own and not the collision detector's: the detector
// updates its tree at the start of a step, before the bodies move, and not
// at all when a body is added, removed or placed between steps; a query
// between steps must see the bodies where they are. This scene follows
// them lazily: the world bumps a revision at every step and at every change
// of a body's pose or of its bodies, and the first query after a change
// brings the scene up to date (proxies move in the tree only when a body
// leaves its fat box, so a resting scene costs one pass over the bodies).
//
// Answers are a pure function of the bodies' poses, shapes and filters,
// never of the tree's shape: the closest hit is the least (fraction, body
// serial, piece), whatever order the walk meets them in, and all hits are
// sorted the same way.
//
// Thread safety: the queries are const and keep their scratch on the
// caller's stack, so any number of threads may cast rays at once between
// steps; the refresh they may start is done once, under a lock.

#include <atomic>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "physics/body/body.h"
#include "physics/collision/broad_phase.h"
#include "physics/collision/collider.h"
#include "physics/collision/dynamic_aabb_tree.h"
#include "physics/query/ray_segment.h"
#include "physics/query/ray_tree.h"
#include "rbsim/physics/collision_filter.h"

namespace rbsim {

// One ray and what it may hit, by dense body index.
struct SceneRay {
  RaySegment segment;
  CollisionFilter filter;
  int excludedIndex = -1;  // dense index of a body never hit; -1: none
};

// A hit as the scene finds it; the world turns it into a RayHit.
struct SceneHit {
  int bodyIndex = -1;  // dense
  int32_t serial = 0;
  int piece = 0;
  int part = 0;
  double fraction = 0.0;
  Vec3 normal = Vec3::Zero();  // world, unit
};

// A shape cast as the scene takes it (World::castShape).
struct SceneSweep {
  ConvexGeometry shape;  // what is swept
  Transform start;       // shape frame -> world at fraction 0
  Vec3 delta = Vec3::Zero();  // m, world: how far the shape moves over the sweep
  CollisionFilter filter;
  int excludedIndex = -1;  // dense index of a body never hit; -1: none
};

// A body a shape cast touches: where along the sweep, which piece, the
// normal (in `hit`), and the point of the body touched.
struct SceneSweepHit {
  SceneHit hit;
  Vec3 point = Vec3::Zero();  // m, world
};

class RayScene {
 public:
  RayScene() = default;
  // A copy (a copied world) starts empty and fills itself at its first
  // query: the tree and the pieces point into the bodies of the original.
  RayScene(const RayScene&) {}
  RayScene& operator=(const RayScene&) {
    m_builtRevision.store(kNever, std::memory_order_relaxed);
    return *this;
  }

  // Brings the scene in line with `bodies` (dense, in serial order) unless
  // it was built for `revision` already. Const: the scene is a cache of
  // the bodies; concurrent callers refresh it once.
  void refresh(std::span<const Body> bodies, uint64_t revision) const;

  // The least (fraction, serial, piece) hit in [0, 1], if any.
  std::optional<SceneHit> closest(const SceneRay& ray) const;
  // Whether anything is hit in [0, 1]: stops at the first hit found.
  bool any(const SceneRay& ray) const;
  // Every body hit, each once (its nearest piece), by (fraction, serial).
  void all(const SceneRay& ray, std::vector<SceneHit>& hits) const;
  // Shape casts, through the same tree (its boxes grown by the swept
  // shape's): the least (fraction, serial, piece) touch in [0, 1], if any,
  // and every body touched, each once (its nearest piece), by (fraction,
  // serial).
  std::optional<SceneSweepHit> sweepClosest(const SceneSweep& sweep) const;
  void sweepAll(const SceneSweep& sweep, std::vector<SceneSweepHit>& hits) const;

  // The batch call borrows the world's task pool, which runs one loop at a
  // time and is made on first use: while another thread's batch holds it,
  // a batch runs on its caller alone (with the same answers).
  std::unique_lock<std::mutex> tryBorrowPool() const {
    return std::unique_lock<std::mutex>(m_poolLock, std::try_to_lock);
  }


 private:
  static constexpr uint64_t kNever = std::numeric_limits<uint64_t>::max();

  struct Entry {  // a body with convex pieces
    int32_t serial = 0;
    int bodyIndex = 0;
    int proxy = DynamicAabbTree::kNull;
    int firstPiece = 0;  // its pieces: m_pieces[firstPiece, firstPiece + pieceCount)
    int pieceCount = 0;
    // A trimesh's triangles instead of pieces (hits name the triangle as
    // their piece), and the body's pose.
    const TriangleMeshCollider* triangles = nullptr;
    Transform pose;
    CollisionFilter filter;
  };
  struct Piece {
    Transform pose;  // geometry frame -> world
    const ConvexGeometry* geometry = nullptr;
    int part = 0;
  };
  struct Plane {
    HalfSpace halfSpace;  // world
    int32_t serial = 0;
    int bodyIndex = 0;
    CollisionFilter filter;
  };

  void rebuild(std::span<const Body> bodies) const;
  bool sameBodies(std::span<const Body> bodies) const;
  // The entry's nearest piece hit in [0, maxFraction], if any.
  std::optional<SceneHit> hitBody(const Entry& entry, const RaySegment& segment, double maxFraction) const;
  std::optional<SceneHit> hitPlane(const Plane& plane, const RaySegment& segment) const;
  // The entry's nearest piece a sweep touches in [0, maxFraction], if any.
  std::optional<SceneSweepHit> sweepBody(const Entry& entry, const SceneSweep& sweep, double maxFraction) const;
  std::optional<SceneSweepHit> sweepPlane(const Plane& plane, const SceneSweep& sweep) const;
  std::optional<SceneSweepHit> sweepTriangles(const Entry& entry, const SceneSweep& sweep, double maxFraction) const;
  // Calls visit(entry) for each entry whose box the sweep's box meets
  // within [0, maxFraction], as RayTree::cast does.
  template <class Visit>
  void walkSweep(const SceneSweep& sweep, double maxFraction, Visit&& visit) const;
  template <class Query>
  static bool mayHit(const Query& query, int bodyIndex, const CollisionFilter& filter) {
    return bodyIndex != query.excludedIndex && query.filter.allows(filter);
  }

  mutable std::mutex m_refreshLock;
  mutable std::mutex m_poolLock;
  mutable std::atomic<uint64_t> m_builtRevision{kNever};
  mutable DynamicAabbTree m_tree{kFatMargin};
  mutable RayTree m_rayTree;  // m_tree laid out for the walk, after every refresh that changed it
  mutable std::vector<Entry> m_entries;  // in serial order; the tree's user data indexes it
  mutable std::vector<Piece> m_pieces;
  mutable std::vector<Plane> m_planes;
  mutable std::vector<Aabb> m_boxes;  // scratch of a refresh: each entry's box

 public:
  // m: how far a body may move before its proxy moves in the tree. Small:
  // a fat box only costs rays false candidates, and the scene is refreshed
  // at most once a step.
  static constexpr double kFatMargin = 0.01;
  // When more than 1/kRebuildShare of the bodies left their fat boxes
  // since the last refresh, the tree is rebuilt rather than followed.
  static constexpr std::size_t kRebuildShare = 8;
};

// Whether `a` is a nearer hit than `b`: by fraction, then body serial, then
// piece, so that ties do not depend on the order hits are found in.
inline bool isNearer(const SceneHit& a, const SceneHit& b) {
  if (a.fraction != b.fraction) return a.fraction < b.fraction;
  if (a.serial != b.serial) return a.serial < b.serial;
  return a.piece < b.piece;
}

}  // namespace rbsim
