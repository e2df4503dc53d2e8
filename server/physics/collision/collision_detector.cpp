#include "physics/collision/collision_detector.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

#include "physics/collision/contact_routines.h"

namespace rbsim {

namespace {

constexpr std::size_t at(int index) {
  return static_cast<std::size_t>(index);
}

Transform poseOf(const Body& body) {
  return {body.rotation(), body.position()};
}

// Bitwise equality (NaN never equals, so a broken pose is never reused).
bool samePose(const Transform& x, const Transform& y) {
  return x.rotation == y.rotation && x.translation == y.translation;
}

constexpr double kSlowReach = 0.5;  // of the contact margin per step

uint64_t pairKey(int32_t serialA, int32_t serialB) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(serialA)) << 32) |
         static_cast<uint32_t>(serialB);
}

}  // namespace

CollisionDetector::CollisionDetector(const ContactSettings& settings, double fatMargin)
    : m_settings(settings), m_broadPhase(fatMargin, settings.margin) {}

void CollisionDetector::detect(std::span<const Body> bodies, const DetectionStep& step, TaskPool& pool) {
  // One pass in body order gathers what the broad phase and the pairs need
  // into a compact array. Each body's collider is looked up only when the
  // body at that index changes: its description (which the entry keeps
  // alive, so the address cannot be reused) is immutable.
  const bool speculative = step.speculative;
  const double dt = step.dt;
  const double slow = kSlowReach * m_settings.margin / dt;  // m/s
  const bool speedsKnown = step.maxSquaredSpeed >= 0.0 && step.maxSquaredSpin >= 0.0;
  const bool anyFast =
      !speedsKnown ||
      2.0 * (step.maxSquaredSpeed + step.maxSquaredSpin * m_maxRadius * m_maxRadius) >= slow * slow;
  m_geometry.resize(bodies.size());
  m_broadPhaseInputs.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    BodyGeometry& geometry = m_geometry[i];
    const Transform pose = poseOf(body);
    const bool sameBody =
        geometry.description.get() == &body.description() && geometry.serial == body.serial();
    const bool newGeometry = geometry.description.get() != &body.description();
    if (newGeometry) {
      geometry.description = body.sharedDescription();
      geometry.collider = geometry.description->collider.get();
      geometry.shape = BroadPhaseShape::of(body);
      geometry.radius = geometry.collider ? colliderRadius(*geometry.collider) : 0.0;
      m_maxRadius = std::max(m_maxRadius, geometry.radius);
    }
    double reach = 0.0;
    if (speculative && (anyFast || newGeometry) && !geometry.shape.isStatic && !body.isSleeping()) {
      // A body that moves less than half the margin in a step needs none: two
      // of them close by less than the margin per step, so the margin sees
      // their contact coming before they touch. Leaving it at zero keeps
      // resting bodies' geometry, and their manifolds' reuse, unchanged. The
      // test is on squares (|v| + |ω| r <= sqrt(2 (|v|² + |ω|² r²))), so most
      // bodies pay no square root.
      const double speed2 = body.linearVelocity().squaredNorm();
      const double spin2 = body.angularVelocity().squaredNorm() * geometry.radius * geometry.radius;
      if (2.0 * (speed2 + spin2) >= slow * slow)
        reach = dt * (std::sqrt(speed2) + std::sqrt(spin2));
    }
    geometry.unchanged = sameBody && samePose(geometry.pose, pose) && geometry.reach == reach;
    geometry.serial = body.serial();
    geometry.pose = pose;
    geometry.reach = reach;
    // A frozen body is out of the simulation: nothing collides with it.
    if (geometry.shape.hasGeometry() && !body.isFrozen()) {
      m_broadPhaseInputs.push_back(
          geometry.shape.placed(body.serial(), static_cast<int>(i), geometry.pose));
      std::optional<Aabb>& box = m_broadPhaseInputs.back().box;
      if (reach > 0.0 && box) box = box->fattened(reach);
    }
  }
  m_broadPhase.update(m_broadPhaseInputs, step.excludedPairs);
  m_previousContacts.swap(m_contacts);
  m_previousContactKeys.swap(m_contactKeys);
  m_previousPairKeys.swap(m_pairKeys);
  m_previousSeparations.swap(m_separations);
  const std::vector<BodyPair>& pairs = m_broadPhase.pairs();
  m_pairKeys.resize(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k)
    m_pairKeys[k] = pairKey(m_geometry[at(pairs[k].a)].serial, m_geometry[at(pairs[k].b)].serial);
  // Runs of a fixed number of pairs, whatever the thread count, joined in
  // order: the same contacts, in the same order, as one loop over the pairs.
  constexpr std::size_t kPairsPerRun = 64;
  m_runs.resize(std::max(m_runs.size(), chunkCount(pairs.size(), kPairsPerRun)));
  forEachChunk(pool, pairs.size(), kPairsPerRun, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    collideRun(m_runs[chunk], begin, end);
  });
  m_contacts.clear();
  m_contactKeys.clear();
  m_separations.clear();
  for (std::size_t chunk = 0; chunk < chunkCount(pairs.size(), kPairsPerRun); ++chunk) {
    const PairRun& run = m_runs[chunk];
    m_contacts.insert(m_contacts.end(), run.contacts.begin(), run.contacts.end());
    m_contactKeys.insert(m_contactKeys.end(), run.contactKeys.begin(), run.contactKeys.end());
    m_separations.insert(m_separations.end(), run.separations.begin(), run.separations.end());
  }
}

