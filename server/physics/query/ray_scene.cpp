#include "physics/query/ray_scene.h"

#include <algorithm>
#include <cstddef>
#include <memory>

#include "physics/query/convex_sweep.h"
#include "physics/query/ray_shapes.h"
#include "physics/query/ray_triangle_mesh.h"

namespace rbsim {

namespace {

constexpr std::size_t at(int index) {
  return static_cast<std::size_t>(index);
}

// What the scene takes of a body: colliding, and not frozen (a frozen body
// is out of the simulation, as the broad phase has it).
const Collider* castableCollider(const Body& body) {
  if (body.isFrozen()) return nullptr;
  return body.description().collider.get();
}

// The normal of a hit: the span's, turned into the world, or opposite the
// ray for a ray that starts inside.
Vec3 worldNormal(const RayEntry& entry, const Mat3& rotation, const Vec3& delta) {
  if (entry.inside) return -delta.normalized();
  return rotation * entry.normal;
}

}  // namespace

void RayScene::refresh(std::span<const Body> bodies, uint64_t revision) const {
  if (m_builtRevision.load(std::memory_order_acquire) == revision) return;
  const std::lock_guard lock(m_refreshLock);
  if (m_builtRevision.load(std::memory_order_relaxed) == revision) return;
  rebuild(bodies);
  m_builtRevision.store(revision, std::memory_order_release);
}

// Whether the bodies with pieces are the entries' bodies, in the same order:
// then the tree is kept and its proxies follow the bodies.
bool RayScene::sameBodies(std::span<const Body> bodies) const {
  std::size_t next = 0;
  for (const Body& body : bodies) {
    const Collider* collider = castableCollider(body);
    if (!collider || (collider->pieces.empty() && !collider->triangles)) continue;
    if (next == m_entries.size() || m_entries[next].serial != body.serial()) return false;
    ++next;
  }
  return next == m_entries.size();
}

void RayScene::rebuild(std::span<const Body> bodies) const {
  // The entries, pieces and planes of the bodies as they are now, and each
  // entry's box.
  const bool sameEntries = sameBodies(bodies);
  if (!sameEntries) m_entries.clear();
  m_pieces.clear();
  m_planes.clear();
  m_boxes.clear();
  std::size_t next = 0;
  std::size_t leaving = 0;  // entries whose body left its fat box
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    const Collider* collider = castableCollider(body);
    if (!collider) continue;
    const Transform pose{body.rotation(), body.position()};
    if (collider->plane)
      m_planes.push_back({worldHalfSpace(*collider->plane, pose), body.serial(), static_cast<int>(i),
                          body.description().collisionFilter});
    if (collider->pieces.empty() && !collider->triangles) continue;
    if (!sameEntries) m_entries.emplace_back();
    Entry& entry = m_entries[next++];
    entry.serial = body.serial();
    entry.bodyIndex = static_cast<int>(i);
    entry.filter = body.description().collisionFilter;
    entry.firstPiece = static_cast<int>(m_pieces.size());
    entry.pieceCount = static_cast<int>(collider->pieces.size());
    entry.triangles = collider->triangles.get();
    entry.pose = pose;
    for (std::size_t p = 0; p < collider->pieces.size(); ++p) {
      const ConvexPiece& piece = collider->pieces[p];
      m_pieces.push_back({pose * piece.placement, &piece.geometry, partOfPiece(*collider, p)});
    }
    const Aabb& box = m_boxes.emplace_back(transformedAabb(collider->bounds, pose));
    if (sameEntries && !m_tree.fatAabb(entry.proxy).contains(box)) ++leaving;
  }

  // The tree: built anew, top down, when the bodies changed or many of them
  // left their fat boxes (one insertion per moved proxy would cost more
  // than the whole build, and leave a worse tree); else its proxies follow
  // their bodies one by one, and a pile at rest moves none.
  bool changed = true;
  if (!sameEntries || leaving > m_entries.size() / kRebuildShare) {
    m_tree = DynamicAabbTree(kFatMargin);
    const std::vector<int> proxies = m_tree.createProxiesTopDown(m_boxes);
    for (std::size_t e = 0; e < m_entries.size(); ++e) m_entries[e].proxy = proxies[e];
  } else {
    changed = false;
    for (std::size_t e = 0; e < m_entries.size(); ++e)
      changed = m_tree.moveProxy(m_entries[e].proxy, m_boxes[e], Vec3::Zero()) || changed;
  }
  if (changed) m_rayTree.assign(m_tree);
}

