// The narrow phase on hull–hull pairs: rbsim's collideConvex (the manifold:
// SAT and clipping for hulls) beside libccd's GJK+EPA and MPR penetration
// (ccdGJKPenetration, ccdMPRPenetration: depth, direction and one point)
// and, when Bullet is installed, Bullet's btGjkPairDetector (GJK, EPA when
// penetrating) followed by btPolyhedralContactClipping::clipHullAgainstHull
// (the manifold), on the same hulls.
//
// Hulls: N random points on an ellipsoid of semi-axes 100 × 70 × 50 mm
// (every point is a hull vertex), built by rbsim's buildConvexHull, for N =
// 8, 64, 256, 576 (576: the largest hull of the KUKA iiwa's links), fixed
// seeds. Each pair is placed at four fixed random configurations (both
// orientations and the direction from A to B), B moved along that
// direction until the signed distance is
//   separated     +10 mm  (outside the contact margin, 5 mm),
//   touching      +0.5 mm (within the margin: a contact with a gap),
//   penetrating   −10 mm  (10 mm deep);
// one benchmark iteration is one pair query, cycling through the four.
// Names: BM_<method>/<N>/<case>. Counters: points (manifold points per
// query: rbsim and Bullet), hit (fraction of queries that reported
// contact or penetration).
//
//   taskset -c 1 build/bench/bench_narrow_phase --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
//   build/bench/bench_narrow_phase --benchmark_filter='/576/'   # one size
//
// Same support function for rbsim and libccd (rbsim's, over the hull's
// vertices); Bullet uses its own (btConvexHullShape, margin 0).
#include <benchmark/benchmark.h>
#include <ccd/ccd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "physics/collision/collider.h"
#include "physics/collision/contact_generation.h"
#include "physics/collision/convex_hull.h"
#include "physics/collision/signed_distance.h"
#include "scenes/scene_random.h"

#if RBSIM_NARROW_PHASE_BULLET
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btConvexPolyhedron.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPolyhedralContactClipping.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#endif