void CollisionDetector::collideRun(PairRun& run, std::size_t firstPair, std::size_t endPair) const {
  run.contacts.clear();
  run.contactKeys.clear();
  run.separations.clear();
  // Where this run's pairs start in the previous lists (all sorted by key).
  const uint64_t firstKey = m_pairKeys[firstPair];
  run.previousPairCursor = static_cast<std::size_t>(
      std::lower_bound(m_previousPairKeys.begin(), m_previousPairKeys.end(), firstKey) -
      m_previousPairKeys.begin());
  run.previousContactCursor = static_cast<std::size_t>(
      std::lower_bound(m_previousContactKeys.begin(), m_previousContactKeys.end(), firstKey) -
      m_previousContactKeys.begin());
  run.previousSeparationCursor = static_cast<std::size_t>(
      std::lower_bound(m_previousSeparations.begin(), m_previousSeparations.end(), firstKey,
                       [](const KeptSeparation& kept, uint64_t key) { return kept.key < key; }) -
      m_previousSeparations.begin());
  const std::vector<BodyPair>& pairs = m_broadPhase.pairs();
  for (std::size_t k = firstPair; k < endPair; ++k) {
    const BodyPair& pair = pairs[k];
    const BodyGeometry& a = m_geometry[at(pair.a)];
    const BodyGeometry& b = m_geometry[at(pair.b)];
    const uint64_t key = m_pairKeys[k];
    if (!(a.unchanged && b.unchanged && reusePair(run, key, pair.a, pair.b)))
      collidePair(run, key, pair.a, pair.b);
    run.contactKeys.resize(run.contacts.size(), key);
  }
}

bool CollisionDetector::reusePair(PairRun& run, uint64_t key, int indexA, int indexB) const {
  std::size_t& pairCursor = run.previousPairCursor;
  std::size_t& contactCursor = run.previousContactCursor;
  while (pairCursor < m_previousPairKeys.size() && m_previousPairKeys[pairCursor] < key) ++pairCursor;
  if (pairCursor == m_previousPairKeys.size() || m_previousPairKeys[pairCursor] != key) return false;
  while (contactCursor < m_previousContactKeys.size() && m_previousContactKeys[contactCursor] < key)
    ++contactCursor;
  for (; contactCursor < m_previousContactKeys.size() && m_previousContactKeys[contactCursor] == key;
       ++contactCursor) {
    BodyContact contact = m_previousContacts[contactCursor];
    contact.bodyA = indexA;  // dense indices may have moved since
    contact.bodyB = indexB;
    run.contacts.push_back(contact);
  }
  // The pair's separation caches carry over with its manifolds.
  std::size_t& separationCursor = run.previousSeparationCursor;
  while (separationCursor < m_previousSeparations.size() &&
         m_previousSeparations[separationCursor].key < key)
    ++separationCursor;
  for (; separationCursor < m_previousSeparations.size() &&
         m_previousSeparations[separationCursor].key == key;
       ++separationCursor)
    run.separations.push_back(m_previousSeparations[separationCursor]);
  return true;
}

