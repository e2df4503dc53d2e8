#include "sensors/gaussian_noise.h"

#include <cmath>
#include <numbers>

namespace rbsim {

namespace {

uint64_t mix(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// In (0, 1]: the top 53 bits, offset by one so that log() never sees 0.
double unitInterval(uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 1.0) * 0x1.0p-53;
}

}  // namespace

double standardNormal(uint64_t seed, int64_t step, uint64_t component) {
  const uint64_t key = mix(mix(mix(seed) ^ static_cast<uint64_t>(step)) ^ component);
  const double u1 = unitInterval(mix(key));
  const double u2 = unitInterval(mix(key ^ 0x5851f42d4c957f2dULL));
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace rbsim