namespace rbsim {
namespace {

constexpr double kMargin = 0.005;  // m: rbsim's default contact margin
constexpr int kConfigurations = 4;

struct Case {
  const char* name;
  double signedDistance;  // m
};
constexpr std::array<Case, 3> kCases = {
    {{"separated", 0.010}, {"touching", 0.0005}, {"penetrating", -0.010}}};

std::shared_ptr<const ConvexHull> ellipsoidHull(int count, uint64_t seed) {
  scenes::SceneRandom random(seed);
  std::vector<Vec3> points;
  while (static_cast<int>(points.size()) < count) {
    const Vec3 d(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
    const double n = d.norm();
    if (n < 0.1 || n > 1) continue;  // uniform directions: rejection from the ball
    points.push_back(Vec3(0.10 * d.x(), 0.07 * d.y(), 0.05 * d.z()) / n);
  }
  Expected<ConvexHull> hull = buildConvexHull(points, "ellipsoid");
  if (!hull.ok()) {
    std::fprintf(stderr, "bench_narrow_phase: %s\n", hull.error().message.c_str());
    std::exit(1);
  }
  return std::make_shared<const ConvexHull>(std::move(*hull));
}

// A pair of hulls at kConfigurations placements with the case's distance.
struct PairSet {
  std::shared_ptr<const ConvexHull> hullA, hullB;
  ConvexGeometry geometryA, geometryB;
  std::array<Transform, kConfigurations> poseA, poseB;

  PairSet(int vertices, double target)
      : hullA(ellipsoidHull(vertices, 0xA11CE + static_cast<uint64_t>(vertices))),
        hullB(ellipsoidHull(vertices, 0xB0B + static_cast<uint64_t>(vertices))),
        geometryA(hullA),
        geometryB(hullB) {
    scenes::SceneRandom random(0x5EED);
    for (int c = 0; c < kConfigurations; ++c) {
      const Quaternion qa = random.rotation(), qb = random.rotation();
      Vec3 d(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
      d.normalize();
      poseA[c] = Transform::fromPose(Vec3::Zero(), qa);
      // Bisection on the offset along d: the signed distance goes from
      // negative (centres together) to positive (0.5 m apart).
      double lo = 0.0, hi = 0.5;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (distanceAt(qb, d * mid, c) < target ? lo : hi) = mid;
      }
      poseB[c] = Transform::fromPose(d * (0.5 * (lo + hi)), qb);
    }
  }

  double distanceAt(const Quaternion& qb, const Vec3& position, int c) const {
    const PlacedConvex a{&geometryA, poseA[c]};
    const PlacedConvex b{&geometryB, Transform::fromPose(position, qb)};
    return signedDistance(a, b).distance;
  }

  PlacedConvex a(int c) const { return {&geometryA, poseA[c]}; }
  PlacedConvex b(int c) const { return {&geometryB, poseB[c]}; }
};

void setCounters(benchmark::State& state, double points, double hits) {
  const double n = static_cast<double>(state.iterations());
  state.counters["points"] = points / n;
  state.counters["hit"] = hits / n;
}

void BM_rbsim(benchmark::State& state, int vertices, double target) {
  const PairSet pairs(vertices, target);
  ContactSettings settings;
  settings.margin = kMargin;
  double points = 0, hits = 0;
  int c = 0;
  for (auto _ : state) {
    ContactManifold manifold;
    const bool touching = collideConvex(pairs.a(c), pairs.b(c), settings, manifold);
    benchmark::DoNotOptimize(manifold);
    points += manifold.pointCount;
    hits += touching;
    c = (c + 1) % kConfigurations;
  }
  setCounters(state, points, hits);
}

// libccd's view of a placed hull. Its EPA and MPR loops stop only on their
// tolerances (libccd 2.1), which rounding can keep them from reaching; as
// in rbsim's ccd_support.cpp, a query beyond a budget answers "behind the
// origin", which ends any loop on its next pass.
struct CcdHull {
  PlacedConvex piece;
  Vec3 centre;
  mutable int calls = 0;

  static void support(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
    const auto* self = static_cast<const CcdHull*>(object);
    const Vec3 d(direction->v[0], direction->v[1], direction->v[2]);
    const Vec3 p = self->calls++ < 1024 ? self->piece.support(d) : Vec3(-1.0 * d.normalized());
    ccdVec3Set(out, p.x(), p.y(), p.z());
  }
  static void center(const void* object, ccd_vec3_t* out) {
    const Vec3& p = static_cast<const CcdHull*>(object)->centre;
    ccdVec3Set(out, p.x(), p.y(), p.z());
  }
};

enum class CcdMethod { GjkEpa, Mpr };

void BM_ccd(benchmark::State& state, CcdMethod method, int vertices, double target) {
  const PairSet pairs(vertices, target);
  std::vector<CcdHull> as, bs;
  for (int c = 0; c < kConfigurations; ++c) {
    as.push_back({pairs.a(c), pairs.poseA[c].apply(interiorPoint(pairs.geometryA))});
    bs.push_back({pairs.b(c), pairs.poseB[c].apply(interiorPoint(pairs.geometryB))});
  }
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd.support2 = CcdHull::support;
  ccd.center1 = ccd.center2 = CcdHull::center;
  ccd.max_iterations = 64;
  ccd.epa_tolerance = 1e-7;  // m: rbsim's relative 1e-6 on hulls of this size
  ccd.mpr_tolerance = 1e-7;
  double hits = 0;
  int c = 0;
  for (auto _ : state) {
    as[static_cast<size_t>(c)].calls = bs[static_cast<size_t>(c)].calls = 0;
    ccd_real_t depth = 0;
    ccd_vec3_t direction, position;
    const int status = method == CcdMethod::GjkEpa
                           ? ccdGJKPenetration(&as[static_cast<size_t>(c)],
                                               &bs[static_cast<size_t>(c)], &ccd, &depth,
                                               &direction, &position)
                           : ccdMPRPenetration(&as[static_cast<size_t>(c)],
                                               &bs[static_cast<size_t>(c)], &ccd, &depth,
                                               &direction, &position);
    benchmark::DoNotOptimize(depth);
    hits += status == 0;
    c = (c + 1) % kConfigurations;
  }
  setCounters(state, 0, hits);
}

#if RBSIM_NARROW_PHASE_BULLET
btVector3 toBt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

btTransform toBt(const Transform& t) {
  btMatrix3x3 basis;
  for (int r = 0; r < 3; ++r)
    basis[r] = btVector3(static_cast<btScalar>(t.rotation(r, 0)),
                         static_cast<btScalar>(t.rotation(r, 1)),
                         static_cast<btScalar>(t.rotation(r, 2)));
  return btTransform(basis, toBt(t.translation));
}

std::unique_ptr<btConvexHullShape> bulletHull(const ConvexHull& hull) {
  auto shape = std::make_unique<btConvexHullShape>();
  for (const Vec3& v : hull.vertices) shape->addPoint(toBt(v), false);
  shape->recalcLocalAabb();
  shape->setMargin(0);  // the hull itself, as rbsim's and libccd's
  shape->initializePolyhedralFeatures();
  return shape;
}

// Collects the points clipHullAgainstHull reports.
struct PointCount : btDiscreteCollisionDetectorInterface::Result {
  int points = 0;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3&, const btVector3&, btScalar) override { ++points; }
};

// GJK's closest points (with a threshold of the contact margin), EPA when
// they overlap.
struct GjkResult : btDiscreteCollisionDetectorInterface::Result {
  bool found = false;
  btVector3 normalOnB{0, 0, 1};
  btScalar distance = 0;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3& normal, const btVector3&, btScalar depth) override {
    found = true;
    normalOnB = normal;
    distance = depth;
  }
};

void BM_bullet(benchmark::State& state, int vertices, double target) {
  const PairSet pairs(vertices, target);
  const std::unique_ptr<btConvexHullShape> a = bulletHull(*pairs.hullA), b = bulletHull(*pairs.hullB);
  std::array<btTransform, kConfigurations> ta, tb;
  for (int c = 0; c < kConfigurations; ++c) {
    ta[static_cast<size_t>(c)] = toBt(pairs.poseA[c]);
    tb[static_cast<size_t>(c)] = toBt(pairs.poseB[c]);
  }
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver epa;
  const btScalar threshold = static_cast<btScalar>(kMargin);
  double points = 0, hits = 0;
  int c = 0;
  btVertexArray worldVertsB1, worldVertsB2;
  for (auto _ : state) {
    btGjkPairDetector gjk(a.get(), b.get(), &simplex, &epa);
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = ta[static_cast<size_t>(c)];
    input.m_transformB = tb[static_cast<size_t>(c)];
    input.m_maximumDistanceSquared = threshold * threshold;
    GjkResult closest;
    gjk.getClosestPoints(input, closest, nullptr);
    PointCount manifold;
    if (closest.found && closest.distance < threshold) {
      // As btConvexConvexAlgorithm does with polyhedral features: the
      // manifold by clipping B's face against A's side planes, along
      // GJK's normal on B (pointing from B towards A, Bullet's convention).
      worldVertsB1.resize(0);
      btPolyhedralContactClipping::clipHullAgainstHull(
          closest.normalOnB, *a->getConvexPolyhedron(), *b->getConvexPolyhedron(),
          ta[static_cast<size_t>(c)], tb[static_cast<size_t>(c)], closest.distance - threshold,
          threshold, worldVertsB1, worldVertsB2, manifold);
      hits += 1;
    }
    benchmark::DoNotOptimize(manifold.points);
    points += manifold.points;
    c = (c + 1) % kConfigurations;
  }
  setCounters(state, points, hits);
}
#endif

void registerAll() {
  for (const int vertices : {8, 64, 256, 576}) {
    for (const Case& k : kCases) {
      const std::string suffix = "/" + std::to_string(vertices) + "/" + k.name;
      const double d = k.signedDistance;
      benchmark::RegisterBenchmark(("BM_rbsim" + suffix).c_str(),
                                   [=](benchmark::State& s) { BM_rbsim(s, vertices, d); });
      benchmark::RegisterBenchmark(("BM_ccd_gjk_epa" + suffix).c_str(), [=](benchmark::State& s) {
        BM_ccd(s, CcdMethod::GjkEpa, vertices, d);
      });
      benchmark::RegisterBenchmark(("BM_ccd_mpr" + suffix).c_str(), [=](benchmark::State& s) {
        BM_ccd(s, CcdMethod::Mpr, vertices, d);
      });
#if RBSIM_NARROW_PHASE_BULLET
      benchmark::RegisterBenchmark(("BM_bullet" + suffix).c_str(),
                                   [=](benchmark::State& s) { BM_bullet(s, vertices, d); });
#endif
    }
  }
}

}  // namespace
}  // namespace rbsim

int main(int argc, char** argv) {
  rbsim::registerAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