SeparationCache CollisionDetector::previousSeparation(PairRun& run, uint64_t key, int pieceA,
                                                      int pieceB) const {
  const auto before = [](const KeptSeparation& kept, uint64_t k, int a, int b) {
    if (kept.key != k) return kept.key < k;
    if (kept.pieceA != a) return kept.pieceA < a;
    return kept.pieceB < b;
  };
  std::size_t& cursor = run.previousSeparationCursor;
  while (cursor < m_previousSeparations.size() &&
         before(m_previousSeparations[cursor], key, pieceA, pieceB))
    ++cursor;
  if (cursor < m_previousSeparations.size()) {
    const KeptSeparation& kept = m_previousSeparations[cursor];
    if (kept.key == key && kept.pieceA == pieceA && kept.pieceB == pieceB) return kept.cache;
  }
  return {};
}

void CollisionDetector::collidePair(PairRun& run, uint64_t key, int indexA, int indexB) const {
  const double reach = m_geometry[at(indexA)].reach + m_geometry[at(indexB)].reach;
  if (reach == 0.0) return collidePair(run, key, indexA, indexB, m_settings);
  ContactSettings settings = m_settings;
  settings.margin += reach;
  collidePair(run, key, indexA, indexB, settings);
}

namespace {
bool isHull(const ConvexGeometry& geometry) {
  return std::holds_alternative<std::shared_ptr<const ConvexHull>>(geometry);
}
}  // namespace

void CollisionDetector::collidePair(PairRun& run, uint64_t key, int indexA, int indexB,
                                    const ContactSettings& settings) const {
  const BodyGeometry& a = m_geometry[at(indexA)];
  const BodyGeometry& b = m_geometry[at(indexB)];
  // The broad phase only pairs bodies that have colliders.
  const Collider& colliderA = *a.collider;
  const Collider& colliderB = *b.collider;
  if (colliderA.triangles || colliderB.triangles)
    return collideTriangleMeshPair(run, indexA, indexB, settings);
  const Transform& poseA = a.pose;
  const Transform& poseB = b.pose;
  const double halfMargin = 0.5 * settings.margin;
  // With at most one piece a side, the broad phase has compared these very
  // boxes already (a collider's bounds are its piece's).
  const bool checkBoxes = colliderA.pieces.size() > 1 || colliderB.pieces.size() > 1;
  const auto grownBox = [&](const ConvexPiece& piece, const Transform& pose) {
    return checkBoxes ? transformedAabb(piece.bounds, pose).fattened(halfMargin)
                      : Aabb::everything();
  };
  const auto reaches = [&](const Aabb& box, const HalfSpace& plane) {
    return !checkBoxes || lowestAlong(box, plane.normal) <= plane.offset + halfMargin;
  };

  // Pieces of B placed in the world, with their boxes grown by half the margin.
  run.placedB.clear();
  for (const ConvexPiece& piece : colliderB.pieces)
    run.placedB.push_back(
        {PlacedConvex{&piece.geometry, poseB * piece.placement}, grownBox(piece, poseB)});

  BodyContact contact;
  contact.bodyA = indexA;
  contact.bodyB = indexB;
  if (colliderA.plane) {
    const HalfSpace plane = worldHalfSpace(*colliderA.plane, poseA);
    for (std::size_t j = 0; j < run.placedB.size(); ++j) {
      if (!reaches(run.placedB[j].box, plane)) continue;
      contact.pieceA = 0;
      contact.pieceB = static_cast<int>(j);
      contact.manifold = {};
      collidePlaneConvex(plane.normal, plane.offset, run.placedB[j].convex, settings,
                         contact.manifold);
      if (contact.manifold.pointCount > 0) run.contacts.push_back(contact);
    }
  }
  for (std::size_t i = 0; i < colliderA.pieces.size(); ++i) {
    const ConvexPiece& piece = colliderA.pieces[i];
    const PlacedConvex placedA{&piece.geometry, poseA * piece.placement};
    const Aabb boxA = grownBox(piece, poseA);
    contact.pieceA = static_cast<int>(i);
    if (colliderB.plane) {
      const HalfSpace plane = worldHalfSpace(*colliderB.plane, poseB);
      if (reaches(boxA, plane)) {
        contact.pieceB = 0;
        contact.manifold = {};
        // The narrow phase puts the plane first; A is the convex here.
        collidePlaneConvex(plane.normal, plane.offset, placedA, settings, contact.manifold);
        flipManifold(contact.manifold);
        if (contact.manifold.pointCount > 0) run.contacts.push_back(contact);
      }
    }
    for (std::size_t j = 0; j < run.placedB.size(); ++j) {
      if (!boxA.overlaps(run.placedB[j].box)) continue;
      contact.pieceB = static_cast<int>(j);
      contact.manifold = {};
      const PlacedConvex& placedB = run.placedB[j].convex;
      if (isHull(*placedA.geometry) || isHull(*placedB.geometry)) {
        // Hull pairs keep what they learnt about their separation.
        KeptSeparation kept{key, contact.pieceA, contact.pieceB,
                            previousSeparation(run, key, contact.pieceA, contact.pieceB)};
        collideConvex(placedA, placedB, settings, contact.manifold, &kept.cache);
        if (kept.cache.axis != Vec3::Zero()) run.separations.push_back(kept);
      } else {
        collideConvex(placedA, placedB, settings, contact.manifold);
      }
      if (contact.manifold.pointCount > 0) run.contacts.push_back(contact);
    }
  }
}

