// The `joints:` list of a world file: a joint per type read as written,
// the example world builds and steps, and every mistake reported at its
// file:line:column and key.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "config/config_loader.h"
#include "rbsim/physics/world.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

const std::string kBodies =
    "bodies:\n"
    "  - {name: base, shape: {type: box, half_extents: [0.1, 0.1, 0.1]}, static: true}\n"
    "  - {name: arm, shape: {type: sphere, radius: 0.05}, mass: 1, position: [0.5, 0, 0]}\n"
    "  - {name: tip, shape: {type: sphere, radius: 0.05}, mass: 1, position: [1.0, 0, 0]}\n";

std::string errorOf(const std::string& joints) {
  const Expected<WorldDef> world = parseWorldConfig(kBodies + "joints:\n" + joints, "j.yaml", "");
  if (world.ok()) {
    ADD_FAILURE() << "accepted:\n" << joints;
    return "";
  }
  return world.error().message;
}

TEST(JointConfig, JointsAreReadAsWrittenAndTheWorldStepsThem) {
  const Expected<WorldDef> def = parseWorldConfig(
      kBodies +
          "joints:\n"
          "  - name: shoulder\n"
          "    type: revolute\n"
          "    body_a: world\n"
          "    body_b: arm\n"
          "    anchor: [0, 0, 0]\n"
          "    axis: [0, 2, 0]\n"
          "    limits: {lower: -1, upper: 1.5}\n"
          "    motor: {max_effort: 3, target_rate: 0.5}\n"
          "  - {name: rod, type: distance, body_a: arm, body_b: tip, anchor: [0.5, 0, 0], anchor_b: [1, 0, 0]}\n",
      "j.yaml", "");
  ASSERT_TRUE(def.ok()) << def.error().message;
  ASSERT_EQ(def->joints.size(), 2u);
  const NamedJointDef& shoulder = def->joints[0];
  EXPECT_EQ(shoulder.def.type, JointType::Revolute);
  EXPECT_EQ(shoulder.bodyA, "world");
  EXPECT_EQ(shoulder.bodyB, "arm");
  EXPECT_EQ(shoulder.def.axis, Vec3(0, 1, 0));
  EXPECT_TRUE(shoulder.def.limit.enabled);
  EXPECT_EQ(shoulder.def.limit.upper, 1.5);
  EXPECT_EQ(shoulder.def.motor.maxEffort, 3.0);
  EXPECT_EQ(shoulder.def.motor.targetRate, 0.5);
  EXPECT_NE(shoulder.source.find("j.yaml:6:5: joints[0]"), std::string::npos) << shoulder.source;
  EXPECT_DOUBLE_EQ(def->joints[1].def.length, 0.5);
  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_EQ(world->jointCount(), 2);
  for (int k = 0; k < 100; ++k) world->step();
  EXPECT_LT(world->jointState(world->findJoint("rod")).error, 1e-9);
}

TEST(JointConfig, DrivesDampingAndFrictionAreReadAsWritten) {
  const Expected<WorldDef> def = parseWorldConfig(
      kBodies +
          "joints:\n"
          "  - {name: servo, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0],\n"
          "     drive: {target: 0.3, stiffness: 200, damping: 20, max_effort: 50, gravity_compensation: true},\n"
          "     damping: 0.1, friction: 0.2}\n"
          "  - {name: soft, type: prismatic, body_a: arm, body_b: tip, anchor: [1, 0, 0], axis: [1, 0, 0],\n"
          "     drive: {frequency: 2, damping_ratio: 0.7}}\n",
      "j.yaml", "");
  ASSERT_TRUE(def.ok()) << def.error().message;
  const JointDef& servo = def->joints[0].def;
  EXPECT_TRUE(servo.drive.enabled);
  EXPECT_EQ(servo.drive.target, 0.3);
  EXPECT_EQ(servo.drive.stiffness, 200.0);
  EXPECT_EQ(servo.drive.damping, 20.0);
  EXPECT_EQ(servo.drive.maxEffort, 50.0);
  EXPECT_EQ(servo.drive.frequency, 0.0);
  EXPECT_TRUE(servo.drive.gravityCompensation);
  EXPECT_EQ(servo.damping, 0.1);
  EXPECT_EQ(servo.friction, 0.2);
  const JointDef& soft = def->joints[1].def;
  EXPECT_EQ(soft.drive.frequency, 2.0);
  EXPECT_EQ(soft.drive.dampingRatio, 0.7);
  EXPECT_EQ(soft.drive.target, 0.0);
  EXPECT_TRUE(std::isinf(soft.drive.maxEffort)) << "no cap unless given";
  EXPECT_FALSE(soft.drive.gravityCompensation) << "off unless asked for";
  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;
}

