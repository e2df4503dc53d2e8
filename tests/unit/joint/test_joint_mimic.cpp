// Mimic joints (JointDef::mimic): a follower's coordinate held at
// multiplier · leader's + offset by one constraint row over both joints'
// bodies. Against closed forms: a gear pair under a torque turns with
// α = τ / (I_a + r² I_b) and passes the follower I_b r α; a gripper's
// fingers and two arms on swinging bases (four bodies in one row) keep the
// coupling to 1e-9 at every step while the energy stays; a follower past
// ±2π keeps its phase; commands to a follower are refused with the reason;
// a checkpoint steps on bit-exactly. And joints that start beyond their
// limits: brought back by positions only, with no velocity from it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "joint/joint_test_worlds.h"

namespace rbsim {
namespace {

using testing::addBody;
using testing::addJoint;
using testing::creationError;
using testing::hinge;
using testing::jointWorldSettings;
using testing::mechanicalEnergy;
using testing::slider;

constexpr double kPi = 3.14159265358979323846;
constexpr IntegratorKind kIntegrators[] = {IntegratorKind::ExplicitEuler, IntegratorKind::SemiImplicitEuler,
                                           IntegratorKind::Rk4};

// Two spheres on vertical hinges through their centres (gravity has no
// torque about them): the leader `a` (mass 2 kg, radius 0.1) and the
// follower `b` (1 kg, radius 0.2), b = ratio · a.
struct GearPair {
  World world;
  JointId a, b;
  double inertiaA = 0.4 * 2.0 * 0.1 * 0.1;  // kg·m², a solid sphere's 2/5 m r²
  double inertiaB = 0.4 * 1.0 * 0.2 * 0.2;

