// Triangle meshes (issue 40): the anchors' pile of boxes (tests/scenes/
// pile_scene.h, dropped, no sleeping) on a floor of 100,352 triangles
// against the same pile on a ground plane, and rays against a terrain of
// 100,352 triangles; rbsim beside Bullet (btBvhTriangleMeshShape,
// btStaticPlaneShape, rayTest) when Bullet is installed.
//
//   taskset -c 1 build/bench/bench_trimesh --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//
// The floor is a flat 224 × 224 grid of cells over 10 m × 10 m (4.5 cm
// cells, so a 20 cm box stands on some 40 triangles); the terrain is the
// same grid of heights 0.2 sin(x) cos(y). The piles step 500 steps of 1 ms
// (the pile falls 5 cm and settles) with one thread; counters: ms_per_step,
// and contacts (manifolds) and the bodies' kinetic energy at the end, to
// see the two floors hold the pile alike.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "ray_tally.h"
#include "rbsim/physics/world.h"
#include "scenes/pile_scene.h"
#include "scenes/scene_random.h"

#if RBSIM_BENCH_TRIMESH_BULLET
#include <btBulletDynamicsCommon.h>

#include "bullet_queries.h"
#endif

namespace rbsim {
namespace {

constexpr int kCells = 224;         // per side: 2 × 224² = 100,352 triangles
constexpr double kHalfSize = 5.0;   // m
constexpr int kPileSteps = 500;
constexpr std::size_t kRays = 4096;

// A grid of kCells × kCells cells over ±kHalfSize, of heights height(x, y),
// each cell two triangles facing up.
template <class Height>
TriangleMesh gridMesh(Height&& height) {
  TriangleMesh mesh;
  const double step = 2.0 * kHalfSize / kCells;
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) {
      const double x = -kHalfSize + i * step, y = -kHalfSize + j * step;
      mesh.vertices.emplace_back(x, y, height(x, y));
    }
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const int a = j * (kCells + 1) + i, b = a + 1, c = a + kCells + 2, d = a + kCells + 1;
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
  return mesh;
}

TriangleMesh floorMesh() {
  return gridMesh([](double, double) { return 0.0; });
}
TriangleMesh terrainMesh() {
  return gridMesh([](double x, double y) { return 0.2 * std::sin(x) * std::cos(y); });
}

// The pile's world, its ground a plane (as the scene has it) or the floor mesh.
World pileWorld(bool onMesh, int boxes) {
  WorldDef def = scenes::makePileScene(boxes, scenes::PileVariant::Dropped);
  def.settings.contact.sleeping = false;
  def.settings.threads = 1;
  if (onMesh) def.bodies[0].shape = TriangleMeshShape{"floor", std::make_shared<const TriangleMesh>(floorMesh())};
  auto world = World::fromDef(def);
  if (!world) throw std::runtime_error(world.error().message);
  return std::move(world).value();
}

double kineticEnergy(const World& world) {
  double energy = 0.0;
  for (const BodyView body : world.bodies()) {
    if (body.isStatic()) continue;
    energy += 0.5 * body.mass() * body.linearVelocity().squaredNorm();
  }
  return energy;
}

void BM_Pile_Rbsim(benchmark::State& state) {
  const bool onMesh = state.range(0) != 0;
  for (auto _ : state) {
    state.PauseTiming();
    World world = pileWorld(onMesh, static_cast<int>(state.range(1)));
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kPileSteps; ++i) world.step();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.counters["ms_per_step"] = 1e3 * seconds / kPileSteps;
    state.counters["manifolds"] = static_cast<double>(world.contacts().size());
    state.counters["ke"] = kineticEnergy(world);
  }
}
BENCHMARK(BM_Pile_Rbsim)->ArgNames({"mesh", "boxes"})->Args({0, 1000})->Args({1, 1000})
    ->Unit(benchmark::kMillisecond)->Iterations(1);

// Rays from above the terrain to below it, in random directions within its bounds.
std::vector<Ray> terrainRays() {
  scenes::SceneRandom random(0x7E44);
  std::vector<Ray> rays(kRays);
  for (Ray& ray : rays) {
    ray.from = Vec3(random.uniform(-4.5, 4.5), random.uniform(-4.5, 4.5), 1.0);
    ray.to = Vec3(random.uniform(-4.5, 4.5), random.uniform(-4.5, 4.5), -1.0);
  }
  return rays;
}

void BM_TerrainRays_Rbsim(benchmark::State& state) {
  World world;
  BodyDef terrain;
  terrain.name = "terrain";
  terrain.shape = TriangleMeshShape{"terrain", std::make_shared<const TriangleMesh>(terrainMesh())};
  terrain.isStatic = true;
  (void)world.createBody(terrain).value();
  const std::vector<Ray> rays = terrainRays();
  (void)world.castRay(rays.front());
  const bench::RayTally tally = bench::castEveryRay(state, rays, [&](const Ray& ray) -> std::optional<double> {
    if (const std::optional<RayHit> hit = world.castRay(ray)) return hit->distance;
    return std::nullopt;
  });
  bench::reportTally(state, tally, rays.size());
}
BENCHMARK(BM_TerrainRays_Rbsim)->Unit(benchmark::kMicrosecond);