std::optional<SceneHit> RayScene::hitBody(const Entry& entry, const RaySegment& segment,
                                          double maxFraction) const {
  if (entry.triangles != nullptr) {
    // The ray in the body frame, where the mesh and its BVH are.
    const RaySegment local(entry.pose.applyInverse(segment.origin),
                           entry.pose.inverseRotate(segment.delta));
    const auto hit = castTriangleMesh(*entry.triangles, local, maxFraction);
    if (!hit) return std::nullopt;
    return SceneHit{entry.bodyIndex, entry.serial, hit->triangle, 0, hit->fraction,
                    entry.pose.rotate(hit->normal)};
  }
  std::optional<SceneHit> best;
  for (int p = 0; p < entry.pieceCount; ++p) {
    const Piece& piece = m_pieces[at(entry.firstPiece + p)];
    // The ray in the piece's frame: fractions are the same in every frame.
    const Vec3 origin = piece.pose.applyInverse(segment.origin);
    const Vec3 direction = piece.pose.inverseRotate(segment.delta);
    const std::optional<RayEntry> hit = firstEntry(convexSpan(*piece.geometry, origin, direction), maxFraction);
    if (!hit || (best && !(hit->fraction < best->fraction))) continue;
    best = SceneHit{entry.bodyIndex, entry.serial, p, piece.part, hit->fraction,
                    worldNormal(*hit, piece.pose.rotation, segment.delta)};
    maxFraction = hit->fraction;
  }
  return best;
}

std::optional<SceneHit> RayScene::hitPlane(const Plane& plane, const RaySegment& segment) const {
  const RaySpan span = halfSpaceSpan(plane.halfSpace.normal, plane.halfSpace.offset, segment.origin, segment.delta);
  const std::optional<RayEntry> hit = firstEntry(span, 1.0);
  if (!hit) return std::nullopt;
  return SceneHit{plane.bodyIndex, plane.serial, 0, 0, hit->fraction,
                  worldNormal(*hit, Mat3::Identity(), segment.delta)};
}

std::optional<SceneHit> RayScene::closest(const SceneRay& ray) const {
  std::optional<SceneHit> best;
  const auto consider = [&](const std::optional<SceneHit>& hit) {
    if (hit && (!best || isNearer(*hit, *best))) best = hit;
  };
  for (const Plane& plane : m_planes)
    if (mayHit(ray, plane.bodyIndex, plane.filter)) consider(hitPlane(plane, ray.segment));
  m_rayTree.cast(ray.segment, best ? best->fraction : 1.0, [&](int entryIndex) {
    const Entry& entry = m_entries[at(entryIndex)];
    const double maxFraction = best ? best->fraction : 1.0;
    if (mayHit(ray, entry.bodyIndex, entry.filter)) consider(hitBody(entry, ray.segment, maxFraction));
    return best ? best->fraction : 1.0;
  });
  return best;
}

bool RayScene::any(const SceneRay& ray) const {
  for (const Plane& plane : m_planes)
    if (mayHit(ray, plane.bodyIndex, plane.filter) && hitPlane(plane, ray.segment)) return true;
  bool found = false;
  m_rayTree.cast(ray.segment, 1.0, [&](int entryIndex) {
    const Entry& entry = m_entries[at(entryIndex)];
    found = mayHit(ray, entry.bodyIndex, entry.filter) && hitBody(entry, ray.segment, 1.0).has_value();
    return found ? -1.0 : 1.0;
  });
  return found;
}

void RayScene::all(const SceneRay& ray, std::vector<SceneHit>& hits) const {
  hits.clear();
  for (const Plane& plane : m_planes)
    if (mayHit(ray, plane.bodyIndex, plane.filter))
      if (const auto hit = hitPlane(plane, ray.segment)) hits.push_back(*hit);
  m_rayTree.cast(ray.segment, 1.0, [&](int entryIndex) {
    const Entry& entry = m_entries[at(entryIndex)];
    if (mayHit(ray, entry.bodyIndex, entry.filter))
      if (const auto hit = hitBody(entry, ray.segment, 1.0)) hits.push_back(*hit);
    return 1.0;
  });
  std::sort(hits.begin(), hits.end(), isNearer);
}

}  // namespace rbsim

// --- shape casts ---

