// Ray casts against the anchors' pile of 1000 boxes (tests/scenes/
// pile_scene.h, as dropped: the cubes where Bullet's, ODE's and MuJoCo's
// start, on the ground plane): random rays through the pile's bounds, the
// closest hit of each. rbsim one ray at a time (World::castRay), in one
// batch on one thread (World::castRays), and, when Bullet is installed,
// btCollisionWorld::rayTest with a ClosestRayResultCallback on the same
// boxes and plane (btDbvtBroadphase, as Bullet's worlds have by default).
// Counters: items_per_second is rays per second on one core; hit_share the
// share of rays that hit; mean_distance (m) the mean distance of the hits,
// to see the two engines answer alike.
//
// Shape casts along the same segments: a sphere of radius 0.05 m and a box
// of half size 0.05 m (turned by a fixed rotation), the first touch of
// each: rbsim's World::castShape beside Bullet's
// btCollisionWorld::convexSweepTest with a ClosestConvexResultCallback.
//
//   taskset -c 1 build/bench/bench_rays --benchmark_repetitions=3 --benchmark_min_time=0.5s
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <memory>
#include <optional>
#include <vector>

#include "ray_tally.h"
#include "rbsim/physics/world.h"
#include "scenes/pile_scene.h"
#include "scenes/scene_random.h"

#if RBSIM_BENCH_RAYS_BULLET
#include "bullet_queries.h"
#endif

namespace rbsim {
namespace {

constexpr int kBoxes = 1000;
constexpr std::size_t kRays = 4096;

// Around the pile: 10 × 10 columns 0.25 m apart (cubes of 0.2 m, turned by
// up to 0.1 rad, so within ±1.3 m) and ten layers from z = 0.05 m up to
// 2.45 m, on the ground plane z = 0.
const Vec3 kLower(-1.4, -1.4, 0.0);
const Vec3 kUpper(1.4, 1.4, 2.6);

// A random point on the bounds' faces: face 0 is the floor (on the ground),
// 1 the top, 2–5 the sides.
Vec3 pointOnBounds(scenes::SceneRandom& random, int face) {
  Vec3 point(random.uniform(kLower.x(), kUpper.x()), random.uniform(kLower.y(), kUpper.y()),
             random.uniform(kLower.z(), kUpper.z()));
  switch (face) {
    case 0: point.z() = -0.1; break;  // below the ground: a ray that gets there hits it inside the ray
    case 1: point.z() = kUpper.z(); break;
    case 2: point.x() = kLower.x(); break;
    case 3: point.x() = kUpper.x(); break;
    case 4: point.y() = kLower.y(); break;
    default: point.y() = kUpper.y(); break;
  }
  return point;
}

// Rays through the pile's bounds: from a point on the top or a side (outside
// every box) to a point on another face, the floor included. Most cross
// boxes; some reach the ground between the columns, a few miss.
std::vector<Ray> randomRays() {
  scenes::SceneRandom random(0x4A75);
  std::vector<Ray> rays(kRays);
  for (Ray& ray : rays) {
    const int from = 1 + static_cast<int>(random.next() % 5);
    int to = static_cast<int>(random.next() % 6);
    if (to == from) to = 0;
    ray.from = pointOnBounds(random, from);
    ray.to = pointOnBounds(random, to);
  }
  return rays;
}

World pileWorld() {
  auto world = World::fromDef(scenes::makePileScene(kBoxes, scenes::PileVariant::Dropped));
  if (!world) throw std::runtime_error(world.error().message);
  return std::move(world).value();
}

void BM_Rays_Rbsim_Single(benchmark::State& state) {
  const World world = pileWorld();
  const std::vector<Ray> rays = randomRays();
  (void)world.castRay(rays.front());  // the ray tree is built at the first cast
  const bench::RayTally tally = bench::castEveryRay(state, rays, [&](const Ray& ray) -> std::optional<double> {
    if (const std::optional<RayHit> hit = world.castRay(ray)) return hit->distance;
    return std::nullopt;
  });
  bench::reportTally(state, tally, rays.size());
}

void BM_Rays_Rbsim_Batch(benchmark::State& state) {
  World world = pileWorld();
  if (!world.setThreads(1)) state.SkipWithError("threads");
  const std::vector<Ray> rays = randomRays();
  std::vector<std::optional<RayHit>> hits(rays.size());
  world.castRays(rays, hits);
  for (auto _ : state) {
    world.castRays(rays, hits);
    benchmark::DoNotOptimize(hits.data());
  }
  bench::RayTally tally;
  for (const auto& hit : hits)
    if (hit) {
      ++tally.hits;
      tally.distance += hit->distance;
    }
  bench::reportTally(state, tally, rays.size());
}

// The first cast after a step of the falling pile: the ray tree follows
// the bodies (proxies move when a body leaves its fat box) and is copied
// for the walk, then one ray. The step itself is not timed.
void BM_Rays_Rbsim_FirstCastAfterStep(benchmark::State& state) {
  World world = pileWorld();
  const Ray ray = randomRays().front();
  (void)world.castRay(ray);
  for (auto _ : state) {
    state.PauseTiming();
    world.step();
    state.ResumeTiming();
    benchmark::DoNotOptimize(world.castRay(ray));
  }
}

// The first cast in a copy of the world: the ray tree built from scratch
// (top down, by the surface-area heuristic), then one ray.
void BM_Rays_Rbsim_FirstCastAfterCopy(benchmark::State& state) {
  const World world = pileWorld();
  const Ray ray = randomRays().front();
  World copy = world;
  for (auto _ : state) {
    state.PauseTiming();
    copy = world;
    state.ResumeTiming();
    benchmark::DoNotOptimize(copy.castRay(ray));
  }
}

// The shapes the casts sweep, and their fixed orientation.
constexpr double kCastSize = 0.05;  // m: the sphere's radius, the box's half size
const Quaternion kCastTurn = Quaternion::fromAxisAngle(Vec3(1, 2, 3).normalized(), 0.4);

void BM_ShapeCasts_Rbsim(benchmark::State& state, CastShape shape) {
  const World world = pileWorld();
  const std::vector<Ray> rays = randomRays();
  (void)world.castRay(rays.front());  // the tree is built at the first query
  const bench::RayTally tally = bench::castEveryRay(state, rays, [&](const Ray& ray) -> std::optional<double> {
    if (const std::optional<ShapeCastHit> hit = world.castShape({shape, ray.from, ray.to, kCastTurn}))
      return hit->distance;
    return std::nullopt;
  });
  bench::reportTally(state, tally, rays.size());
}

#if RBSIM_BENCH_RAYS_BULLET
using bench::bulletRayTest;
using bench::toBullet;

// The same scene in a btCollisionWorld: a static plane and the boxes as
// collision objects (a ray test needs no dynamics).
struct BulletPile {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &config};
  btStaticPlaneShape plane{btVector3(0, 0, 1), 0};
  btBoxShape box{btVector3(0.1, 0.1, 0.1)};
  std::vector<std::unique_ptr<btCollisionObject>> objects;

