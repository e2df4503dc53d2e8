#pragma once
// Surface properties of a body: restitution and Coulomb friction.

#include <optional>

namespace rbsim {

struct Material {
  double restitution = 0.0;    // e in [0, 1]: 0 = no bounce, 1 = lossless
  double friction = 0.5;       // kinetic Coulomb coefficient μk (non-dimensional)
  double staticFriction = -1;  // μs >= μk; < 0 means "same as friction"

  double staticCoefficient() const { return staticFriction < 0.0 ? friction : staticFriction; }
};

// What a body's `material:` says; unset fields take the world's defaults.
struct MaterialSpec {
  std::optional<double> restitution;
  std::optional<double> friction;
  std::optional<double> staticFriction;
};

inline Material resolveMaterial(const MaterialSpec& spec, const Material& defaults) {
  Material m;
  m.restitution = spec.restitution.value_or(defaults.restitution);
  m.friction = spec.friction.value_or(defaults.friction);
  // μs follows μk when only μk is given, so "friction: 0.2" alone means 0.2 for both.
  m.staticFriction = spec.staticFriction ? *spec.staticFriction
                     : spec.friction     ? *spec.friction
                                         : defaults.staticCoefficient();
  return m;
}

}  // namespace rbsim
