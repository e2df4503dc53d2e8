// Whole mechanisms in contact with the ground and each other.
//  - A ragdoll (15 bodies: ball joints with cones at the waist, neck,
//    shoulders and hips, hinges with limits at the elbows, wrists, knees
//    and ankles; the skeleton of bench/joints/joint_scenes.h) dropped on
//    the ground comes to rest (asleep) with no joint error above 1 cm —
//    here, above 1e-9 m or rad — on the way.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "joint/joint_test_worlds.h"
#include "joint_scenes.h"

namespace rbsim {
namespace {

namespace jb = bench::joints;
using testing::addJoint;
using testing::kGravity;

Vec3 vec(const jb::Vec3& v) { return {v[0], v[1], v[2]}; }

// The ground and one ragdoll upright 1 m up, leaning 0.4 rad so that it
// falls over; its bodies in `bodies`.
World makeRagdollWorld(std::vector<BodyId>& bodies) {
  WorldSettings settings;
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

TEST(JointScenes, ADroppedRagdollComesToRestWithItsJointsClosed) {
  std::vector<BodyId> bodies;
  World world = makeRagdollWorld(bodies);
  const double dt = world.settings().dt;
  double worstError = 0.0;
  int steps = 0;
  for (; steps < 8000 && world.sleepingBodyCount() < static_cast<int>(bodies.size()); ++steps) {
    world.step();
    for (int j = 0; j < world.jointCount(); ++j) worstError = std::max(worstError, world.jointStateAt(j).error);
  }
  double fastest = 0.0;
  for (const BodyId body : bodies) fastest = std::max(fastest, world.body(body).linearVelocity().norm());
  std::printf("ragdoll dropped from 1 m: asleep after %.2f s, largest joint error on the way %.1e m or rad, fastest body %.2e m/s\n",
              steps * dt, worstError, fastest);
  EXPECT_EQ(world.sleepingBodyCount(), static_cast<int>(bodies.size())) << "at rest within 8 s";
  EXPECT_LT(worstError, 1e-9);
  for (const BodyId body : bodies) EXPECT_GT(world.body(body).position().z(), 0.0) << "above the ground";
}

// The ragdoll, and beside it a wheel spun by a motor against friction, a
// servo arm on a drive, a lamp on a rope: every joint type, limit and
// actuator, in contact and in free flight.
World makeBusyJointedWorld() {
  std::vector<BodyId> bodies;
  World world = makeRagdollWorld(bodies);
  const BodyId wheel = testing::addBody(world, "wheel", CylinderShape{0.2, 0.05}, 2.0, Vec3(2, 0, 1));
  JointDef axle = testing::hinge("axle", BodyId{}, wheel, Vec3(2, 0, 1), Vec3(0, 1, 0));
  axle.motor = {true, 6.0, 0.4};
  axle.friction = 0.05;
  addJoint(world, axle);
  const BodyId arm = testing::addBody(world, "arm", BoxShape{Vec3(0.3, 0.03, 0.03)}, 1.0, Vec3(-1.7, 0, 1));
  JointDef servo = testing::hinge("servo", BodyId{}, arm, Vec3(-2, 0, 1), Vec3(0, 1, 0));
  servo.drive.enabled = true;
  servo.drive.target = -0.6;
  servo.drive.stiffness = 40.0;
  servo.drive.damping = 1.0;
  servo.damping = 0.02;
  addJoint(world, servo);
  const BodyId lamp = testing::addBody(world, "lamp", SphereShape{0.1}, 1.0, Vec3(0.5, 2, 1.5));
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

TEST(JointDeterminism, AJointedWorldRunTwiceIsBitIdentical) {
  World a = makeBusyJointedWorld(), b = makeBusyJointedWorld();
  for (int i = 0; i < 2000; ++i) {
    a.step();
    b.step();
    ASSERT_EQ(a.stateHash(), b.stateHash()) << "step " << i;
  }
  EXPECT_GT(a.contactPointCount(), 10) << "the ragdoll is on the ground";
}

TEST(JointDeterminism, GoldenHash) {
  World world = makeBusyJointedWorld();
  for (int i = 0; i < 2000; ++i) world.step();
  const uint64_t hash = world.stateHash();
  std::printf("golden: joints 0x%016llx\n", static_cast<unsigned long long>(hash));
  EXPECT_EQ(hash, 0x56d6a2ca68bd7ae9ull);
}

}  // namespace
}  // namespace rbsim