  BulletPile() {
    const WorldDef def = scenes::makePileScene(kBoxes, scenes::PileVariant::Dropped);
    for (const BodyDef& body : def.bodies) {
      auto object = std::make_unique<btCollisionObject>();
      const bool isPlane = std::holds_alternative<PlaneShape>(body.shape);
      object->setCollisionShape(isPlane ? static_cast<btCollisionShape*>(&plane) : &box);
      const Quaternion& q = body.orientation;  // (w, x, y, z); Bullet's is (x, y, z, w)
      object->setWorldTransform(btTransform(btQuaternion(q.x, q.y, q.z, q.w), toBullet(body.position)));
      world.addCollisionObject(object.get());
      objects.push_back(std::move(object));
    }
    world.updateAabbs();
  }
  ~BulletPile() {
    for (auto& object : objects) world.removeCollisionObject(object.get());
  }
};

void BM_Rays_Bullet_RayTest(benchmark::State& state) {
  BulletPile pile;
  const std::vector<Ray> rays = randomRays();
  const bench::RayTally tally = bench::castEveryRay(state, rays, [&](const Ray& ray) -> std::optional<double> {
    return bulletRayTest(pile.world, ray);
  });
  bench::reportTally(state, tally, rays.size());
}
BENCHMARK(BM_Rays_Bullet_RayTest)->Unit(benchmark::kMicrosecond);

void BM_ShapeCasts_Bullet(benchmark::State& state, bool sphere) {
  BulletPile pile;
  const std::vector<Ray> rays = randomRays();
  btSphereShape ball(kCastSize);
  btBoxShape box(btVector3(kCastSize, kCastSize, kCastSize));
  const btConvexShape* shape = sphere ? static_cast<btConvexShape*>(&ball) : &box;
  const btQuaternion turn(kCastTurn.x, kCastTurn.y, kCastTurn.z, kCastTurn.w);
  const bench::RayTally tally = bench::castEveryRay(state, rays, [&](const Ray& ray) -> std::optional<double> {
    const btVector3 from = toBullet(ray.from);
    const btVector3 to = toBullet(ray.to);
    btCollisionWorld::ClosestConvexResultCallback callback(from, to);
    pile.world.convexSweepTest(shape, btTransform(turn, from), btTransform(turn, to), callback);
    if (!callback.hasHit()) return std::nullopt;
    return callback.m_closestHitFraction * (to - from).length();
  });
  bench::reportTally(state, tally, rays.size());
}
BENCHMARK_CAPTURE(BM_ShapeCasts_Bullet, sphere, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ShapeCasts_Bullet, box, false)->Unit(benchmark::kMicrosecond);
#endif

BENCHMARK_CAPTURE(BM_ShapeCasts_Rbsim, sphere, CastShape(SphereShape{kCastSize}))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ShapeCasts_Rbsim, box, CastShape(BoxShape{Vec3::Constant(kCastSize)}))
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_Rays_Rbsim_Single)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Rays_Rbsim_Batch)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Rays_Rbsim_FirstCastAfterStep)->Unit(benchmark::kMicrosecond)->Iterations(300);
BENCHMARK(BM_Rays_Rbsim_FirstCastAfterCopy)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace rbsim

BENCHMARK_MAIN();
