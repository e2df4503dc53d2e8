// Mass properties of a union of solids (a compound body), from its parts'.
#include <cassert>

#include "rbsim/physics/mass_properties.h"

namespace rbsim {

MassProperties combinedMassProperties(std::span<const PlacedMassProperties> parts) {
  assert(!parts.empty());
  MassProperties total;
  Vec3 firstMoment = Vec3::Zero();  // Σ m c, kg·m
  for (const PlacedMassProperties& part : parts) {
    total.mass += part.properties.mass;
    total.volume += part.properties.volume;
    firstMoment += part.properties.mass * part.placement.apply(part.properties.centerOfMass);
  }
  total.centerOfMass = firstMoment / total.mass;
  for (const PlacedMassProperties& part : parts) {
    const Mat3& rotation = part.placement.rotation;
    // A tensor turns with its frame: I' = R I Rᵀ (still about the part's own
    // centre of mass), then moves to the common one.
    const Mat3 rotated = rotation * part.properties.inertia * rotation.transpose();
    const Vec3 offset = part.placement.apply(part.properties.centerOfMass) - total.centerOfMass;
    total.inertia += shiftInertia(rotated, part.properties.mass, offset);
  }
  // Round-off leaves the sum of symmetric tensors a hair asymmetric when the
  // rotations are not exact; the principal axes want it symmetric.
  total.inertia = 0.5 * (total.inertia + total.inertia.transpose()).eval();
  return total;
}

}  // namespace rbsim
