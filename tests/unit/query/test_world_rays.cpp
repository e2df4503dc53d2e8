// World::castRay and its kin (rbsim/physics/ray_cast.h): bodies placed and
// turned in the world, compounds, meshes and planes, the three queries,
// filters, the batch call against single calls, and the world changing
// between casts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <variant>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "physics/query/ray_shapes.h"
#include "rbsim/physics/world.h"
#include "unit/query/query_test_worlds.h"
#include "scenes/pile_scene.h"
#include "scenes/scene_random.h"

namespace rbsim {
namespace {

constexpr double kTol = 1e-12;

void expectHit(const std::optional<RayHit>& hit, BodyId body, const Ray& ray, double fraction,
               const Vec3& normal) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, body);
  EXPECT_NEAR(hit->fraction, fraction, kTol);
  EXPECT_NEAR(hit->distance, fraction * (ray.to - ray.from).norm(), kTol);
  EXPECT_NEAR((hit->point - (ray.from + fraction * (ray.to - ray.from))).norm(), 0.0, kTol);
  EXPECT_NEAR((hit->normal - normal).norm(), 0.0, kTol) << hit->normal.transpose();
}

TEST(WorldRays, TurnedBoxes) {
  World world;
  // Turned 90° about z, the box's x half extent 1 lies along y.
  const BodyId a = testing::addQueryBody(world, "a", BoxShape{Vec3(1, 0.5, 0.5)}, {3, 0, 0},
                       Quaternion::fromAxisAngle(Vec3::UnitZ(), std::numbers::pi / 2));
  const Ray alongX{{0, 0, 0}, {10, 0, 0}};
  expectHit(world.castRay(alongX), a, alongX, 0.25, {-1, 0, 0});
  const Ray alongY{{3, -5, 0}, {3, 5, 0}};
  expectHit(world.castRay(alongY), a, alongY, 0.4, {0, -1, 0});
  // A unit cube turned 45° about z at (5, 0, 0): its faces (±1, ±1, 0)/√2
  // at distance 1 from the centre. At y = 0.2 the ray enters through the
  // face (−1, 1, 0)/√2 at x = 5 − √2 + 0.2.
  World turned;
  const BodyId c = testing::addQueryBody(turned, "c", BoxShape{Vec3::Ones()}, {5, 0, 0},
                       Quaternion::fromAxisAngle(Vec3::UnitZ(), std::numbers::pi / 4));
  const Ray ray{{0, 0.2, 0}, {10, 0.2, 0}};
  expectHit(turned.castRay(ray), c, ray, (5 - std::sqrt(2.0) + 0.2) / 10, Vec3(-1, 1, 0).normalized());
}

TEST(WorldRays, EveryShapeKindThroughTheWorld) {
  World world;
  const BodyId sphere = testing::addQueryBody(world, "sphere", SphereShape{1.0}, {0, 0, 0});
  const BodyId cylinder = testing::addQueryBody(world, "cylinder", CylinderShape{0.5, 1.0}, {0, 10, 0},
                              Quaternion::fromAxisAngle(Vec3::UnitX(), std::numbers::pi / 2));
  const BodyId capsule = testing::addQueryBody(world, "capsule", CapsuleShape{0.5, 1.0}, {0, 20, 0},
                             Quaternion::fromAxisAngle(Vec3::UnitY(), std::numbers::pi / 2));
  const BodyId ground = testing::addQueryBody(world, "ground", PlaneShape{Vec3::UnitZ(), -5.0}, Vec3::Zero(),
                            Quaternion::identity(), true);
  Ray ray{{-5, 0.6, 0}, {5, 0.6, 0}};
  expectHit(world.castRay(ray), sphere, ray, 0.42, {-0.8, 0.6, 0});
  // The cylinder's axis turned onto −y: along y the ray meets a cap.
  ray = {{0, 5, 0}, {0, 15, 0}};
  expectHit(world.castRay(ray), cylinder, ray, 0.4, {0, -1, 0});
  ray = {{0, 10.5, 3}, {0, 10.5, -3}};
  expectHit(world.castRay(ray), cylinder, ray, 2.5 / 6, {0, 0, 1});
  // The capsule's axis turned onto x: from +x the ray meets a hemisphere.
  ray = {{5, 20, 0}, {-5, 20, 0}};
  expectHit(world.castRay(ray), capsule, ray, 0.35, {1, 0, 0});
  ray = {{0.3, 20, 0}, {0.3, 20, 4}};  // the cylindrical side, from inside
  const auto inside = world.castRay(ray);
  ASSERT_TRUE(inside);
  EXPECT_EQ(inside->body, capsule);
  EXPECT_EQ(inside->fraction, 0.0);
  EXPECT_EQ(inside->point, ray.from);
  EXPECT_NEAR((inside->normal - Vec3(0, 0, -1)).norm(), 0.0, kTol);
  // The ground plane z = −5.
  ray = {{7, 7, 0}, {7, 7, -10}};
  expectHit(world.castRay(ray), ground, ray, 0.5, {0, 0, 1});
}

