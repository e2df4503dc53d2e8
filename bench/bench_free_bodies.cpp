// Free-body stepping cost: the foundation issue's benchmark.
//
// Scene: tests/scenes/free_bodies_scene.h (N cubes, random spins, no gravity,
// no contacts, dt = 1 ms). Reported: time per World::step() and, as a
// counter, nanoseconds per body-step. Reference figures (Bullet 3.24, ODE
// 0.16) come from the anchors harness (bench/anchors/ours.cpp), run in the
// same session.
//
//   taskset -c 1 build/bench/bench_free_bodies --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "rbsim/physics/world.h"
#include "scenes/free_bodies_scene.h"

namespace rbsim {
namespace {

void stepFreeBodies(benchmark::State& state, IntegratorKind integrator) {
  const int count = static_cast<int>(state.range(0));
  auto world = World::fromDef(scenes::makeFreeBodiesScene(count, integrator));
  if (!world) {
    state.SkipWithError(world.error().message.c_str());
    return;
  }
  for (auto _ : state) {
    world->step();
    benchmark::ClobberMemory();
  }
  // Seconds per body-step, printed with an SI prefix (e.g. "85n" = 85 ns).
  state.counters["per_body_step"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * count,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_FreeBodies_SemiImplicitEuler(benchmark::State& state) {
  stepFreeBodies(state, IntegratorKind::SemiImplicitEuler);
}
void BM_FreeBodies_Rk4(benchmark::State& state) { stepFreeBodies(state, IntegratorKind::Rk4); }
void BM_FreeBodies_ExplicitEuler(benchmark::State& state) {
  stepFreeBodies(state, IntegratorKind::ExplicitEuler);
}

BENCHMARK(BM_FreeBodies_SemiImplicitEuler)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FreeBodies_Rk4)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FreeBodies_ExplicitEuler)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rbsim

BENCHMARK_MAIN();
