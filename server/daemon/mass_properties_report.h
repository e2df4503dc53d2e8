#pragma once
// `rbserver --mass-properties`: the mass properties of every body as JSON.

#include <string>

#include "rbsim/physics/world.h"

namespace rbsim {

// For every body, in creation order: name, source ("given" when the config
// gave mass, center_of_mass and inertia, "shape" when computed from the
// shape, "static" for an immovable body), mass (kg), volume (m³, the shape's),
// center_of_mass (m) and inertia (kg·m², 3×3 about the centre of mass), both
// in the frame the shape was given in, principal_moments (ascending) and
// principal_axes (a list of three unit vectors in that frame, one per moment).
// Static bodies (a plane, a robot's fixed base) have no finite mass: they
// report mass, centre of mass, inertia and moments 0, as world_t does, and
// their shape's volume.
std::string massPropertiesJson(const World& world);

}  // namespace rbsim