  GearPair(IntegratorKind integrator, double dt, double ratio, double offset = 0.0)
      : world(jointWorldSettings(integrator, dt)) {
    const BodyId wheelA = addBody(world, "wheel_a", SphereShape{0.1}, 2.0, Vec3(0, 0, 1));
    const BodyId wheelB = addBody(world, "wheel_b", SphereShape{0.2}, 1.0, Vec3(1, 0, 1));
    a = addJoint(world, hinge("a", BodyId{}, wheelA, Vec3(0, 0, 1), Vec3::UnitZ()));
    JointDef follower = hinge("b", BodyId{}, wheelB, Vec3(1, 0, 1), Vec3::UnitZ());
    follower.mimic = {true, "a", ratio, offset};
    follower.position = offset;  // where the coupling holds it with a at 0
    b = addJoint(world, follower);
  }
};

TEST(MimicJoints, AGearPairTurnsAsOneInertiaAndPassesTheFollowerItsShare) {
  constexpr double kTorque = 0.3;  // N·m on the leader
  for (const IntegratorKind integrator : kIntegrators) {
    for (const double dt : {1e-3, 5e-4}) {
      for (const double ratio : {-2.0, 0.5}) {
        SCOPED_TRACE(::testing::Message() << integratorName(integrator) << ", dt " << dt << ", ratio " << ratio);
        GearPair gear(integrator, dt, ratio);
        ASSERT_TRUE(gear.world.setJointEffort(gear.a, kTorque).ok());
        const double alpha = kTorque / (gear.inertiaA + ratio * ratio * gear.inertiaB);
        const int steps = static_cast<int>(std::lround(0.5 / dt));
        double worstCoupling = 0.0;
        for (int k = 0; k < steps; ++k) {
          gear.world.step();
          const double qa = gear.world.jointState(gear.a).position, qb = gear.world.jointState(gear.b).position;
          worstCoupling = std::max(worstCoupling, std::abs(qb - ratio * qa));
        }
        const double t = steps * dt;
        const JointState a = gear.world.jointState(gear.a), b = gear.world.jointState(gear.b);
        EXPECT_LT(worstCoupling, 1e-9) << "rad, at every step";
        EXPECT_NEAR(a.rate, alpha * t, 1e-9 * alpha * t) << "ω = α t";
        // The orientation update (normalise(q + ½h ω q)) is second order
        // in the angle a step turns.
        EXPECT_NEAR(a.position, 0.5 * alpha * t * t, 1e-5 * (dt / 1e-3) * (dt / 1e-3) * alpha * t * t) << "θ = α t² / 2";
        EXPECT_NEAR(b.rate, ratio * alpha * t, 1e-9 * std::abs(ratio) * alpha * t);
        // The follower turns by what the coupling passes it alone: I_b r α.
        EXPECT_NEAR(b.axisEffort, gear.inertiaB * ratio * alpha, 1e-6 * gear.inertiaB * std::abs(ratio) * alpha)
            << "N·m";
      }
    }
  }
}

TEST(MimicJoints, AFollowerOfAContinuousJointKeepsItsPhasePastAFullTurn) {
  // 3 N·m on the leader for 1 s turns it 7.3 turns; the follower at 1.5
  // times that. Both coordinates wrap; the coupling counts turns.
  constexpr double kTorque = 3.0, kRatio = 1.5, kOffset = 0.2;
  GearPair gear(IntegratorKind::SemiImplicitEuler, 1e-3, kRatio, kOffset);
  ASSERT_TRUE(gear.world.setJointEffort(gear.a, kTorque).ok());
  const double alpha = kTorque / (gear.inertiaA + kRatio * kRatio * gear.inertiaB);
  for (int k = 0; k < 1000; ++k) gear.world.step();
  const double turned = 0.5 * alpha * 1.0;  // rad, at t = 1 s
  ASSERT_GT(turned, 2.0 * kPi * 5.0) << "several turns";
  const JointState a = gear.world.jointState(gear.a), b = gear.world.jointState(gear.b);
  // A revolute's coordinate is its angle modulo 4π (the relative
  // quaternion's), so b − 1.5 a − offset is a multiple of 6π, of 2π.
  EXPECT_NEAR(std::remainder(b.position - kRatio * a.position - kOffset, 2.0 * kPi), 0.0, 1e-9);
  EXPECT_NEAR(a.rate, alpha * 1.0, 1e-9 * alpha) << "ω = α t";
  EXPECT_NEAR(b.rate, kRatio * a.rate, 1e-9 * std::abs(b.rate));
}

// A gripper: a palm hanging from the world on a hinge, two fingers on
// sliders along ±y; the right finger follows the left.
struct Gripper {
  World world;
  JointId swing, left, right;
  BodyId palm, fingerLeft, fingerRight;