TEST(WorldRays, MeshAndCompoundReportTheirPieceAndPart) {
  World world;
  // A tetrahedron as a triangle mesh: its slanted face x + y + z = 1.
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const BodyId tetra = testing::addQueryBody(world, "tetra", MeshShape{"tetra", mesh}, {10, 0, 0});
  Ray ray{{10.2, 0.2, 5}, {10.2, 0.2, -5}};
  expectHit(world.castRay(ray), tetra, ray, 0.44, Vec3(1, 1, 1).normalized());
  ray = {{10.2, 0.3, -5}, {10.2, 0.3, 5}};
  expectHit(world.castRay(ray), tetra, ray, 0.5, {0, 0, -1});

  // Two spheres and a box, at (±1, 0, 0) and (0, 0, 2) in a compound
  // turned 90° about z (so part 0 sits at (0, −1, 0), part 1 at (0, 1, 0)).
  CompoundShape compound;
  compound.parts.push_back({SphereShape{0.5}, {-1, 0, 0}, Quaternion::identity(), {}});
  compound.parts.push_back({SphereShape{0.5}, {1, 0, 0}, Quaternion::identity(), {}});
  compound.parts.push_back({BoxShape{Vec3(0.5, 0.25, 0.25)}, {0, 0, 2}, Quaternion::identity(), {}});
  const BodyId body = testing::addQueryBody(world, "compound", compound, {0, 0, 0},
                          Quaternion::fromAxisAngle(Vec3::UnitZ(), std::numbers::pi / 2));
  ray = {{-5, 1, 0}, {5, 1, 0}};
  auto hit = world.castRay(ray);
  expectHit(hit, body, ray, 0.45, {-1, 0, 0});
  EXPECT_EQ(hit->part, 1);
  EXPECT_EQ(hit->piece, 1);
  ray = {{0, -5, 0}, {0, 5, 0}};
  hit = world.castRay(ray);
  expectHit(hit, body, ray, 0.35, {0, -1, 0});
  EXPECT_EQ(hit->part, 0);
  // The box part, turned with the compound: its x half extent along y.
  ray = {{0, -5, 2}, {0, 5, 2}};
  hit = world.castRay(ray);
  expectHit(hit, body, ray, 0.45, {0, -1, 0});
  EXPECT_EQ(hit->part, 2);
  EXPECT_EQ(hit->piece, 2);
  // All hits on the body: one, where the ray first enters it.
  EXPECT_EQ(world.castRayAll({{0, -5, 0}, {0, 5, 0}}).size(), 1u);
}

// Three boxes in a row along x and a ground plane, for the queries.
struct Row {
  World world;
  BodyId ground, near, middle, far;
  Row() {
    ground = testing::addQueryBody(world, "ground", PlaneShape{}, Vec3::Zero(), Quaternion::identity(), true);
    near = testing::addQueryBody(world, "near", BoxShape{Vec3::Constant(0.5)}, {2, 0, 1});
    middle = testing::addQueryBody(world, "middle", SphereShape{0.5}, {4, 0, 1});
    far = testing::addQueryBody(world, "far", BoxShape{Vec3::Constant(0.5)}, {6, 0, 1}, Quaternion::identity(), true);
  }
};

