// The joints' API (rbsim/physics/world.h, joint_definition.h): what a bad
// definition is told, what removal does, what a joint reports, and that
// jointed worlds step deterministically (copies, identical worlds).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::creationError;
using testing::hinge;
using testing::jointWorldSettings;

TEST(JointApi, BadDefinitionsAreRefusedWithTheJointAndTheReasonNamed) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, 1.0, Vec3(0, 0, 1));
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  const BodyId floor = *world.createBody(ground);

  EXPECT_NE(creationError(world, hinge("", BodyId{}, box, Vec3::Zero(), Vec3::UnitZ())).find("needs a name"),
            std::string::npos);
  addJoint(world, hinge("taken", BodyId{}, box, Vec3::Zero(), Vec3::UnitZ()));
  EXPECT_NE(creationError(world, hinge("taken", BodyId{}, box, Vec3::Zero(), Vec3::UnitZ())).find("name is taken"),
            std::string::npos);
  EXPECT_NE(creationError(world, hinge("self", box, box, Vec3::Zero(), Vec3::UnitZ())).find("to itself"),
            std::string::npos);
  EXPECT_NE(creationError(world, hinge("still", floor, BodyId{}, Vec3::Zero(), Vec3::UnitZ())).find("neither side moves"),
            std::string::npos);
  EXPECT_NE(creationError(world, hinge("axis", BodyId{}, box, Vec3::Zero(), Vec3::Zero())).find("joint 'axis': the axis"),
            std::string::npos);
  EXPECT_NE(creationError(world, hinge("nan", BodyId{}, box, Vec3(NAN, 0, 0), Vec3::UnitZ())).find("anchor is not finite"),
            std::string::npos);
  JointDef rod;
  rod.name = "rod";
  rod.type = JointType::Distance;
  rod.bodyB = box;
  rod.anchor = rod.anchorB = Vec3(0, 0, 1);
  EXPECT_NE(creationError(world, rod).find("length must be positive"), std::string::npos);

  const BodyId removed = addBody(world, "removed", SphereShape{0.1}, 1.0, Vec3(2, 0, 0));
  ASSERT_TRUE(world.removeBody(removed).ok());
  EXPECT_NE(creationError(world, hinge("stale", BodyId{}, removed, Vec3::Zero(), Vec3::UnitZ())).find("body_b: "),
            std::string::npos);
  EXPECT_EQ(world.jointCount(), 1) << "only the good joint was made";

  WorldSettings penalty = jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3);
  penalty.contact.model = ContactModel::Penalty;
  World soft(penalty);
  const BodyId ball = addBody(soft, "ball", SphereShape{0.1}, 1.0, Vec3::Zero());
  EXPECT_NE(creationError(soft, hinge("h", BodyId{}, ball, Vec3::Zero(), Vec3::UnitZ())).find("impulse contact model"),
            std::string::npos);
}

TEST(JointApi, RemovingABodyRemovesItsJointsAndStaleJointIdsAreErrors) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId a = addBody(world, "a", SphereShape{0.05}, 1.0, Vec3(0.5, 0, 0));
  const BodyId b = addBody(world, "b", SphereShape{0.05}, 1.0, Vec3(1.0, 0, 0));
  const JointId shoulder = addJoint(world, hinge("shoulder", BodyId{}, a, Vec3::Zero(), Vec3::UnitY()));
  const JointId elbow = addJoint(world, hinge("elbow", a, b, Vec3(0.5, 0, 0), Vec3::UnitY()));
  EXPECT_EQ(world.findJoint("elbow"), elbow);
  ASSERT_TRUE(world.removeBody(b).ok());
  EXPECT_EQ(world.jointCount(), 1);
  EXPECT_FALSE(world.isValid(elbow));
  EXPECT_TRUE(world.findJoint("elbow").isNull());
  EXPECT_THROW((void)world.jointState(elbow), std::invalid_argument);
  EXPECT_FALSE(world.removeJoint(elbow).ok());
  ASSERT_TRUE(world.removeJoint(shoulder).ok());
  EXPECT_EQ(world.jointCount(), 0);
  // With the joint gone the sphere falls free.
  world.step();
  EXPECT_NEAR(world.body(a).linearVelocity().z(), -testing::kGravity * 1e-3, 1e-15);
}