  Gripper(IntegratorKind integrator, double dt, double multiplier, double offset)
      : world(jointWorldSettings(integrator, dt)) {
    palm = addBody(world, "palm", BoxShape{Vec3(0.05, 0.1, 0.02)}, 0.5, Vec3(0.3, 0, 1));
    fingerLeft = addBody(world, "finger_left", BoxShape{Vec3(0.01, 0.01, 0.04)}, 0.05, Vec3(0.3, 0.05, 0.94));
    fingerRight = addBody(world, "finger_right", BoxShape{Vec3(0.01, 0.01, 0.04)}, 0.05, Vec3(0.3, -0.05, 0.94));
    swing = addJoint(world, hinge("swing", BodyId{}, palm, Vec3(0, 0, 1), Vec3::UnitY()));
    JointDef leader = slider("left", palm, fingerLeft, Vec3(0.3, 0.05, 0.94), Vec3::UnitY());
    leader.limit = {true, -0.04, 0.04};
    left = addJoint(world, leader);
    JointDef follower = slider("right", palm, fingerRight, Vec3(0.3, -0.05, 0.94), -Vec3::UnitY());
    follower.limit = {true, -0.04, 0.04};
    follower.mimic = {true, "left", multiplier, offset};
    follower.position = offset;
    right = addJoint(world, follower);
  }
};

TEST(MimicJoints, AGrippersFingersMoveTogetherUnderOneCommandWhileThePalmSwings) {
  for (const IntegratorKind integrator : kIntegrators) {
    for (const double dt : {1e-3, 5e-4}) {
      for (const auto& [multiplier, offset] : {std::pair{1.0, 0.0}, std::pair{0.5, 0.01}}) {
        SCOPED_TRACE(::testing::Message() << integratorName(integrator) << ", dt " << dt << ", multiplier "
                                          << multiplier << ", offset " << offset);
        Gripper gripper(integrator, dt, multiplier, offset);
        JointDrive drive;
        drive.enabled = true;
        drive.target = 0.03;
        drive.stiffness = 200.0;
        drive.damping = 5.0;
        ASSERT_TRUE(gripper.world.setJointDrive(gripper.left, drive).ok());
        double worst = 0.0;
        const int steps = static_cast<int>(std::lround(1.0 / dt));
        for (int k = 0; k < steps; ++k) {
          gripper.world.step();
          const double ql = gripper.world.jointState(gripper.left).position;
          const double qr = gripper.world.jointState(gripper.right).position;
          worst = std::max(worst, std::abs(qr - (multiplier * ql + offset)));
        }
        EXPECT_LT(worst, 1e-9) << "m, at every step";
        const JointState left = gripper.world.jointState(gripper.left);
        const JointState right = gripper.world.jointState(gripper.right);
        EXPECT_NEAR(left.position, 0.03, 2e-3) << "the drive opened the leader";
        EXPECT_GT(right.position, multiplier * 0.02 + offset) << "and the follower with it";
        EXPECT_LT(right.error, 1e-9) << "the follower's own slider rows hold";
        // The right finger is as far out along −y as the coupling says.
        const double out = -(gripper.world.body(gripper.fingerRight).position() -
                             gripper.world.body(gripper.palm).position())
                                .dot(gripper.world.body(gripper.palm).orientation().rotate(Vec3::UnitY()));
        EXPECT_NEAR(out, 0.05 + right.position - offset, 1e-9);
      }
    }
  }
}

TEST(MimicJoints, ACouplingOfFourBodiesKeepsTheEnergy) {
  // Two double pendulums side by side, each an arm on a hinge to the world
  // and a forearm on a hinge to the arm; forearm 2 follows forearm 1 × 0.7.
  // The coupling row spans all four bodies; it does no work, so the
  // frictionless system keeps its energy to the integrator's O(dt²).
  for (const double dt : {1e-3, 5e-4}) {
    SCOPED_TRACE(::testing::Message() << "dt " << dt);
    World world(jointWorldSettings(IntegratorKind::SemiImplicitEuler, dt));
    BodyId arm[2], forearm[2];
    JointId elbow[2];
    for (int k = 0; k < 2; ++k) {
      const double y = 0.5 * k;
      arm[k] = addBody(world, "arm" + std::to_string(k), BoxShape{Vec3(0.2, 0.02, 0.02)}, 1.0, Vec3(0.2, y, 1));
      forearm[k] = addBody(world, "forearm" + std::to_string(k), BoxShape{Vec3(0.15, 0.02, 0.02)}, 0.5 + 0.3 * k,
                           Vec3(0.55, y, 1));
      addJoint(world, hinge("shoulder" + std::to_string(k), BodyId{}, arm[k], Vec3(0, y, 1), Vec3::UnitY()));
      JointDef def = hinge("elbow" + std::to_string(k), arm[k], forearm[k], Vec3(0.4, y, 1), Vec3::UnitY());
      if (k == 1) def.mimic = {true, "elbow0", 0.7, 0.0};
      elbow[k] = addJoint(world, def);
    }
    const double start = mechanicalEnergy(world);
    double worstCoupling = 0.0, worstEnergy = 0.0;
    const int steps = static_cast<int>(std::lround(2.0 / dt));
    for (int k = 0; k < steps; ++k) {
      world.step();
      worstCoupling = std::max(worstCoupling, std::abs(world.jointState(elbow[1]).position -
                                                       0.7 * world.jointState(elbow[0]).position));
      worstEnergy = std::max(worstEnergy, std::abs(mechanicalEnergy(world) - start));
    }
    EXPECT_LT(worstCoupling, 1e-9) << "rad";
    EXPECT_GT(std::abs(world.jointState(elbow[0]).position), 0.05) << "the elbows did bend";
    EXPECT_LT(worstEnergy, 2e-3 * (dt / 1e-3) * (dt / 1e-3)) << "J, of about 20 J of swing";
  }
}

TEST(MimicJoints, AFollowerTakesNoCommandOfItsOwnAndNamesItsLeader) {
  GearPair gear(IntegratorKind::SemiImplicitEuler, 1e-3, 2.0);
  const std::string reason = "joint 'b' follows joint 'a' (mimic): command its leader";
  JointMotor motor{true, 1.0, 5.0};
  Expected<bool> refused = gear.world.setJointMotor(gear.b, motor);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find(reason), std::string::npos) << refused.error().message;
  JointDrive drive;
  drive.enabled = true;
  drive.stiffness = 10.0;
  refused = gear.world.setJointDrive(gear.b, drive);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find(reason), std::string::npos) << refused.error().message;
  refused = gear.world.setJointEffort(gear.b, 1.0);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find(reason), std::string::npos) << refused.error().message;
  EXPECT_TRUE(gear.world.setJointDrive(gear.b, JointDrive{}).ok()) << "turning nothing off is fine";
  EXPECT_TRUE(gear.world.setJointMotor(gear.a, motor).ok()) << "the leader takes it";

  // Made wrong: each refusal says what.
  const BodyId wheel = addBody(gear.world, "wheel_c", SphereShape{0.1}, 1.0, Vec3(2, 0, 1));
  JointDef def = hinge("c", BodyId{}, wheel, Vec3(2, 0, 1), Vec3::UnitZ());
  def.mimic = {true, "nobody", 1.0, 0.0};
  EXPECT_NE(creationError(gear.world, def).find("joint 'c': mimic: no joint 'nobody' to follow"), std::string::npos)
      << creationError(gear.world, def);
  def.mimic = {true, "c", 1.0, 0.0};
  EXPECT_NE(creationError(gear.world, def).find("a joint cannot follow itself"), std::string::npos);
  def.mimic = {true, "a", NAN, 0.0};
  EXPECT_NE(creationError(gear.world, def).find("the multiplier and offset must be finite"), std::string::npos);
  def.mimic = {true, "a", 1.0, 0.0};
  def.motor = motor;
  EXPECT_NE(creationError(gear.world, def).find("takes no motor, drive or effort of its own"), std::string::npos);
  def.motor = {};
  const BodyId ball = addBody(gear.world, "ball", SphereShape{0.1}, 1.0, Vec3(3, 0, 1));
  JointDef socket;
  socket.name = "socket";
  socket.type = JointType::Spherical;
  socket.bodyB = ball;
  socket.anchor = Vec3(3, 0, 1.2);
  addJoint(gear.world, socket);
  def.mimic = {true, "socket", 1.0, 0.0};
  EXPECT_NE(creationError(gear.world, def).find("only a revolute or prismatic joint leads"), std::string::npos)
      << creationError(gear.world, def);
}

