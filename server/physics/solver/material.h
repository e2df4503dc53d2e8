#pragma once
// How the surface properties of two bodies combine at their contact.

#include <algorithm>
#include <cmath>

#include "rbsim/physics/material.h"

namespace rbsim {

// The pair's coefficients. Restitution: the larger of the two (a bouncy ball
// bounces on any floor, as in Box2D). Friction: the geometric mean, so that a
// frictionless surface is frictionless against anything and equal materials
// keep their own coefficient (Bullet multiplies instead; with μ = 0.5 on
// both bodies its pairs get 0.25, ours 0.5).
struct PairMaterial {
  double restitution = 0.0;
  double friction = 0.5;
  double staticFriction = 0.5;
};

inline PairMaterial combineMaterials(const Material& a, const Material& b) {
  return {std::max(a.restitution, b.restitution), std::sqrt(a.friction * b.friction),
          std::sqrt(a.staticCoefficient() * b.staticCoefficient())};
}

}  // namespace rbsim
