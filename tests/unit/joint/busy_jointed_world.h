#pragma once
// Jointed worlds shared by the joint tests and the parallel step's tests:
// a ragdoll on the ground, and a busy world with every joint type, limit
// and actuator, in contact and in free flight.

#include <vector>

#include "joint/joint_test_worlds.h"
#include "joint_scenes.h"
#include "rbsim/physics/world.h"

namespace rbsim::testing {

namespace jb = bench::joints;

inline Vec3 vec(const jb::Vec3& v) { return {v[0], v[1], v[2]}; }

// The ground and one ragdoll upright 1 m up, leaning 0.4 rad so that it
// falls over; its bodies in `bodies`.
inline World makeRagdollWorld(std::vector<BodyId>& bodies,
                              ContactSolverKind solver = ContactSolverKind::SequentialImpulses) {
  WorldSettings settings;
  settings.contact.solver.kind = solver;
  settings.dt = 1e-3;
  settings.gravity = Vec3(0, 0, -kGravity);
  settings.contact.defaultMaterial.friction = 0.5;
  settings.contact.defaultMaterial.restitution = 0.0;
  World world(settings);
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  EXPECT_TRUE(world.createBody(ground).ok());
  jb::Scene scene;
  jb::addRagdoll(scene, {0, 0, 1.0}, jb::axisAngle({1, 0.3, 0}, 0.4));
  bodies.clear();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const jb::BodySpec& spec = scene.bodies[i];
    BodyDef def;
    def.name = jb::kRagdollParts[i].name;
    if (spec.shape == jb::ShapeKind::kSphere) def.shape = SphereShape{spec.radius};
    else def.shape = BoxShape{vec(spec.halfExtents)};
    def.mass = spec.mass;
    def.position = vec(spec.pose.position);
    const jb::Quat& q = spec.pose.orientation;
    def.orientation = Quaternion{q[0], q[1], q[2], q[3]};
    const Expected<BodyId> id = world.createBody(def);
    EXPECT_TRUE(id.ok()) << id.error().message;
    bodies.push_back(id.ok() ? *id : BodyId{});
  }
  for (std::size_t j = 0; j < scene.joints.size(); ++j) {
    const jb::JointSpec& spec = scene.joints[j];
    JointDef def;
    def.name = jb::kRagdollJoints[j].name;
    def.type = spec.kind == jb::JointKind::kHinge ? JointType::Revolute : JointType::Spherical;
    def.bodyA = bodies[static_cast<std::size_t>(spec.bodyA)];
    def.bodyB = bodies[static_cast<std::size_t>(spec.bodyB)];
    def.anchor = vec(spec.anchor);
    def.axis = vec(spec.axis);
    if (spec.kind == jb::JointKind::kHinge) def.limit = {true, spec.lower, spec.upper};
    else def.coneAngle = spec.swing;
    addJoint(world, def);
  }
  return world;
}

// The ragdoll, and beside it a wheel spun by a motor against friction, a
// servo arm on a drive, a lamp on a rope: every joint type, limit and
// actuator, in contact and in free flight.
inline World makeBusyJointedWorld(ContactSolverKind solver = ContactSolverKind::SequentialImpulses) {
  std::vector<BodyId> bodies;
  World world = makeRagdollWorld(bodies, solver);
  const BodyId wheel = addBody(world, "wheel", CylinderShape{0.2, 0.05}, 2.0, Vec3(2, 0, 1));
  JointDef axle = hinge("axle", BodyId{}, wheel, Vec3(2, 0, 1), Vec3(0, 1, 0));
  axle.motor = {true, 6.0, 0.4};
  axle.friction = 0.05;
  addJoint(world, axle);
  const BodyId arm = addBody(world, "arm", BoxShape{Vec3(0.3, 0.03, 0.03)}, 1.0, Vec3(-1.7, 0, 1));
  JointDef servo = hinge("servo", BodyId{}, arm, Vec3(-2, 0, 1), Vec3(0, 1, 0));
  servo.drive.enabled = true;
  servo.drive.target = -0.6;
  servo.drive.stiffness = 40.0;
  servo.drive.damping = 1.0;
  servo.damping = 0.02;
  addJoint(world, servo);
  const BodyId lamp = addBody(world, "lamp", SphereShape{0.1}, 1.0, Vec3(0.5, 2, 1.5));
  JointDef rope;
  rope.name = "rope";
  rope.type = JointType::Distance;
  rope.bodyB = lamp;
  rope.anchor = Vec3(0, 2, 2);
  rope.anchorB = Vec3(0.5, 2, 1.5);
  rope.limit = {true, 0.0, 0.9};
  addJoint(world, rope);
  return world;
}

}  // namespace rbsim::testing