TEST(MimicJoints, ACheckpointOfACouplingStepsOnBitExactly) {
  Gripper gripper(IntegratorKind::SemiImplicitEuler, 1e-3, 0.5, 0.01);
  JointDrive drive;
  drive.enabled = true;
  drive.target = 0.03;
  drive.stiffness = 200.0;
  drive.damping = 5.0;
  ASSERT_TRUE(gripper.world.setJointDrive(gripper.left, drive).ok());
  for (int k = 0; k < 150; ++k) gripper.world.step();
  const Expected<std::vector<uint8_t>> bytes = gripper.world.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  Expected<World> copy = World::decodeSnapshot(*bytes, gripper.world.settings());
  ASSERT_TRUE(copy.ok()) << copy.error().message;
  EXPECT_TRUE(copy->jointDefinition(copy->findJoint("right")).mimic.enabled);
  for (int k = 0; k < 300; ++k) {
    gripper.world.step();
    copy->step();
  }
  EXPECT_EQ(copy->stateHash(), gripper.world.stateHash());
}

TEST(MimicJoints, RemovingTheLeaderFreesTheFollower) {
  GearPair gear(IntegratorKind::SemiImplicitEuler, 1e-3, 2.0);
  ASSERT_TRUE(gear.world.removeJoint(gear.a).ok());
  EXPECT_FALSE(gear.world.jointDefinition(gear.b).mimic.enabled);
  EXPECT_TRUE(gear.world.setJointEffort(gear.b, 0.1).ok()) << "a joint of its own now";
  for (int k = 0; k < 100; ++k) gear.world.step();
  EXPECT_GT(gear.world.jointState(gear.b).rate, 0.0);
}