TEST(WorldRays, ClosestAllAndAny) {
  Row row;
  const Ray ray{{0, 0, 1}, {10, 0, 1}};
  expectHit(row.world.castRay(ray), row.near, ray, 0.15, {-1, 0, 0});
  const std::vector<RayHit> all = row.world.castRayAll(ray);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].body, row.near);
  EXPECT_EQ(all[1].body, row.middle);
  EXPECT_EQ(all[2].body, row.far);
  EXPECT_NEAR(all[1].distance, 3.5, kTol);
  EXPECT_NEAR(all[2].distance, 5.5, kTol);
  EXPECT_TRUE(row.world.castRayAny(ray));
  // Down through the row's gap onto the ground; and a ray that misses everything.
  const Ray down{{3, 0, 3}, {3, 0, -1}};
  expectHit(row.world.castRay(down), row.ground, down, 0.75, {0, 0, 1});
  const Ray miss{{0, 0, 2}, {10, 0, 2}};
  EXPECT_FALSE(row.world.castRay(miss));
  EXPECT_TRUE(row.world.castRayAll(miss).empty());
  EXPECT_FALSE(row.world.castRayAny(miss));
  // The cut-off: a ray that ends before the first body, and one that ends on it.
  EXPECT_FALSE(row.world.castRay({{0, 0, 1}, {1.49, 0, 1}}));
  EXPECT_FALSE(row.world.castRayAny({{0, 0, 1}, {1.49, 0, 1}}));
  const Ray onIt = Ray::along({0, 0, 1}, {1, 0, 0}, 1.5);
  expectHit(row.world.castRay(onIt), row.near, onIt, 1.0, {-1, 0, 0});
  EXPECT_EQ(row.world.castRayAll({{0, 0, 1}, {4, 0, 1}}).size(), 2u);
  // Degenerate rays hit nothing.
  EXPECT_FALSE(row.world.castRay({{0, 0, 1}, {0, 0, 1}}));
  EXPECT_FALSE(row.world.castRay({{0, 0, 1}, {NAN, 0, 1}}));
}

TEST(WorldRays, FiltersAndTheExcludedBody) {
  Row row;
  const Ray ray{{0, 0, 1}, {10, 0, 1}};
  RayFilter filter;
  filter.excluded = row.near;  // a sensor on the near box
  expectHit(row.world.castRay(ray, filter), row.middle, ray, 0.35, {-1, 0, 0});
  EXPECT_EQ(row.world.castRayAll(ray, filter).size(), 2u);
  // A ray of category 2 only meets bodies whose masks hold it: all do by
  // default; give the middle body a mask without it through a new world.
  World world;
  BodyDef def;
  def.name = "blind";
  def.shape = SphereShape{0.5};
  def.position = {4, 0, 1};
  def.collisionFilter = {1, ~2u};
  const BodyId blind = *world.createBody(def);
  def.name = "seen";
  def.position = {6, 0, 1};
  def.collisionFilter = {4, CollisionFilter::kAllBits};
  const BodyId seen = *world.createBody(def);
  RayFilter category2;
  category2.filter = {2, CollisionFilter::kAllBits};
  expectHit(world.castRay(ray, category2), seen, ray, 0.55, {-1, 0, 0});
  expectHit(world.castRay(ray), blind, ray, 0.35, {-1, 0, 0});
  // A ray whose mask leaves out group 1 sees only "seen" (group 4).
  RayFilter only4;
  only4.filter = {1, 4};
  EXPECT_EQ(world.castRayAll(ray, only4).size(), 1u);
  EXPECT_FALSE(world.castRayAny(ray, {{1, 8}, {}}));
  // An excluded id that is no longer valid is an error, as for body().
  ASSERT_TRUE(world.removeBody(blind));
  RayFilter stale;
  stale.excluded = blind;
  EXPECT_THROW(world.castRay(ray, stale), std::invalid_argument);
}

TEST(WorldRays, TiesGoToTheBodyCreatedFirst) {
  World world;
  const BodyId first = testing::addQueryBody(world, "first", BoxShape{Vec3::Constant(0.5)}, {2, 0, 0});
  testing::addQueryBody(world, "second", BoxShape{Vec3::Constant(0.5)}, {2, 0, 0.5});  // the same face plane x = 1.5
  const Ray ray{{0, 0, 0.25}, {4, 0, 0.25}};
  EXPECT_EQ(world.castRay(ray)->body, first);
  const auto all = world.castRayAll(ray);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].body, first);
}

TEST(WorldRays, SeesTheBodiesWhereTheyAreNow) {
  World world;
  const BodyId ball = testing::addQueryBody(world, "ball", SphereShape{0.5}, {0, 0, 10});
  const Ray down{{0, 0, 20}, {0, 0, 0}};
  EXPECT_NEAR(world.castRay(down)->point.z(), 10.5, kTol);
  // Falling for 0.5 s: the ray follows it after every step.
  for (int i = 0; i < 500; ++i) world.step();
  EXPECT_NEAR(world.castRay(down)->point.z(), world.body(ball).position().z() + 0.5, 1e-12);
  EXPECT_LT(world.body(ball).position().z(), 9.0);
  // Placed elsewhere between steps.
  RigidState state = world.body(ball).state();
  state.position = {0, 0, 3};
  ASSERT_TRUE(world.setBodyState(ball, state));
  EXPECT_NEAR(world.castRay(down)->point.z(), 3.5, kTol);
  // A body added, then removed; a frozen body is out of the simulation.
  const BodyId lid = testing::addQueryBody(world, "lid", BoxShape{Vec3(1, 1, 0.1)}, {0, 0, 15});
  EXPECT_EQ(world.castRay(down)->body, lid);
  ASSERT_TRUE(world.removeBody(lid));
  EXPECT_EQ(world.castRay(down)->body, ball);
  ASSERT_TRUE(world.freezeBody(ball));
  EXPECT_FALSE(world.castRay(down));
  // A copy answers for itself.
  World other;
  testing::addQueryBody(other, "x", SphereShape{1.0}, {0, 0, 5});
  World copy = other;
  EXPECT_NEAR(copy.castRay(down)->point.z(), 6.0, kTol);
  copy = world;
  EXPECT_FALSE(copy.castRay(down));
}