namespace rbsim {

template <class Visit>
void RayScene::walkSweep(const SceneSweep& sweep, double maxFraction, Visit&& visit) const {
  // The swept shape's box, centred on a point that moves with it: the
  // tree's boxes grown by its half extents are met by that point's segment
  // wherever the swept box meets the boxes themselves.
  const Aabb bounds = placedBounds(sweep.shape, sweep.start);
  m_rayTree.sweep(RaySegment(bounds.center(), sweep.delta), bounds.halfExtents(), maxFraction,
                  [&](int entryIndex) { return visit(m_entries[at(entryIndex)]); });
}

namespace {

// A triangle as a convex solid for GJK (its support is its farthest
// corner): a flat hull of three vertices, seen from both sides as rays see
// a trimesh's triangles.
ConvexGeometry triangleSolid(const ContactTriangle& triangle) {
  auto hull = std::make_shared<ConvexHull>();
  hull->vertices.assign(triangle.vertices.begin(), triangle.vertices.end());
  hull->lowerCorner = triangle.vertices[0].cwiseMin(triangle.vertices[1]).cwiseMin(triangle.vertices[2]);
  hull->upperCorner = triangle.vertices[0].cwiseMax(triangle.vertices[1]).cwiseMax(triangle.vertices[2]);
  hull->centroid = (triangle.vertices[0] + triangle.vertices[1] + triangle.vertices[2]) / 3.0;
  for (const Vec3& v : triangle.vertices) hull->radius = std::max(hull->radius, (v - hull->centroid).norm());
  return std::shared_ptr<const ConvexHull>(std::move(hull));
}

}  // namespace

// A trimesh's first triangle touched: the sweep moved into the mesh's
// frame, its box swept through the triangles' BVH (boxes grown by the
// shape's half extents, as in the scene's tree), narrowed at each touch.
std::optional<SceneSweepHit> RayScene::sweepTriangles(const Entry& entry, const SceneSweep& sweep,
                                                      double maxFraction) const {
  const Transform start = entry.pose.inverse() * sweep.start;
  const Vec3 delta = entry.pose.inverseRotate(sweep.delta);
  const Aabb bounds = placedBounds(sweep.shape, start);
  const RaySegment path(bounds.center(), delta);
  const Eigen::Array3d grow = bounds.halfExtents().array();
  std::optional<SweepContact> best;
  int bestTriangle = 0;
  entry.triangles->bvh.traverse(
      [&](const Aabb& box) {
        return segmentEntersBox(path, box.min.array() - grow, box.max.array() + grow, maxFraction) <= maxFraction;
      },
      [&](int t) {
        const ConvexGeometry triangle = triangleSolid(entry.triangles->triangle(t, Transform::identity()));
        const std::optional<SweepContact> touch =
            sweepAgainstConvex(sweep.shape, start, delta, {&triangle, Transform::identity()}, maxFraction);
        if (!touch) return;
        if (best && (touch->fraction > best->fraction || (touch->fraction == best->fraction && t > bestTriangle)))
          return;
        best = touch;
        bestTriangle = t;
        maxFraction = touch->fraction;
      });
  if (!best) return std::nullopt;
  return SceneSweepHit{{entry.bodyIndex, entry.serial, bestTriangle, 0, best->fraction, entry.pose.rotate(best->normal)},
                       entry.pose.apply(best->point)};
}

std::optional<SceneSweepHit> RayScene::sweepBody(const Entry& entry, const SceneSweep& sweep,
                                                 double maxFraction) const {
  if (entry.triangles != nullptr) return sweepTriangles(entry, sweep, maxFraction);
  std::optional<SceneSweepHit> best;
  for (int p = 0; p < entry.pieceCount; ++p) {
    const Piece& piece = m_pieces[at(entry.firstPiece + p)];
    const std::optional<SweepContact> touch =
        sweepAgainstConvex(sweep.shape, sweep.start, sweep.delta, {piece.geometry, piece.pose}, maxFraction);
    if (!touch || (best && !(touch->fraction < best->hit.fraction))) continue;
    best = SceneSweepHit{{entry.bodyIndex, entry.serial, p, piece.part, touch->fraction, touch->normal}, touch->point};
    maxFraction = touch->fraction;
  }
  return best;
}

std::optional<SceneSweepHit> RayScene::sweepPlane(const Plane& plane, const SceneSweep& sweep) const {
  const std::optional<SweepContact> touch = sweepAgainstHalfSpace(sweep.shape, sweep.start, sweep.delta, plane.halfSpace, 1.0);
  if (!touch) return std::nullopt;
  return SceneSweepHit{{plane.bodyIndex, plane.serial, 0, 0, touch->fraction, touch->normal}, touch->point};
}

std::optional<SceneSweepHit> RayScene::sweepClosest(const SceneSweep& sweep) const {
  std::optional<SceneSweepHit> best;
  const auto consider = [&](const std::optional<SceneSweepHit>& touch) {
    if (touch && (!best || isNearer(touch->hit, best->hit))) best = touch;
  };
  for (const Plane& plane : m_planes)
    if (mayHit(sweep, plane.bodyIndex, plane.filter)) consider(sweepPlane(plane, sweep));
  walkSweep(sweep, best ? best->hit.fraction : 1.0, [&](const Entry& entry) {
    const double maxFraction = best ? best->hit.fraction : 1.0;
    if (mayHit(sweep, entry.bodyIndex, entry.filter)) consider(sweepBody(entry, sweep, maxFraction));
    return best ? best->hit.fraction : 1.0;
  });
  return best;
}

void RayScene::sweepAll(const SceneSweep& sweep, std::vector<SceneSweepHit>& hits) const {
  hits.clear();
  for (const Plane& plane : m_planes)
    if (mayHit(sweep, plane.bodyIndex, plane.filter))
      if (const auto touch = sweepPlane(plane, sweep)) hits.push_back(*touch);
  walkSweep(sweep, 1.0, [&](const Entry& entry) {
    if (mayHit(sweep, entry.bodyIndex, entry.filter))
      if (const auto touch = sweepBody(entry, sweep, 1.0)) hits.push_back(*touch);
    return 1.0;
  });
  std::sort(hits.begin(), hits.end(),
            [](const SceneSweepHit& a, const SceneSweepHit& b) { return isNearer(a.hit, b.hit); });
}

}  // namespace rbsim