TEST(JointsBeyondTheirLimits, AreBroughtBackByPositionsAloneWithNoVelocity) {
  // An arm turning in the horizontal plane (a vertical hinge: gravity has
  // no torque about it), made 0.7 rad beyond its upper limit; a slider made
  // 0.035 m beyond its lower one. Each comes back to its bound within a
  // few steps (0.1 rad or 0.01 m a step) and nothing moves faster for it.
  for (const IntegratorKind integrator : kIntegrators) {
    for (const double dt : {1e-3, 5e-4}) {
      SCOPED_TRACE(::testing::Message() << integratorName(integrator) << ", dt " << dt);
      World world(jointWorldSettings(integrator, dt));
      world.setGravity(Vec3::Zero());  // nothing but the limits acts
      const double start = 1.2;
      const Quaternion turned = Quaternion::fromAxisAngle(Vec3::UnitZ(), start);
      const BodyId arm =
          addBody(world, "arm", BoxShape{Vec3(0.25, 0.02, 0.02)}, 1.0, Vec3(0, 0, 1) + turned.rotate(Vec3(0.25, 0, 0)), turned);
      JointDef hingeDef = hinge("hinge", BodyId{}, arm, Vec3(0, 0, 1), Vec3::UnitZ());
      hingeDef.position = start;
      hingeDef.limit = {true, -0.5, 0.5};
      const JointId hingeJoint = addJoint(world, hingeDef);
      const BodyId block = addBody(world, "block", BoxShape{Vec3(0.05, 0.05, 0.05)}, 2.0, Vec3(1, 0, 0.5));
      JointDef sliderDef = slider("slider", BodyId{}, block, Vec3(1, 0, 0.5), Vec3::UnitX());
      sliderDef.position = -0.055;
      sliderDef.limit = {true, -0.02, 0.02};
      const JointId sliderJoint = addJoint(world, sliderDef);
      EXPECT_NEAR(world.jointState(hingeJoint).position, start, 1e-12) << "made where it was placed";
      double fastest = 0.0;
      int hingeBack = -1, sliderBack = -1;
      for (int k = 1; k <= 20; ++k) {
        world.step();
        const JointState h = world.jointState(hingeJoint), s = world.jointState(sliderJoint);
        fastest = std::max({fastest, std::abs(h.rate), std::abs(s.rate)});
        if (hingeBack < 0 && h.position <= 0.5 + 1e-9) hingeBack = k;
        if (sliderBack < 0 && s.position >= -0.02 - 1e-9) sliderBack = k;
        EXPECT_LE(h.position, start + 1e-12) << "never further out";
      }
      EXPECT_EQ(hingeBack, 7) << "0.7 rad at 0.1 rad a step";
      EXPECT_EQ(sliderBack, 4) << "0.035 m at 0.01 m a step";
      EXPECT_LT(fastest, 1e-9) << "no velocity from the correction";
      EXPECT_LT(world.totalKineticEnergy(), 1e-18) << "J";
      EXPECT_NEAR(world.jointState(hingeJoint).position, 0.5, 1e-9);
      EXPECT_NEAR(world.jointState(sliderJoint).position, -0.02, 1e-9);
    }
  }
}

}  // namespace
}  // namespace rbsim