TEST(JointConfig, RopesAndConesAreReadAsWritten) {
  const Expected<WorldDef> def = parseWorldConfig(
      kBodies +
          "joints:\n"
          "  - {name: hip, type: spherical, body_a: base, body_b: arm, anchor: [0, 0, 0], axis: [1, 0, 0],\n"
          "     cone_limit: 0.7}\n"
          "  - {name: rope, type: distance, body_a: arm, body_b: tip, anchor: [0.5, 0, 0], anchor_b: [1, 0, 0],\n"
          "     limits: {lower: 0.2, upper: 0.8}}\n",
      "j.yaml", "");
  ASSERT_TRUE(def.ok()) << def.error().message;
  EXPECT_EQ(def->joints[0].def.coneAngle, 0.7);
  EXPECT_EQ(def->joints[0].def.axis, Vec3(1, 0, 0));
  EXPECT_TRUE(def->joints[1].def.limit.enabled);
  EXPECT_EQ(def->joints[1].def.limit.lower, 0.2);
  EXPECT_EQ(def->joints[1].def.limit.upper, 0.8);
  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  const std::string base = "  - {name: j, type: spherical, body_a: world, body_b: arm, anchor: [0, 0, 0]";
  EXPECT_NE(errorOf(base + ", axis: [1, 0, 0]}\n").find("takes an axis only with cone_limit"), std::string::npos);
  EXPECT_NE(errorOf(base + ", cone_limit: 0.5}\n").find("joints[0].axis: missing required key"), std::string::npos);
  EXPECT_NE(errorOf(base + ", axis: [1, 0, 0], cone_limit: 3.5}\n").find("joints[0].cone_limit"), std::string::npos);
  EXPECT_NE(errorOf("  - {name: j, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0], "
                    "cone_limit: 1}\n")
                .find("only spherical joints take cone_limit"),
            std::string::npos);
  const std::string rod = "  - {name: j, type: distance, body_a: world, body_b: arm, anchor: [0, 0, 0], anchor_b: [0.5, 0, 0]";
  EXPECT_NE(errorOf(rod + ", length: 1, limits: {lower: 0, upper: 1}}\n").find("not both"), std::string::npos);
  EXPECT_NE(errorOf(rod + ", limits: {lower: -1, upper: 1}}\n").find("joints[0].limits.lower"), std::string::npos);
  EXPECT_NE(errorOf(rod + ", limits: {lower: 0, upper: 0}}\n").find("a rope's upper length must be positive"),
            std::string::npos);
}

TEST(JointConfig, TheExampleWorldLoadsAndItsJointsHold) {
  const Expected<WorldDef> def = loadWorldConfig(std::string(rbsim::test_support::kTestDataDir) + "/../../config/worlds/joints.yaml");
  ASSERT_TRUE(def.ok()) << def.error().message;
  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_EQ(world->jointCount(), 11);
  for (int k = 0; k < 2000; ++k) world->step();
  for (int j = 0; j < world->jointCount(); ++j) EXPECT_LT(world->jointStateAt(j).error, 1e-6) << world->jointStateAt(j).name;
  EXPECT_NEAR(world->jointState(world->findJoint("axle")).rate, 5.0, 1e-9) << "the motor reached its target";
  EXPECT_NEAR(world->jointState(world->findJoint("lift")).position, -0.5, 1e-9) << "the carriage rests at its limit";
  EXPECT_NEAR(world->jointState(world->findJoint("servo")).position, 0.8, 1e-6) << "the servo turned the arm to its target";
  EXPECT_EQ(world->jointState(world->findJoint("door_hinge")).rate, 0.0) << "damping and friction stopped the door";
  EXPECT_NEAR(world->jointState(world->findJoint("lamp_rope")).position, 1.0, 1e-9) << "the lamp hangs on its taut rope";
  EXPECT_NEAR(world->jointState(world->findJoint("hip")).position, 0.3, 1e-9) << "the leg rests on the hip's cone";
}