// A body moved by less than the ray tree's fat margin keeps its proxy where
// it was, yet the rays see it where it is now.
TEST(WorldRays, SmallMovesInsideTheFatBoxAreSeen) {
  World world;
  const BodyId box = testing::addQueryBody(world, "box", BoxShape{Vec3::Constant(0.5)}, {2, 0, 0});
  testing::addQueryBody(world, "other", SphereShape{0.5}, {0, 5, 0});
  const Ray ray{{0, 0, 0}, {4, 0, 0}};
  EXPECT_NEAR(world.castRay(ray)->point.x(), 1.5, kTol);
  for (const double x : {2.001, 1.997, 2.004}) {
    RigidState state = world.body(box).state();
    state.position.x() = x;
    ASSERT_TRUE(world.setBodyState(box, state));
    const auto hit = world.castRay(ray);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->point.x(), x - 0.5, kTol);
  }
}

// Random rays through the pile's bounds, from outside it.
std::vector<Ray> pileRays(int count, uint64_t seed) {
  scenes::SceneRandom random(seed);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const Vec3 from(random.uniform(-2, 2), random.uniform(-2, 2), random.uniform(0.05, 3));
    const Vec3 to(random.uniform(-2, 2), random.uniform(-2, 2), random.uniform(-0.5, 3));
    rays.push_back({from, to});
  }
  return rays;
}

bool sameBits(const std::optional<RayHit>& a, const std::optional<RayHit>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->body == b->body && a->part == b->part && a->piece == b->piece &&
         std::memcmp(&a->fraction, &b->fraction, sizeof(double)) == 0 &&
         std::memcmp(&a->distance, &b->distance, sizeof(double)) == 0 &&
         std::memcmp(a->point.data(), b->point.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a->normal.data(), b->normal.data(), 3 * sizeof(double)) == 0;
}

TEST(WorldRays, BatchEqualsSingleCastsBitForBitOnAnyThreads) {
  auto world = World::fromDef(scenes::makePileScene(1000, scenes::PileVariant::Dropped));
  ASSERT_TRUE(world);
  for (int i = 0; i < 50; ++i) world->step();  // the pile moving: boxes turned, tree refreshed
  const std::vector<Ray> rays = pileRays(5000, 0x5EED);
  std::vector<std::optional<RayHit>> single;
  for (const Ray& ray : rays) single.push_back(world->castRay(ray));
  int hits = 0;
  for (const auto& hit : single) hits += hit ? 1 : 0;
  EXPECT_GT(hits, 2500);
  for (const int threads : {1, 2, 3}) {
    ASSERT_TRUE(world->setThreads(threads));
    std::vector<std::optional<RayHit>> batch(rays.size());
    world->castRays(rays, batch);
    for (std::size_t i = 0; i < rays.size(); ++i)
      ASSERT_TRUE(sameBits(batch[i], single[i])) << "ray " << i << " on " << threads << " threads";
  }
  std::vector<std::optional<RayHit>> wrongSize(3);
  EXPECT_THROW(world->castRays(rays, wrongSize), std::invalid_argument);
}

