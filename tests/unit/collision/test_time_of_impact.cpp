#include <gtest/gtest.h>

#include <cmath>

#include "support/body_copies.h"
#include "physics/collision/time_of_impact.h"
#include "rbsim/physics/world.h"

namespace rbsim {
namespace {

constexpr double kTolerance = 1e-4;  // m

BisectionSettings bisection() {
  BisectionSettings settings;
  settings.tolerance = kTolerance;
  return settings;
}

CcdSettings ccd(int maxIterations = 32) {
  CcdSettings settings;
  settings.tolerance = kTolerance;
  settings.maxIterations = maxIterations;
  return settings;
}

Collider convexCollider(const ConvexGeometry& geometry) {
  Collider collider;
  collider.pieces.push_back({geometry, Transform::identity(), geometryBounds(geometry)});
  collider.bounds = collider.pieces.back().bounds;
  return collider;
}

Collider groundCollider() {
  Collider collider;
  collider.plane = PlaneShape{};
  collider.bounds = Aabb::everything();
  return collider;
}

RigidState stateAt(const Vec3& position, const Quaternion& orientation = Quaternion::identity()) {
  RigidState state;
  state.position = position;
  state.orientation = orientation;
  return state;
}

PoseAtFraction fixedAt(const Transform& pose) {
  return [pose](double) { return pose; };
}

// Falling at a constant 5 m/s from h = 1 m, radius 0.1 m, over a 0.25 s step:
// contact at t = (h − r)/v = 0.18 s.
struct ConstantFall {
  double height = 1.0, radius = 0.1, speed = 5.0, dt = 0.25;
  RigidState start() const { return stateAt(Vec3(0, 0, height)); }
  RigidState end() const { return stateAt(Vec3(0, 0, height - speed * dt)); }
  double contactTime() const { return (height - radius) / speed; }
};

TEST(TimeOfImpact, BisectionFindsASphereFallingOntoAPlane) {
  const ConstantFall fall;
  const TimeOfImpact toi = bisectCollisionTime(
      groundCollider(), fixedAt(Transform::identity()), convexCollider(SphereShape{fall.radius}),
      interpolatedMotion(fall.start(), fall.end()), bisection());
  ASSERT_EQ(toi.status, ImpactStatus::Hit);
  EXPECT_GT(toi.distance, 0.0);
  EXPECT_LE(toi.distance, kTolerance);
  // Apart by at most the tolerance: at most tolerance/v before the contact.
  const double time = toi.fraction * fall.dt;
  EXPECT_LE(time, fall.contactTime());
  EXPECT_GE(time, fall.contactTime() - kTolerance / fall.speed);
  EXPECT_TRUE(toi.normal.isApprox(Vec3::UnitZ()));
}

TEST(TimeOfImpact, BisectionFindsASphereFallingOntoABox) {
  const ConstantFall fall;
  const Transform boxPose{Mat3::Identity(), Vec3(0, 0, -0.5)};  // top face at z = 0
  const TimeOfImpact toi = bisectCollisionTime(
      convexCollider(SphereShape{fall.radius}), interpolatedMotion(fall.start(), fall.end()),
      convexCollider(BoxShape{Vec3(1, 1, 0.5)}), fixedAt(boxPose), bisection());
  ASSERT_EQ(toi.status, ImpactStatus::Hit);
  const double time = toi.fraction * fall.dt;
  EXPECT_LE(time, fall.contactTime() + 1e-12);
  EXPECT_GE(time, fall.contactTime() - kTolerance / fall.speed);
  EXPECT_TRUE(toi.normal.isApprox(-Vec3::UnitZ(), 1e-6));  // from the sphere down to the box
}

// Under gravity, integrating a copy of the body's state (integratedMotion): RK4 is
// exact for constant acceleration, so contact is at the root of
// h + v0 t − ½ g t² = r; semi-implicit Euler over one step of τ gives
// h + (v0 − g τ) τ instead, and the search must find its root.
TEST(TimeOfImpact, BisectionUnderGravityMatchesTheIntegratorsClosedForm) {
  const double radius = 0.1, height = 2.0, v0 = -1.0, g = 9.81, dt = 1.0;
  struct Case {
    IntegratorKind integrator;
    double quadratic;  // coefficient of t² in z(t)
  };
  for (const Case& c :
       {Case{IntegratorKind::Rk4, -0.5 * g}, Case{IntegratorKind::SemiImplicitEuler, -g}}) {
    WorldSettings settings;
    settings.dt = dt;
    settings.integrator = c.integrator;
    World world(settings);
    BodyDef def;
    def.name = "ball";
    def.shape = SphereShape{radius};
    def.position = Vec3(0, 0, height);
    def.linearVelocity = Vec3(0, 0, v0);
    const auto id = world.createBody(def);
    ASSERT_TRUE(id.ok());

    const TimeOfImpact toi = bisectCollisionTime(
        groundCollider(), fixedAt(Transform::identity()), convexCollider(SphereShape{radius}),
        integratedMotion(testing::bodyCopy(world, *id), settings.integrator, settings.gravity, settings.dt),
        bisection());
    ASSERT_EQ(toi.status, ImpactStatus::Hit);
    // quadratic t² + v0 t + (h − r) = 0, the first positive root.
    const double a = c.quadratic, b = v0, k = height - radius;
    const double exact = (-b - std::sqrt(b * b - 4 * a * k)) / (2 * a);
    const double speedAtContact = std::abs(v0 + 2 * a * exact);
    const double time = toi.fraction * dt;
    EXPECT_LE(time, exact + 1e-12);
    EXPECT_GE(time, exact - kTolerance / speedAtContact - 1e-12);
  }
}

TEST(TimeOfImpact, BisectionReportsOverlapAtTheStartAndMissesNothingElse) {
  const Collider ball = convexCollider(SphereShape{0.1});
  const TimeOfImpact overlapping =
      bisectCollisionTime(groundCollider(), fixedAt(Transform::identity()), ball,
                          interpolatedMotion(stateAt(Vec3(0, 0, 0.05)), stateAt(Vec3(0, 0, 0.5))));
  EXPECT_EQ(overlapping.status, ImpactStatus::Overlapping);
  EXPECT_EQ(overlapping.fraction, 0.0);
  const TimeOfImpact apart =
      bisectCollisionTime(groundCollider(), fixedAt(Transform::identity()), ball,
                          interpolatedMotion(stateAt(Vec3(0, 0, 1.0)), stateAt(Vec3(0, 0, 0.5))));
  EXPECT_EQ(apart.status, ImpactStatus::Separated);
  EXPECT_EQ(apart.fraction, 1.0);
}

// A bullet: r = 1 cm at 500 m/s against a wall 5 mm thick, in one 1 ms step.
struct Bullet {
  double radius = 0.01, speed = 500.0, dt = 1e-3, wallHalfThickness = 0.0025;
  Vec3 startPosition = Vec3(-0.2, 0.0, 0.0);
  RigidState start() const { return stateAt(startPosition); }
  RigidState end() const { return stateAt(startPosition + Vec3(speed * dt, 0, 0)); }
  Collider ball() const { return convexCollider(SphereShape{radius}); }
  Collider wall() const { return convexCollider(BoxShape{Vec3(wallHalfThickness, 1, 1)}); }
  double contactTime() const { return (-startPosition.x() - wallHalfThickness - radius) / speed; }
};

TEST(TimeOfImpact, AFastSmallSphereTunnelsThroughAThinWallForDiscreteDetection) {
  const Bullet bullet;
  const Transform wallPose = Transform::identity();
  const auto poseOf = [](const RigidState& s) {
    return Transform::fromPose(s.position, s.orientation);
  };
  EXPECT_GT(
      colliderDistance(bullet.ball(), poseOf(bullet.start()), bullet.wall(), wallPose).distance,
      0.1);
  EXPECT_GT(colliderDistance(bullet.ball(), poseOf(bullet.end()), bullet.wall(), wallPose).distance,
            0.1);
  const TimeOfImpact bisection =
      bisectCollisionTime(bullet.ball(), interpolatedMotion(bullet.start(), bullet.end()),
                          bullet.wall(), fixedAt(wallPose));
  EXPECT_EQ(bisection.status, ImpactStatus::Separated);
}

TEST(TimeOfImpact, ConservativeAdvancementCatchesTheTunnellingSphere) {
  const Bullet bullet;
  const TimeOfImpact toi =
      conservativeAdvancement(bullet.ball(), SweptMotion::between(bullet.start(), bullet.end()),
                              bullet.wall(), SweptMotion::stationary(RigidState{}), ccd());
  ASSERT_EQ(toi.status, ImpactStatus::Hit);
  const double time = toi.fraction * bullet.dt;
  EXPECT_NEAR(time, bullet.contactTime(), kTolerance / bullet.speed);
  EXPECT_LE(time, bullet.contactTime() + 1e-15);
  EXPECT_GE(toi.distance, -1e-12);
  EXPECT_LE(toi.distance, kTolerance);
  EXPECT_TRUE(toi.normal.isApprox(Vec3::UnitX(), 1e-9));  // from the ball to the wall
  EXPECT_LE(toi.iterations, 4);

  // The same with the roles swapped: the normal turns round.
  const TimeOfImpact swapped =
      conservativeAdvancement(bullet.wall(), SweptMotion::stationary(RigidState{}), bullet.ball(),
                              SweptMotion::between(bullet.start(), bullet.end()), ccd());
  ASSERT_EQ(swapped.status, ImpactStatus::Hit);
  EXPECT_NEAR(swapped.fraction, toi.fraction, 1e-12);
  EXPECT_TRUE(swapped.normal.isApprox(-Vec3::UnitX(), 1e-9));
}

TEST(TimeOfImpact, ConservativeAdvancementFindsTheFirstContactOfASpinningRod) {
  // A rod 1 m long turning 1 rad in the step about z, a ball off to its side.
  const Collider rod = convexCollider(BoxShape{Vec3(0.5, 0.01, 0.01)});
  const Collider ball = convexCollider(SphereShape{0.05});
  const SweptMotion spin =
      SweptMotion::fromVelocities(RigidState{}, Vec3::Zero(), Vec3(0, 0, 100.0), 0.01);
  const Transform ballPose{Mat3::Identity(), Vec3(0.3, 0.3, 0.0)};
  const TimeOfImpact toi = conservativeAdvancement(
      rod, spin, ball, SweptMotion::stationary(stateAt(ballPose.translation)), ccd(100));
  ASSERT_EQ(toi.status, ImpactStatus::Hit);
  EXPECT_LE(toi.distance, kTolerance);

  // Dense sampling: the first sample in contact comes after the reported time.
  double firstContact = 1.0;
  for (int i = 0; i <= 20000; ++i) {
    const double s = i / 20000.0;
    if (colliderDistance(rod, spin.poseAt(s), ball, ballPose).distance <= 0.0) {
      firstContact = s;
      break;
    }
  }
  ASSERT_LT(firstContact, 1.0);
  EXPECT_LE(toi.fraction, firstContact);
  EXPECT_GE(toi.fraction, firstContact - 1e-3);
  // The normal points from the rod towards the ball.
  EXPECT_GT(toi.normal.dot(ballPose.translation - toi.pointA), 0.0);
}

TEST(TimeOfImpact, ConservativeAdvancementSeesSeparatingAndOverlappingPairs) {
  const Collider ball = convexCollider(SphereShape{0.1});
  const SweptMotion away =
      SweptMotion::fromVelocities(stateAt(Vec3(0, 0, 1)), Vec3(0, 0, 10), Vec3::Zero(), 0.01);
  EXPECT_EQ(
      conservativeAdvancement(groundCollider(), SweptMotion::stationary(RigidState{}), ball, away)
          .status,
      ImpactStatus::Separated);
  const SweptMotion tooShort =
      SweptMotion::fromVelocities(stateAt(Vec3(0, 0, 1)), Vec3(0, 0, -10), Vec3::Zero(), 0.01);
  EXPECT_EQ(conservativeAdvancement(groundCollider(), SweptMotion::stationary(RigidState{}), ball,
                                    tooShort)
                .status,
            ImpactStatus::Separated);
  const SweptMotion inside = SweptMotion::stationary(stateAt(Vec3(0, 0, 0.05)));
  const TimeOfImpact overlapping = conservativeAdvancement(
      groundCollider(), SweptMotion::stationary(RigidState{}), ball, inside);
  EXPECT_EQ(overlapping.status, ImpactStatus::Overlapping);
  EXPECT_EQ(overlapping.fraction, 0.0);
}

TEST(TimeOfImpact, SweptMotionInterpolatesBetweenStates) {
  const RigidState start = stateAt(Vec3(1, 2, 3), Quaternion::fromAxisAngle(Vec3(1, 1, 0), 0.3));
  const RigidState end = stateAt(Vec3(2, 2, 1), Quaternion::fromAxisAngle(Vec3(0, 1, 1), 1.2));
  const SweptMotion motion = SweptMotion::between(start, end);
  const Transform atEnd = motion.poseAt(1.0);
  EXPECT_TRUE(atEnd.translation.isApprox(end.position));
  EXPECT_TRUE(atEnd.rotation.isApprox(end.orientation.toRotationMatrix(), 1e-12));
  EXPECT_TRUE(motion.poseAt(0.0).rotation.isApprox(start.orientation.toRotationMatrix()));
  // Halfway, the rotation is half of the relative one.
  const Mat3 relative = atEnd.rotation * start.orientation.toRotationMatrix().transpose();
  const Mat3 half = motion.poseAt(0.5).rotation * start.orientation.toRotationMatrix().transpose();
  EXPECT_TRUE((half * half).isApprox(relative, 1e-12));
}

TEST(TimeOfImpact, ContinuousTimeOfImpactOfTwoBodies) {
  World world;
  BodyDef wall;
  wall.name = "wall";
  wall.shape = BoxShape{Vec3(0.0025, 1, 1)};
  wall.isStatic = true;
  BodyDef ball;
  ball.name = "ball";
  ball.shape = SphereShape{0.01};
  ball.position = Vec3(-0.2, 0, 0);
  const auto wallId = world.createBody(wall);
  const auto ballId = world.createBody(ball);
  ASSERT_TRUE(wallId && ballId);
  const Body& ballBody = testing::bodyCopy(world, *ballId);
  RigidState end = ballBody.state();
  end.position.x() += 0.5;
  const TimeOfImpact toi =
      continuousTimeOfImpact(testing::bodyCopy(world, *wallId), world.body(*wallId).state(), ballBody, end);
  ASSERT_EQ(toi.status, ImpactStatus::Hit);
  EXPECT_NEAR(toi.fraction, 0.375, 2 * kTolerance / 0.5);
  EXPECT_TRUE(toi.normal.isApprox(-Vec3::UnitX(), 1e-9));
}

}  // namespace
}  // namespace rbsim