TEST(JointConfig, SpringsAreReadAsWritten) {
  const Expected<WorldDef> def = parseWorldConfig(
      kBodies +
          "joints:\n"
          "  - {name: bungee, type: distance, body_a: base, body_b: arm, anchor: [0, 0, 0], anchor_b: [0.5, 0, 0],\n"
          "     spring: {stiffness: 40, damping: 2}, length: 0.4, limits: {lower: 0.1, upper: 0.9}}\n"
          "  - {name: soft, type: distance, body_a: arm, body_b: tip, anchor: [0.5, 0, 0], anchor_b: [1, 0, 0],\n"
          "     spring: {frequency: 3, damping_ratio: 0.5}}\n",
      "j.yaml", "");
  ASSERT_TRUE(def.ok()) << def.error().message;
  const JointDef& bungee = def->joints[0].def;
  EXPECT_TRUE(bungee.drive.enabled);
  EXPECT_EQ(bungee.drive.target, 0.4) << "the rest length";
  EXPECT_EQ(bungee.drive.stiffness, 40.0);
  EXPECT_EQ(bungee.drive.damping, 2.0);
  EXPECT_TRUE(bungee.limit.enabled);
  EXPECT_EQ(bungee.limit.upper, 0.9);
  const JointDef& soft = def->joints[1].def;
  EXPECT_EQ(soft.drive.frequency, 3.0);
  EXPECT_EQ(soft.drive.dampingRatio, 0.5);
  EXPECT_DOUBLE_EQ(soft.drive.target, 0.5) << "by default the anchors' distance";
  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;

  const std::string rod = "  - {name: j, type: distance, body_a: world, body_b: arm, anchor: [0, 0, 0], anchor_b: [0.5, 0, 0]";
  EXPECT_NE(errorOf(rod + ", spring: {stiffness: 1, target: 2}}\n").find("joints[0].spring.target: unknown key"),
            std::string::npos);
  EXPECT_NE(errorOf(rod + ", spring: {stiffness: -1}}\n").find("joints[0].spring.stiffness"), std::string::npos);
  EXPECT_NE(errorOf(rod + ", spring: {stiffness: 1}, length: -1}\n").find("joints[0].length"), std::string::npos);
  EXPECT_NE(errorOf("  - {name: j, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0], "
                    "spring: {stiffness: 1}}\n")
                .find("only distance joints take a spring"),
            std::string::npos);
}

