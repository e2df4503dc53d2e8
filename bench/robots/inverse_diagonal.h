#pragma once
// The diagonal of M⁻¹ for a symmetric positive definite n × n matrix M
// (row-major): each joint's effective inertia for the PD gains of both
// robot benchmarks. Gauss–Jordan on [M | I], no pivoting needed.

#include <cstddef>
#include <vector>

inline std::vector<double> inverseDiagonal(std::vector<double> m, std::size_t n) {
  std::vector<double> inverse(n * n, 0.0);
  for (std::size_t k = 0; k < n; ++k) inverse[k * n + k] = 1;
  for (std::size_t c = 0; c < n; ++c) {
    const double pivot = m[c * n + c];
    for (std::size_t j = 0; j < n; ++j) {
      m[c * n + j] /= pivot;
      inverse[c * n + j] /= pivot;
    }
    for (std::size_t r = 0; r < n; ++r) {
      if (r == c) continue;
      const double factor = m[r * n + c];
      for (std::size_t j = 0; j < n; ++j) {
        m[r * n + j] -= factor * m[c * n + j];
        inverse[r * n + j] -= factor * inverse[c * n + j];
      }
    }
  }
  std::vector<double> diagonal(n);
  for (std::size_t k = 0; k < n; ++k) diagonal[k] = inverse[k * n + k];
  return diagonal;
}