#if RBSIM_BENCH_TRIMESH_BULLET
using bench::toBullet;

// A mesh as Bullet's static triangle mesh (its own copy of the arrays).
struct BulletMesh {
  std::vector<int> indices;
  std::vector<btScalar> vertices;
  std::unique_ptr<btTriangleIndexVertexArray> array;
  std::unique_ptr<btBvhTriangleMeshShape> shape;

  explicit BulletMesh(const TriangleMesh& mesh) {
    for (const auto& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
    for (const Vec3& v : mesh.vertices) vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
    array = std::make_unique<btTriangleIndexVertexArray>(
        static_cast<int>(mesh.triangles.size()), indices.data(), 3 * static_cast<int>(sizeof(int)),
        static_cast<int>(mesh.vertices.size()), vertices.data(), 3 * static_cast<int>(sizeof(btScalar)));
    shape = std::make_unique<btBvhTriangleMeshShape>(array.get(), true);
  }
};

// The pile in a btDiscreteDynamicsWorld (default solver, 10 iterations),
// friction 0.5 per pair (sqrt per object), no sleeping.
struct BulletPile {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  btStaticPlaneShape plane{btVector3(0, 0, 1), 0};
  btBoxShape box{btVector3(0.1, 0.1, 0.1)};
  std::optional<BulletMesh> floor;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<std::unique_ptr<btDefaultMotionState>> states;

  BulletPile(bool onMesh, int boxes) {
    world.setGravity(btVector3(0, 0, -9.81));
    if (onMesh) floor.emplace(floorMesh());
    const WorldDef def = scenes::makePileScene(boxes, scenes::PileVariant::Dropped);
    for (const BodyDef& body : def.bodies) {
      const bool isGround = body.isStatic;
      btCollisionShape* shape = isGround ? (onMesh ? static_cast<btCollisionShape*>(floor->shape.get()) : &plane)
                                         : static_cast<btCollisionShape*>(&box);
      const btScalar mass = isGround ? 0.0 : 8.0;  // 1000 kg/m³ × (0.2 m)³
      btVector3 inertia(0, 0, 0);
      if (!isGround) box.calculateLocalInertia(mass, inertia);
      const Quaternion& q = body.orientation;
      states.push_back(std::make_unique<btDefaultMotionState>(
          btTransform(btQuaternion(q.x, q.y, q.z, q.w), toBullet(body.position))));
      auto rigid = std::make_unique<btRigidBody>(mass, states.back().get(), shape, inertia);
      rigid->setFriction(std::sqrt(0.5));
      rigid->setActivationState(DISABLE_DEACTIVATION);
      world.addRigidBody(rigid.get());
      bodies.push_back(std::move(rigid));
    }
  }
  ~BulletPile() {
    for (auto& body : bodies) world.removeRigidBody(body.get());
  }
};

void BM_Pile_Bullet(benchmark::State& state) {
  const bool onMesh = state.range(0) != 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto pile = std::make_unique<BulletPile>(onMesh, static_cast<int>(state.range(1)));
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kPileSteps; ++i) pile->world.stepSimulation(1e-3, 0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.counters["ms_per_step"] = 1e3 * seconds / kPileSteps;
    state.counters["manifolds"] = pile->dispatcher.getNumManifolds();
    double energy = 0.0;
    for (const auto& body : pile->bodies)
      if (body->getInvMass() > 0) energy += 0.5 * 8.0 * body->getLinearVelocity().length2();
    state.counters["ke"] = energy;
    state.PauseTiming();
    pile.reset();
    state.ResumeTiming();
  }
}
BENCHMARK(BM_Pile_Bullet)->ArgNames({"mesh", "boxes"})->Args({0, 1000})->Args({1, 1000})
    ->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_TerrainRays_Bullet(benchmark::State& state) {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btCollisionWorld world(&dispatcher, &broadphase, &config);
  BulletMesh terrain(terrainMesh());
  btCollisionObject object;
  object.setCollisionShape(terrain.shape.get());
  world.addCollisionObject(&object);
  world.updateAabbs();
  const std::vector<Ray> rays = terrainRays();
  const bench::RayTally tally = bench::castEveryRay(state, rays, [&](const Ray& ray) -> std::optional<double> {
    return bench::bulletRayTest(world, ray);
  });
  world.removeCollisionObject(&object);
  bench::reportTally(state, tally, rays.size());
}
BENCHMARK(BM_TerrainRays_Bullet)->Unit(benchmark::kMicrosecond);
#endif

}  // namespace
}  // namespace rbsim

BENCHMARK_MAIN();