TEST(JointApi, AJointReportsItsCoordinateRateAndReaction) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  // A pendulum hanging still: the hinge holds its weight, m g up on the bob.
  const BodyId bob = addBody(world, "bob", SphereShape{0.05}, 2.0, Vec3(0, 0, -0.5));
  const JointId pivot = addJoint(world, hinge("pivot", BodyId{}, bob, Vec3::Zero(), Vec3::UnitY()));
  for (int k = 0; k < 100; ++k) world.step();
  JointState state = world.jointState(pivot);
  EXPECT_EQ(state.name, "pivot");
  EXPECT_EQ(state.type, JointType::Revolute);
  EXPECT_TRUE(state.active);
  EXPECT_NEAR(state.position, 0.0, 1e-12);
  EXPECT_LT((state.force - Vec3(0, 0, 2.0 * testing::kGravity)).norm(), 1e-9) << state.force.transpose();
  EXPECT_LT(state.error, 1e-12);
  // Turned by 0.3 rad about the axis and spun at 2 rad/s: the coordinate and
  // its rate are the hinge's angle and speed (right-handed about +y).
  World turned(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  turned.setGravity(Vec3::Zero());
  const Vec3 arm = Quaternion::fromAxisAngle(Vec3::UnitY(), 0.3).rotate(Vec3(0, 0, -0.5));
  const BodyId swung = addBody(turned, "bob", SphereShape{0.05}, 2.0, Vec3(0, 0, -0.5));
  const JointId hinge2 = addJoint(turned, hinge("pivot", BodyId{}, swung, Vec3::Zero(), Vec3::UnitY()));
  RigidState rotated = turned.body(swung).state();
  rotated.position = arm;
  rotated.orientation = Quaternion::fromAxisAngle(Vec3::UnitY(), 0.3);
  ASSERT_TRUE(turned.setBodyState(swung, rotated).ok());
  ASSERT_TRUE(turned.setBodyVelocities(swung, Vec3(0, 2, 0).cross(arm), Vec3(0, 2, 0)).ok());
  state = turned.jointState(hinge2);
  EXPECT_NEAR(state.position, 0.3, 1e-12);
  EXPECT_NEAR(state.rate, 2.0, 1e-12);
  EXPECT_LT((state.axis - Vec3::UnitY()).norm(), 1e-12);
}

TEST(JointApi, AStateSetFromOutsideIsClosedWithoutAddingEnergy) {
  // A client moves the bob 1 cm off its hinge's circle: the next step puts
  // it back on by moving it, not by launching it.
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  world.setGravity(Vec3::Zero());
  const BodyId bob = addBody(world, "bob", SphereShape{0.05}, 1.0, Vec3(0, 0, -0.5));
  const JointId pivot = addJoint(world, hinge("pivot", BodyId{}, bob, Vec3::Zero(), Vec3::UnitY()));
  RigidState moved = world.body(bob).state();
  moved.position.z() -= 0.01;
  ASSERT_TRUE(world.setBodyState(bob, moved).ok());
  EXPECT_NEAR(world.jointState(pivot).error, 0.01, 1e-12);
  world.step();
  EXPECT_LT(world.jointState(pivot).error, 1e-11);
  EXPECT_LT(world.totalKineticEnergy(), 1e-20) << "closed by a move, with no velocity";
}

