#pragma once
// Small worlds for the contact-response tests.

#include <cmath>
#include <string>

#include "rbsim/physics/world.h"

namespace rbsim::testing {

// The contact solver the contact tests run with: test_contact_response
// compiles them with the default, test_contact_response_soft_step with
// RBSIM_TEST_SOFT_STEP defined, so that every contact test holds for both.
inline constexpr ContactSolverKind kTestContactSolver =
#ifdef RBSIM_TEST_SOFT_STEP
    ContactSolverKind::SoftStep;
#else
    ContactSolverKind::SequentialImpulses;
#endif

inline WorldSettings contactSettings(double restitution, double friction) {
  WorldSettings settings;
  settings.dt = 1e-3;
  settings.contact.solver.kind = kTestContactSolver;
  settings.contact.defaultMaterial.restitution = restitution;
  settings.contact.defaultMaterial.friction = friction;
  settings.contact.defaultMaterial.staticFriction = friction;
  return settings;
}

// A static half-space whose surface passes through the origin with the given
// outward normal (z = 0 for the default).
inline BodyId addGround(World& world, const Vec3& normal = Vec3::UnitZ()) {
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{normal.normalized(), 0.0};
  ground.isStatic = true;
  return *world.createBody(ground);
}

inline BodyId addSphere(World& world, const std::string& name, double radius, const Vec3& position,
                        const Vec3& velocity = Vec3::Zero()) {
  BodyDef def;
  def.name = name;
  def.shape = SphereShape{radius};
  def.position = position;
  def.linearVelocity = velocity;
  return *world.createBody(def);
}

inline BodyId addBox(World& world, const std::string& name, const Vec3& halfExtents,
                     const Vec3& position, const Quaternion& orientation = Quaternion::identity(),
                     const Vec3& velocity = Vec3::Zero()) {
  BodyDef def;
  def.name = name;
  def.shape = BoxShape{halfExtents};
  def.position = position;
  def.orientation = orientation;
  def.linearVelocity = velocity;
  return *world.createBody(def);
}

// Deepest penetration over the last step's contacts (m; 0 without contact).
inline double deepestContact(const World& world) {
  double deepest = 0.0;
  for (const SolvedManifold& m : world.contacts())
    for (int p = 0; p < m.pointCount; ++p) deepest = std::max(deepest, m.points[p].depth);
  return deepest;
}

}  // namespace rbsim::testing
