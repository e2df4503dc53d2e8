#pragma once
// Gaussian noise that is a pure function of (seed, step, component): the
// same reading gets the same noise in every run, after a RESET, a
// checkpoint restored or a replay, on any number of threads, without any
// generator state to save. A counter-based generator (Salmon et al.,
// "Parallel random numbers: as easy as 1, 2, 3", SC 2011, make the case):
// the counter is hashed with SplitMix64's finaliser (Steele, Lea and Flood,
// "Fast splittable pseudorandom number generators", OOPSLA 2014) into two
// uniform numbers, made Gaussian by the Box–Muller transform.

#include <cstdint>

namespace rbsim {

// A standard normal number for the component `component` of the reading
// taken after step `step` by a sensor seeded with `seed`.
double standardNormal(uint64_t seed, int64_t step, uint64_t component);

}  // namespace rbsim