TEST(JointApi, JointedWorldsStepDeterministically) {
  const auto build = [] {
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
    BodyDef ground;
    ground.name = "ground";
    ground.shape = PlaneShape{};
    ground.isStatic = true;
    EXPECT_TRUE(world.createBody(ground).ok());
    BodyId previous;
    for (int k = 0; k < 6; ++k) {
      const BodyId link = addBody(world, "link" + std::to_string(k), BoxShape{Vec3(0.05, 0.02, 0.02)}, 0.2,
                                  Vec3(0.1 * k + 0.05, 0, 0.4));
      addJoint(world, hinge("j" + std::to_string(k), previous, link, Vec3(0.1 * k, 0, 0.4), Vec3(0, 1, 0.2)));
      previous = link;
    }
    const BodyId box = addBody(world, "box", BoxShape{Vec3(0.1, 0.1, 0.1)}, 1.0, Vec3(0.4, 0, 0.1));
    EXPECT_TRUE(world.applyWrench(box, {Vec3(3, 0, 0), Vec3::Zero(), Vec3::Zero()}).ok());
    return world;
  };
  World first = build(), second = build();
  for (int k = 0; k < 1500; ++k) {
    first.step();
    second.step();
  }
  EXPECT_EQ(first.stateHash(), second.stateHash());
  World copy = first;
  for (int k = 0; k < 500; ++k) {
    first.step();
    copy.step();
  }
  EXPECT_EQ(first.stateHash(), copy.stateHash()) << "a copy steps on bit for bit";
}

TEST(JointApi, AFrozenBodyDropsItsJointsAndACheckpointKeepsThemSo) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId a = addBody(world, "a", SphereShape{0.05}, 1.0, Vec3(0.5, 0, 0));
  const BodyId b = addBody(world, "b", SphereShape{0.05}, 1.0, Vec3(1.0, 0, 0));
  const BodyId c = addBody(world, "c", SphereShape{0.05}, 1.0, Vec3(1.5, 0, 0));
  addJoint(world, hinge("shoulder", BodyId{}, a, Vec3::Zero(), Vec3::UnitY()));
  addJoint(world, hinge("elbow", a, b, Vec3(0.5, 0, 0), Vec3::UnitY()));
  addJoint(world, hinge("wrist", b, c, Vec3(1.0, 0, 0), Vec3::UnitY()));
  ASSERT_TRUE(world.freezeBody(a).ok());
  EXPECT_EQ(world.jointCount(), 1);
  EXPECT_TRUE(world.findJoint("shoulder").isNull());
  EXPECT_TRUE(world.findJoint("elbow").isNull());
  EXPECT_FALSE(world.findJoint("wrist").isNull()) << "a joint of other bodies stays";
  world.step();
  EXPECT_NEAR(world.body(b).linearVelocity().z(), -testing::kGravity * 1e-3, 1e-15) << "b falls free";
  const Expected<std::vector<uint8_t>> snapshot = world.encodeSnapshot();
  ASSERT_TRUE(snapshot.ok()) << snapshot.error().message;
  Expected<World> restored = World::decodeSnapshot(*snapshot, world.settings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  EXPECT_EQ(restored->jointCount(), 1) << "still dropped";
  world.step();
  restored->step();
  EXPECT_EQ(restored->stateHash(), world.stateHash());
}

// The guard's freeze (here: a speed above the limit) removes the body's
// joints in the step it froze, and its event names them for the log.
TEST(JointApi, TheGuardsFreezeNamesTheJointsItRemoved) {
  World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, 1e-3));
  const BodyId a = addBody(world, "a", SphereShape{0.05}, 1.0, Vec3(0.5, 0, 0));
  const BodyId b = addBody(world, "b", SphereShape{0.05}, 1.0, Vec3(1.0, 0, 0));
  addJoint(world, hinge("shoulder", BodyId{}, a, Vec3::Zero(), Vec3::UnitY()));
  addJoint(world, hinge("elbow", a, b, Vec3(0.5, 0, 0), Vec3::UnitY()));
  StateLimits limits = world.settings().limits;
  limits.maxLinearSpeed = 10.0;
  world.setStateLimits(limits);
  ASSERT_TRUE(world.setBodyVelocities(b, Vec3(0, 0, 50.0), Vec3::Zero()).ok());
  world.step();
  ASSERT_EQ(world.freezeEvents().size(), 1u);
  const FreezeEvent& event = world.freezeEvents().front();
  EXPECT_EQ(event.name, "b");
  EXPECT_EQ(event.droppedJoints, std::vector<std::string>{"elbow"});
  EXPECT_NE(describeFreeze(event).find("its joint 'elbow' was removed"), std::string::npos) << describeFreeze(event);
  EXPECT_EQ(world.jointCount(), 1);
  EXPECT_FALSE(world.findJoint("shoulder").isNull());
}

}  // namespace
}  // namespace rbsim
