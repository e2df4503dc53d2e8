#pragma once
// Deterministic random numbers for scene builders (tests and benchmarks).
// splitmix64, because std:: distributions may differ between standard
// libraries and a scene must be the same everywhere.

#include <cmath>
#include <cstdint>
#include <numbers>

#include "rbsim/physics/quaternion.h"

namespace rbsim::scenes {

class SceneRandom {
 public:
  explicit SceneRandom(uint64_t seed) : m_state(seed) {}

  uint64_t next() {
    uint64_t z = (m_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [a, b) from the top 53 bits.
  double uniform(double a, double b) {
    return a + (b - a) * (static_cast<double>(next() >> 11) * 0x1.0p-53);
  }
  // Uniformly distributed rotation (Shoemake, "Uniform random rotations", 1992).
  Quaternion rotation() {
    const double u1 = uniform(0, 1), u2 = uniform(0, 1), u3 = uniform(0, 1);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    constexpr double kTwoPi = 2 * std::numbers::pi;
    return Quaternion{a * std::sin(kTwoPi * u2), a * std::cos(kTwoPi * u2),
                      b * std::sin(kTwoPi * u3), b * std::cos(kTwoPi * u3)}
        .normalized();
  }

 private:
  uint64_t m_state;
};

}  // namespace rbsim::scenes
