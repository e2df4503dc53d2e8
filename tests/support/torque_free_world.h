#pragma once
// A world with nothing in it but one body: no gravity, no ground, the
// integrator and step asked for. The setting of the torque-free tests
// (conservation of L and E, the intermediate-axis flip, nutation drift).

#include <gtest/gtest.h>

#include "rbsim/physics/world.h"

namespace rbsim::testing {

inline WorldSettings torqueFreeSettings(IntegratorKind integrator, double dt) {
  WorldSettings settings;
  settings.dt = dt;
  settings.gravity = Vec3::Zero();
  settings.integrator = integrator;
  return settings;
}

inline World torqueFreeWorld(const BodyDef& body, IntegratorKind integrator, double dt) {
  World world(torqueFreeSettings(integrator, dt));
  const auto created = world.createBody(body);
  EXPECT_TRUE(created.ok()) << created.error().message;
  return world;
}

}  // namespace rbsim::testing