TEST(JointConfig, APositionIsTheJointsCoordinateWhereTheBodiesArePlaced) {
  // The arm is placed 0.3 rad round from its zero pose (along +x from the
  // shoulder); the tip 0.1 m along its slider from its zero.
  const Expected<WorldDef> def = parseWorldConfig(
      "bodies:\n"
      "  - {name: arm, shape: {type: sphere, radius: 0.05}, mass: 1, position: [0.4776682, 0, -0.1477601],\n"
      "     rpy: [0, 0.3, 0]}\n"
      "  - {name: tip, shape: {type: sphere, radius: 0.05}, mass: 1, position: [1.1, 0, 0]}\n"
      "joints:\n"
      "  - {name: shoulder, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0],\n"
      "     position: 0.3, limits: {lower: -0.5, upper: 0.5}}\n"
      "  - {name: slide, type: prismatic, body_a: world, body_b: tip, anchor: [1.1, 0, 0], axis: [1, 0, 0],\n"
      "     position: 0.1, drive: {target: 0.1, stiffness: 10}}\n",
      "j.yaml", "");
  ASSERT_TRUE(def.ok()) << def.error().message;
  EXPECT_EQ(def->joints[0].def.position, 0.3);
  EXPECT_EQ(def->joints[1].def.position, 0.1);
  Expected<World> world = World::fromDef(*def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_NEAR(world->jointState(world->findJoint("shoulder")).position, 0.3, 1e-15);
  EXPECT_NEAR(world->jointState(world->findJoint("slide")).position, 0.1, 1e-15);
  const Expected<WorldDef> unset = parseWorldConfig(
      kBodies +
          "joints:\n"
          "  - {name: j, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0]}\n",
      "j.yaml", "");
  ASSERT_TRUE(unset.ok()) << unset.error().message;
  EXPECT_EQ(unset->joints[0].def.position, 0.0) << "the default";
}

TEST(JointConfig, APositionOnAJointWithoutAnAxisOrBeyondItsLimitsIsAnError) {
  EXPECT_EQ(errorOf("  - {name: j, type: fixed, body_a: world, body_b: arm, anchor: [0, 0, 0], position: 0.1}\n"),
            "j.yaml:6:75: joints[0].position: only revolute and prismatic joints take position, this one is fixed");
  EXPECT_EQ(errorOf("  - {name: j, type: spherical, body_a: world, body_b: arm, anchor: [0, 0, 0], position: 0.1}\n"),
            "j.yaml:6:79: joints[0].position: only revolute and prismatic joints take position, this one is spherical");
  EXPECT_EQ(errorOf("  - {name: j, type: distance, body_a: world, body_b: arm, anchor: [0, 0, 1],\n"
                    "     position: 0.1, anchor_b: [0.5, 0, 0]}\n"),
            "j.yaml:7:6: joints[0].position: only revolute and prismatic joints take position, this one is distance");
  EXPECT_EQ(errorOf("  - {name: j, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0],\n"
                    "     limits: {lower: -0.5, upper: 0.5}, position: 0.7}\n"),
            "j.yaml:7:51: joints[0].position: the joint starts at 0.700000, outside its limits [-0.500000, 0.500000]: "
            "a joint cannot start beyond its stops");
  EXPECT_EQ(errorOf("  - {name: j, type: prismatic, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [1, 0, 0],\n"
                    "     position: -0.3, limits: {lower: -0.2, upper: 0.2}}\n"),
            "j.yaml:7:16: joints[0].position: the joint starts at -0.300000, outside its limits [-0.200000, 0.200000]: "
            "a joint cannot start beyond its stops");
  EXPECT_EQ(errorOf("  - {name: j, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0],\n"
                    "     position: .nan}\n"),
            "j.yaml:7:16: joints[0].position: expected a finite number, got \".nan\"");
}

TEST(JointConfig, ActuatorLimitsAreReadAsWrittenAndCheckedAtTheirKey) {
  const Expected<WorldDef> def = parseWorldConfig(
      kBodies +
          "joints:\n"
          "  - {name: j, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0],\n"
          "     actuator_limits: {effort: 80, rate: 3}}\n"
          "  - {name: k, type: prismatic, body_a: arm, body_b: tip, anchor: [1, 0, 0], axis: [1, 0, 0],\n"
          "     actuator_limits: {rate: 0.5}}\n",
      "j.yaml", "");
  ASSERT_TRUE(def.ok()) << def.error().message;
  EXPECT_EQ(def->joints[0].def.actuatorLimits.effort, 80.0);
  EXPECT_EQ(def->joints[0].def.actuatorLimits.rate, 3.0);
  EXPECT_EQ(def->joints[1].def.actuatorLimits.rate, 0.5);
  EXPECT_TRUE(std::isinf(def->joints[1].def.actuatorLimits.effort)) << "not given: uncapped";

  const std::string hinge = "  - {name: j, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0],\n";
  EXPECT_EQ(errorOf(hinge + "     actuator_limits: {}}\n"),
            "j.yaml:7:23: joints[0].actuator_limits: actuator limits need an effort (N·m or N), a rate (rad/s or m/s) "
            "or both");
  EXPECT_NE(errorOf(hinge + "     actuator_limits: {effort: 0}}\n").find("j.yaml:7:32: joints[0].actuator_limits.effort"),
            std::string::npos)
      << errorOf(hinge + "     actuator_limits: {effort: 0}}\n");
  EXPECT_NE(errorOf(hinge + "     actuator_limits: {speed: 2}}\n").find("speed"), std::string::npos);
  EXPECT_NE(errorOf("  - {name: j, type: fixed, body_a: world, body_b: arm, anchor: [0, 0, 0],\n"
                    "     actuator_limits: {effort: 1}}\n")
                .find("only revolute and prismatic joints take actuator_limits, this one is fixed"),
            std::string::npos);
}

TEST(JointConfig, MistakesAreNamedAtTheirLineAndKey) {
  const std::string base = "  - {name: j, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0]";
  EXPECT_NE(errorOf("  - {name: j, type: revolute, body_a: world, body_b: ghost, anchor: [0, 0, 0], axis: [0, 1, 0]}\n")
                .find("j.yaml:6:"),
            std::string::npos);
  EXPECT_NE(errorOf("  - {name: j, type: revolute, body_a: world, body_b: ghost, anchor: [0, 0, 0], axis: [0, 1, 0]}\n")
                .find("no body named \"ghost\""),
            std::string::npos);
  EXPECT_NE(errorOf(base + ", axis: [0, 0, 0]}\n").find("duplicate"), std::string::npos) << "a key twice";
  EXPECT_NE(errorOf("  - {name: j, type: revolute, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 0, 0]}\n")
                .find("joints[0].axis: the axis must not be zero"),
            std::string::npos);
  EXPECT_NE(errorOf(base + ", limits: {lower: 1, upper: -1}}\n").find("joints[0].limits.upper: upper"), std::string::npos);
  EXPECT_NE(errorOf("  - {name: j, type: revolute, body_a: arm, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0]}\n")
                .find("the same body"),
            std::string::npos);
  EXPECT_NE(errorOf("  - {name: j, type: spherical, body_a: world, body_b: base, anchor: [0, 0, 0]}\n").find("neither side moves"),
            std::string::npos);
  EXPECT_NE(errorOf(base + ", motor: {max_effort: -1}}\n").find("joints[0].motor.max_effort"), std::string::npos);
  EXPECT_NE(errorOf("  - {name: j, type: fixed, body_a: world, body_b: arm, anchor: [0, 0, 0], axis: [0, 1, 0]}\n")
                .find("only revolute and prismatic joints take axis"),
            std::string::npos);
  EXPECT_NE(errorOf(base + ", drive: {target: 0}}\n").find("joints[0].drive.stiffness: missing required key"), std::string::npos);
  EXPECT_NE(errorOf(base + ", drive: {stiffness: 1, frequency: 2}}\n").find("not both"), std::string::npos);
  EXPECT_NE(errorOf(base + ", drive: {stiffness: 1, damping_ratio: 2}}\n").find("damping_ratio goes with frequency"),
            std::string::npos);
  EXPECT_NE(errorOf(base + ", drive: {stiffness: -1}}\n").find("joints[0].drive.stiffness"), std::string::npos);
  EXPECT_NE(errorOf(base + ", drive: {stiffness: 1, max_effort: 0}}\n").find("joints[0].drive.max_effort"),
            std::string::npos);
  EXPECT_NE(errorOf(base + ", motor: {max_effort: 1}, drive: {stiffness: 1}}\n").find("a motor or a drive, not both"),
            std::string::npos);
  EXPECT_NE(errorOf(base + ", damping: -0.1}\n").find("joints[0].damping"), std::string::npos);
  EXPECT_NE(errorOf(base + ", friction: .nan}\n").find("joints[0].friction"), std::string::npos);
  EXPECT_NE(errorOf("  - {name: j, type: spherical, body_a: world, body_b: arm, anchor: [0, 0, 0], damping: 1}\n")
                .find("only revolute and prismatic joints take damping"),
            std::string::npos);
  EXPECT_NE(errorOf("  - {name: j, type: hinge, body_a: world, body_b: arm, anchor: [0, 0, 0]}\n").find("expected one of fixed"),
            std::string::npos);
  EXPECT_NE(errorOf(base + "}\n" + base + "}\n").find("duplicate joint name \"j\""), std::string::npos);
  EXPECT_NE(errorOf(base + ", speed: 3}\n").find("speed"), std::string::npos) << "an unknown key";
}

}  // namespace
}  // namespace rbsim