void CollisionDetector::collideTriangleMeshPair(PairRun& run, int indexA, int indexB,
                                                const ContactSettings& settings) const {
  const BodyGeometry& a = m_geometry[at(indexA)];
  const BodyGeometry& b = m_geometry[at(indexB)];
  const bool meshIsA = a.collider->triangles != nullptr;
  const BodyGeometry& mesh = meshIsA ? a : b;
  const BodyGeometry& other = meshIsA ? b : a;
  // Two trimeshes (both static) or a trimesh and a plane have no contacts.
  if (other.collider->triangles || other.collider->plane) return;
  BodyContact contact;
  contact.bodyA = indexA;
  contact.bodyB = indexB;
  std::vector<TriangleManifold>& manifolds = run.triangleManifolds;
  const std::size_t firstContact = run.contacts.size();
  for (std::size_t j = 0; j < other.collider->pieces.size(); ++j) {
    const ConvexPiece& piece = other.collider->pieces[j];
    manifolds.clear();
    collideTriangleMeshPiece(*mesh.collider->triangles, mesh.pose,
                             PlacedConvex{&piece.geometry, other.pose * piece.placement}, settings,
                             manifolds);
    for (TriangleManifold& found : manifolds) {
      if (meshIsA) {
        contact.pieceA = found.triangle;
        contact.pieceB = static_cast<int>(j);
      } else {
        flipManifold(found.manifold);  // the narrow phase puts the mesh first
        contact.pieceA = static_cast<int>(j);
        contact.pieceB = found.triangle;
      }
      contact.manifold = found.manifold;
      run.contacts.push_back(contact);
    }
  }
  // Contacts go in (piece A, piece B) order; with the mesh as A, the loop
  // above went piece by piece of B.
  if (meshIsA)
    std::stable_sort(run.contacts.begin() + static_cast<std::ptrdiff_t>(firstContact),
                     run.contacts.end(), [](const BodyContact& x, const BodyContact& y) {
                       return x.pieceA != y.pieceA ? x.pieceA < y.pieceA : x.pieceB < y.pieceB;
                     });
}

int CollisionDetector::contactPointCount() const {
  int count = 0;
  for (const BodyContact& contact : m_contacts) count += contact.manifold.pointCount;
  return count;
}

}  // namespace rbsim
