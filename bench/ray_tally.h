#pragma once
// What the query benchmarks (bench_rays.cpp, bench_trimesh.cpp) share: cast
// every ray of a set in the benchmark's loop and tally the hits, then
// report rays per second, the share that hit and their mean distance, so
// that two engines can be seen to answer alike.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "rbsim/physics/ray_cast.h"

namespace rbsim::bench {

struct RayTally {
  int hits = 0;
  double distance = 0.0;  // m, summed over the hits
};

// `cast(ray)` gives the hit's distance (m), or nothing for a miss. The
// tally is the last pass's.
template <class Cast>
RayTally castEveryRay(benchmark::State& state, const std::vector<Ray>& rays, Cast&& cast) {
  RayTally tally;
  for (auto _ : state) {
    tally = {};
    for (const Ray& ray : rays) {
      if (const std::optional<double> distance = cast(ray)) {
        ++tally.hits;
        tally.distance += *distance;
      }
    }
    benchmark::DoNotOptimize(tally.distance);
  }
  return tally;
}

// items_per_second (rays), hit_share and mean_distance (m).
inline void reportTally(benchmark::State& state, const RayTally& tally, std::size_t rays) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(rays));
  state.counters["hit_share"] = static_cast<double>(tally.hits) / static_cast<double>(rays);
  state.counters["mean_distance"] = tally.hits > 0 ? tally.distance / tally.hits : 0.0;
}

}  // namespace rbsim::bench