// Queries from many threads at once, right after a step (so that the
// first of them brings the ray tree up to date while the others wait for
// it): single rays, batches (one borrows the world's pool, the others run
// on their callers) and shape casts, each answering as a copy of the world
// answers on one thread. Run under ThreadSanitizer by the README's test
// command (scripts/run_tests.sh), with the parallel step's tests.
TEST(WorldRays, ConcurrentQueriesFromManyThreads) {
  auto world = World::fromDef(scenes::makePileScene(300, scenes::PileVariant::Dropped));
  ASSERT_TRUE(world);
  ASSERT_TRUE(world->setThreads(2));
  const std::vector<Ray> rays = pileRays(600, 0x7EAD);
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 20; ++i) world->step();
    const World reference = *world;  // a copy: its own tree, built by one thread
    std::vector<std::optional<RayHit>> expected;
    std::vector<std::optional<ShapeCastHit>> expectedCasts;
    for (const Ray& ray : rays) {
      expected.push_back(reference.castRay(ray));
      expectedCasts.push_back(reference.castShape({SphereShape{0.03}, ray.from, ray.to, Quaternion::identity()}));
    }
    constexpr int kThreads = 4;
    std::vector<int> mismatches(kThreads, 0);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&, t] {
        if (t % 2 == 0) {
          std::vector<std::optional<RayHit>> batch(rays.size());
          world->castRays(rays, batch);
          for (std::size_t i = 0; i < rays.size(); ++i) mismatches[t] += sameBits(batch[i], expected[i]) ? 0 : 1;
        } else {
          for (std::size_t i = 0; i < rays.size(); ++i) {
            mismatches[t] += sameBits(world->castRay(rays[i]), expected[i]) ? 0 : 1;
            const auto cast = world->castShape({SphereShape{0.03}, rays[i].from, rays[i].to, Quaternion::identity()});
            const bool same = cast.has_value() == expectedCasts[i].has_value() &&
                              (!cast || (cast->body == expectedCasts[i]->body &&
                                         cast->fraction == expectedCasts[i]->fraction));
            mismatches[t] += same ? 0 : 1;
          }
        }
      });
    }
    for (std::thread& thread : threads) thread.join();
    for (int t = 0; t < kThreads; ++t) EXPECT_EQ(mismatches[t], 0) << "thread " << t << ", round " << round;
  }
}

// The answers are a function of the poses, not of the ray tree's history:
// a world queried after every step answers as its copy queried only once.
TEST(WorldRays, AnswersDoNotDependOnWhenTheTreeWasBuilt) {
  auto world = World::fromDef(scenes::makePileScene(300, scenes::PileVariant::Dropped));
  ASSERT_TRUE(world);
  World quiet = *world;
  const std::vector<Ray> rays = pileRays(500, 0xACE);
  for (int i = 0; i < 200; ++i) {
    world->step();
    quiet.step();
    (void)world->castRay(rays[static_cast<std::size_t>(i)]);
  }
  for (const Ray& ray : rays) ASSERT_TRUE(sameBits(world->castRay(ray), quiet.castRay(ray)));
}

// Against every body's exact shape one by one: the tree walk loses nothing.
TEST(WorldRays, TreeWalkAgreesWithTestingEveryBody) {
  auto world = World::fromDef(scenes::makePileScene(200, scenes::PileVariant::Dropped));
  ASSERT_TRUE(world);
  for (int i = 0; i < 100; ++i) world->step();
  int hits = 0;
  for (const Ray& ray : pileRays(2000, 0xF00D)) {
    const Vec3 delta = ray.to - ray.from;
    double nearest = std::numeric_limits<double>::infinity();
    std::vector<BodyId> bodiesHit;
    for (int i = 0; i < world->bodyCount(); ++i) {
      const BodyView body = world->bodyAt(i);
      const BodyDescription& description = body.description();
      RaySpan span;
      if (const auto* plane = std::get_if<PlaneShape>(&description.shape)) {
        span = halfSpaceSpan(plane->normal, plane->offset, ray.from, delta);  // the ground, at the origin
      } else {
        // The shape's frame in the world: body -> world after shape -> body.
        const Mat3 rotation = body.rotation() * description.shapeRotation;
        const Vec3 origin = body.position() + body.rotation() * description.shapeTranslation;
        span = boxSpan(std::get<BoxShape>(description.shape).halfExtents,
                       rotation.transpose() * (ray.from - origin), rotation.transpose() * delta);
      }
      if (const auto entry = firstEntry(span, 1.0)) {
        nearest = std::min(nearest, entry->fraction);
        bodiesHit.push_back(world->idOf(i));
      }
    }
    const auto closest = world->castRay(ray);
    ASSERT_EQ(closest.has_value(), std::isfinite(nearest));
    EXPECT_EQ(world->castRayAny(ray), std::isfinite(nearest));
    const std::vector<RayHit> all = world->castRayAll(ray);
    ASSERT_EQ(all.size(), bodiesHit.size());
    if (!closest) continue;
    ++hits;
    EXPECT_NEAR(closest->fraction, nearest, kTol);
    ASSERT_TRUE(sameBits(closest, all.front()));
    for (std::size_t k = 1; k < all.size(); ++k) EXPECT_LE(all[k - 1].fraction, all[k].fraction);
  }
  EXPECT_GT(hits, 400);
}

}  // namespace
}  // namespace rbsim
