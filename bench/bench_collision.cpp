// Collision detection cost: the broad phase alone, the whole pipeline
// (broad phase, narrow phase, manifolds) on a resting pile, and stepping the
// free-body scene with detection on.
//
// Scenes: random moving boxes (below); tests/scenes/pile_scene.h (settled
// variant: 10 × 10 columns of touching cubes on a ground plane);
// tests/scenes/free_bodies_scene.h (spinning cubes 0.5 m apart, no contacts).
// Counters: per_body (time per body per iteration, with an SI prefix: "85n"
// = 85 ns), pairs, manifolds, points.
//
//   taskset -c 1 build/bench/bench_collision --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "physics/collision/broad_phase.h"
#include "physics/world/contact_detection.h"
#include "rbsim/physics/world.h"
#include "scenes/free_bodies_scene.h"
#include "scenes/pile_scene.h"
#include "scenes/scene_random.h"
#include "support/body_copies.h"

namespace rbsim {
namespace {

void setPerBody(benchmark::State& state, int count) {
  state.counters["per_body"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * count,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// N boxes (half-extents 0.05–0.15 m) scattered in a cube holding one box per
// 0.064 m³ (0.4 m spacing on average, so the pair count grows like N), moving
// at up to 2 m/s in random directions with dt = 1 ms and bouncing off the
// cube's walls. A fifth are static.
struct MovingBoxes {
  std::vector<BroadPhaseBody> bodies;
  std::vector<Vec3> centers;
  std::vector<Vec3> halves;
  std::vector<Vec3> steps;  // m per update
  double side = 0.0;        // m

  explicit MovingBoxes(int count) : side(0.4 * std::cbrt(static_cast<double>(count))) {
    scenes::SceneRandom random(0xB0B5u);
    for (int i = 0; i < count; ++i) {
      BroadPhaseBody body;
      body.serial = i + 1;
      body.index = i;
      body.isStatic = random.uniform(0, 1) < 0.2;
      centers.emplace_back(random.uniform(0, side), random.uniform(0, side),
                           random.uniform(0, side));
      halves.emplace_back(random.uniform(0.05, 0.15), random.uniform(0.05, 0.15),
                          random.uniform(0.05, 0.15));
      const Vec3 velocity(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
      steps.push_back(body.isStatic ? Vec3::Zero() : Vec3(velocity * 2.0 / std::sqrt(3.0) * 1e-3));
      body.box = Aabb{centers.back() - halves.back(), centers.back() + halves.back()};
      bodies.push_back(body);
    }
  }

  void move() {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        const double next = centers[i][axis] + steps[i][axis];
        if (next < 0.0 || next > side) steps[i][axis] = -steps[i][axis];
      }
      centers[i] += steps[i];
      bodies[i].box = Aabb{centers[i] - halves[i], centers[i] + halves[i]};
    }
  }
};

void BM_BroadPhase_MovingBoxes(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  MovingBoxes scene(count);
  BroadPhase broadPhase(0.05, 0.005);
  broadPhase.update(scene.bodies);
  double pairs = 0.0;
  double moved = 0.0;
  for (auto _ : state) {
    scene.move();
    broadPhase.update(scene.bodies);
    pairs += static_cast<double>(broadPhase.pairs().size());
    moved += broadPhase.movedProxyCount();
  }
  setPerBody(state, count);
  state.counters["pairs"] = pairs / static_cast<double>(state.iterations());
  state.counters["moved"] = moved / static_cast<double>(state.iterations());
}

// The same bodies, none moving: the cost of a resting scene (pairs are
// still re-checked against the tight boxes).
void BM_BroadPhase_RestingBoxes(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  MovingBoxes scene(count);
  BroadPhase broadPhase(0.05, 0.005);
  for (auto _ : state) {
    broadPhase.update(scene.bodies);
    benchmark::DoNotOptimize(broadPhase.pairs().data());
  }
  setPerBody(state, count);
}

void BM_Collision_SettledPile(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  auto world = World::fromDef(scenes::makePileScene(count, scenes::PileVariant::Settled));
  if (!world) {
    state.SkipWithError(world.error().message.c_str());
    return;
  }
  CollisionDetector detector;
  // The world's bodies as the detector takes them (a World hands out none).
  const testing::BodyCopies copies(*world);
  for (auto _ : state) {
    detectContacts(detector, copies.bodies(), world->settings());
    benchmark::DoNotOptimize(detector.contacts().data());
  }
  setPerBody(state, count);
  state.counters["pairs"] = static_cast<double>(detector.broadPhase().pairs().size());
  state.counters["manifolds"] = static_cast<double>(detector.contacts().size());
  state.counters["points"] = detector.contactPointCount();
}

// The free-body scene stepped with the world's own contact pipeline off, so
// that step() only integrates; `detect` adds our detection after each step.
void stepFreeBodies(benchmark::State& state, bool detect) {
  const int count = static_cast<int>(state.range(0));
  WorldDef def = scenes::makeFreeBodiesScene(count, IntegratorKind::SemiImplicitEuler);
  def.settings.contact.enabled = false;
  auto world = World::fromDef(def);
  if (!world) {
    state.SkipWithError(world.error().message.c_str());
    return;
  }
  CollisionDetector detector;
  testing::BodyCopies copies(*world);
  for (auto _ : state) {
    world->step();
    if (detect) {
      // Bringing the copies of the bodies up to the step (a World hands out
      // none of its own) is not part of what is measured.
      state.PauseTiming();
      copies.update(*world);
      state.ResumeTiming();
      detectContacts(detector, copies.bodies(), world->settings());
    }
    benchmark::DoNotOptimize(detector.contacts().data());
  }
  setPerBody(state, count);
  state.counters["manifolds"] = static_cast<double>(detector.contacts().size());
}

void BM_FreeBodies_StepAndDetect(benchmark::State& state) {
  stepFreeBodies(state, true);
}
// The baseline: integration alone.
void BM_FreeBodies_StepOnly(benchmark::State& state) {
  stepFreeBodies(state, false);
}

BENCHMARK(BM_BroadPhase_MovingBoxes)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(4000)
    ->Arg(10000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BroadPhase_RestingBoxes)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(4000)
    ->Arg(10000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Collision_SettledPile)->Arg(100)->Arg(1000)->Arg(4000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FreeBodies_StepAndDetect)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FreeBodies_StepOnly)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rbsim

BENCHMARK_MAIN();
