#pragma once
// How rbsim builds the world of a joint scene (joint_scenes.h): its
// settings, ground, bodies and joints. Shared by the benchmark's rbsim
// adapter (rbsim_joints.cpp) and the tests that step the same scenes
// (tests/unit/joint/test_joint_allocations.cpp), so both measure one world.
//
// Joints are solved at the position level (docs/joints_design.md): ball
// joints are JointType::Spherical, hinges JointType::Revolute with the
// scene's limits. The scene's iteration count is the contact solver's
// velocity iterations; the joints are solved exactly whatever it is. No
// sleeping (as the peers here: every engine simulates every body for the
// whole run). Ball joints with a swing limit take it as their cone
// (JointDef::coneAngle); twist ranges are not supported yet.

#include <string>
#include <vector>

#include "joint_scenes.h"
#include "rbsim/physics/world.h"

namespace rbsim::bench::joints {

inline rbsim::Vec3 toVec3(const Vec3& v) {
  return {v[0], v[1], v[2]};
}

inline WorldSettings sceneWorldSettings(const Scene& s) {
  WorldSettings settings;
  settings.dt = s.dt;
  settings.gravity = toVec3(s.gravity);
  settings.contact.enabled = s.contacts;
  settings.contact.sleeping = false;
  settings.contact.solver.velocityIterations = s.velocityIterations;
  settings.contact.defaultMaterial.friction = kFriction;
  settings.contact.defaultMaterial.staticFriction = kFriction;
  settings.contact.defaultMaterial.restitution = 0.0;
  return settings;
}

// The ground plane of a scene that has one (Scene::ground).
inline BodyDef sceneGround() {
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  return ground;
}

// The scene's body number `index`.
inline BodyDef sceneBody(const BodySpec& b, std::size_t index) {
  BodyDef def;
  def.name = "body" + std::to_string(index);
  if (b.shape == ShapeKind::kSphere) def.shape = SphereShape{b.radius};
  else def.shape = BoxShape{toVec3(b.halfExtents)};
  def.mass = b.mass;
  def.position = toVec3(b.pose.position);
  def.orientation = {b.pose.orientation[0], b.pose.orientation[1], b.pose.orientation[2], b.pose.orientation[3]};
  return def;
}

// The scene's joint number `index`, between bodies created in the scene's order.
inline JointDef sceneJoint(const JointSpec& j, const std::vector<BodyId>& bodies, int index) {
  JointDef def;
  def.name = "joint" + std::to_string(index);
  def.type = j.kind == JointKind::kHinge ? JointType::Revolute : JointType::Spherical;
  def.bodyA = bodies[static_cast<std::size_t>(j.bodyA)];
  def.bodyB = j.bodyB == kWorld ? BodyId{} : bodies[static_cast<std::size_t>(j.bodyB)];
  def.anchor = toVec3(j.anchor);
  def.axis = toVec3(j.axis);
  // The scene's hinge limits are B's rotation relative to A about the
  // axis, zero at the build pose: rbsim's joint coordinate exactly.
  if (j.kind == JointKind::kHinge && j.limited) def.limit = {true, j.lower, j.upper};
  if (j.kind == JointKind::kBall && j.limited && j.swing > 0) def.coneAngle = j.swing;
  return def;
}

}  // namespace rbsim::bench::joints
