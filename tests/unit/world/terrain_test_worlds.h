#pragma once
// What the trimesh and heightfield world tests share: a world of one
// contact solver, and the analytic plane their terrains are held against.

#include "unit/solver/contact_test_worlds.h"

namespace rbsim::testing {

inline WorldSettings terrainSettings(ContactSolverKind kind, double restitution, double friction) {
  WorldSettings settings = contactSettings(restitution, friction);
  settings.contact.solver.kind = kind;
  return settings;
}

// A static ground plane (z up, turned by `orientation`).
inline BodyId addGroundPlane(World& world, const Quaternion& orientation = Quaternion::identity()) {
  BodyDef def;
  def.name = "ground";
  def.shape = PlaneShape{};
  def.isStatic = true;
  def.orientation = orientation;
  return *world.createBody(def);
}

}  // namespace rbsim::testing
