// Wrench modes over steps, against momenta computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "session/wrench_scheduler.h"

namespace rbsim {
namespace {

constexpr double kDt = 0.001;

World makeWorld() {
  WorldSettings settings;
  settings.dt = kDt;
  settings.gravity = Vec3::Zero();
  World world(settings);
  double x = 0.0;
  for (const char* name : {"a", "b"}) {
    BodyDef def;
    def.name = name;
    def.shape = SphereShape{0.1};
    def.mass = 2.0;
    def.position = Vec3(x, 0.0, 0.0);  // 10 m apart: the pushes never bring them together
    x -= 10.0;
    EXPECT_TRUE(world.createBody(def).ok());
  }
  return world;
}

WrenchRequest push(const std::string& client, const std::string& body, double fx, WrenchMode mode,
                   int64_t firstStep, int64_t durationSteps = 1) {
  WrenchRequest r;
  r.client = client;
  r.body = body;
  r.force = Vec3(fx, 0, 0);
  r.mode = mode;
  r.firstStep = firstStep;
  r.durationSteps = durationSteps;
  return r;
}

void run(World& world, WrenchScheduler& scheduler, int steps) {
  for (int i = 0; i < steps; ++i) {
    const int64_t step = world.stepCount() + 1;
    scheduler.applyForStep(world, step);
    world.step();
    scheduler.finishStep(step);
  }
}

double momentumX(const World& world, const char* name) {
  return world.body(world.findBody(name)).linearMomentum().x();
}

TEST(WrenchScheduler, OneStepActsOnceDurationActsItsSteps) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 10.0, WrenchMode::OneStep, 1));
  scheduler.add(push("c", "b", 10.0, WrenchMode::Duration, 1, 25));
  run(world, scheduler, 100);
  EXPECT_NEAR(momentumX(world, "a"), 10.0 * kDt, 1e-15);
  EXPECT_NEAR(momentumX(world, "b"), 10.0 * kDt * 25, 1e-13);
  EXPECT_EQ(scheduler.activeCount(), 0);
}

TEST(WrenchScheduler, ScheduledWrenchStartsAtItsStep) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 1.0, WrenchMode::OneStep, 5));
  run(world, scheduler, 4);
  EXPECT_EQ(momentumX(world, "a"), 0.0);
  run(world, scheduler, 1);  // step 5
  EXPECT_NEAR(momentumX(world, "a"), kDt, 1e-18);
}

TEST(WrenchScheduler, PersistentIsReplacedPerClientAndBodyAndCleared) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 1.0, WrenchMode::Persistent, 1));
  scheduler.add(push("other", "a", 0.5, WrenchMode::Persistent, 1));
  run(world, scheduler, 10);  // 1.5 N for 10 steps
  scheduler.add(push("c", "a", 3.0, WrenchMode::Persistent, 11));  // replaces c's 1 N
  run(world, scheduler, 10);  // 3.5 N for 10 steps
  EXPECT_EQ(scheduler.activeCount(), 2);
  WrenchRequest clear = push("c", "a", 0.0, WrenchMode::Clear, 21);
  scheduler.add(clear);
  run(world, scheduler, 10);  // only other's 0.5 N
  EXPECT_NEAR(momentumX(world, "a"), (1.5 * 10 + 3.5 * 10 + 0.5 * 10) * kDt, 1e-14);
  EXPECT_EQ(scheduler.activeCount(), 1);
  // Clear with an empty body clears the client on every body.
  scheduler.add(push("other", "b", 1.0, WrenchMode::Duration, 31, 1000));
  WrenchRequest clearAll = push("other", "", 0.0, WrenchMode::Clear, 31);
  scheduler.add(clearAll);
  run(world, scheduler, 1);
  EXPECT_EQ(scheduler.activeCount(), 0);
}

// The count a clear's ack carries is what the clear then removes, whether it
// acts at once or later, among wrenches that start or run out before it.
TEST(WrenchScheduler, CountClearedByIsWhatTheClearRemoves) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 1.0, WrenchMode::Persistent, 1));
  scheduler.add(push("c", "a", 2.0, WrenchMode::Persistent, 1));  // replaces the first
  scheduler.add(push("c", "a", 1.0, WrenchMode::Duration, 1, 5));   // over by step 5
  scheduler.add(push("c", "a", 1.0, WrenchMode::Duration, 1, 50));
  scheduler.add(push("c", "a", 1.0, WrenchMode::OneStep, 1));       // never counted
  scheduler.add(push("c", "b", 1.0, WrenchMode::Persistent, 1));    // another body
  scheduler.add(push("other", "a", 1.0, WrenchMode::Persistent, 1));  // another client
  run(world, scheduler, 2);
  scheduler.add(push("c", "a", 1.0, WrenchMode::Duration, 8, 10));  // pending, starts before
  scheduler.add(push("c", "a", 1.0, WrenchMode::Persistent, 30));   // pending, starts after

  WrenchRequest clear = push("c", "a", 0.0, WrenchMode::Clear, 10);
  // Acting at step 10: the 2 N persistent, the 50-step duration and the
  // duration from step 8; the 5-step one has run out.
  EXPECT_EQ(scheduler.countClearedBy(clear), 3);
  WrenchRequest now = push("c", "a", 0.0, WrenchMode::Clear, 3);
  EXPECT_EQ(scheduler.countClearedBy(now), 3);  // the 5-step duration still acts at step 3
  WrenchRequest all = push("c", "", 0.0, WrenchMode::Clear, 10);
  EXPECT_EQ(scheduler.countClearedBy(all), 4);  // and b's
  WrenchRequest everyClient = push("x", "a", 0.0, WrenchMode::ClearAllClients, 10);
  EXPECT_EQ(scheduler.countClearedBy(everyClient), 4);  // and other's on a
  WrenchRequest nobody = push("x", "a", 0.0, WrenchMode::Clear, 10);
  EXPECT_EQ(scheduler.countClearedBy(nobody), 0);

  // What the scheduler then does: 3 of the 6 acting at step 10 go.
  scheduler.add(clear);
  run(world, scheduler, 7);  // steps 3..9
  const int before = scheduler.activeCount();
  EXPECT_EQ(before, 5);      // a: 2 N, 50-step, step-8 duration; b; other
  run(world, scheduler, 1);  // step 10
  EXPECT_EQ(scheduler.activeCount(), before - 3);
}

TEST(WrenchScheduler, ClearAllClientsClearsEveryClientsOnTheBody) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 1.0, WrenchMode::Persistent, 1));
  scheduler.add(push("other", "a", 1.0, WrenchMode::Persistent, 1));
  scheduler.add(push("other", "b", 1.0, WrenchMode::Persistent, 1));
  run(world, scheduler, 1);
  scheduler.add(push("third", "a", 0.0, WrenchMode::ClearAllClients, 2));
  run(world, scheduler, 1);
  ASSERT_EQ(scheduler.activeCount(), 1);
  EXPECT_EQ(scheduler.active().front().body, "b");
}

TEST(WrenchScheduler, WrenchOnRemovedBodyIsDropped) {
  World world = makeWorld();
  WrenchScheduler scheduler;
  scheduler.add(push("c", "a", 1.0, WrenchMode::Persistent, 1));
  run(world, scheduler, 2);
  world.removeBody(world.findBody("a"));
  run(world, scheduler, 1);
  EXPECT_EQ(scheduler.activeCount(), 0);
}

// A world point is taken into the body when the wrench first acts, not when
// it is accepted, and from then on moves with the body: on a box sliding
// along x, a sideways force at a point above its centre turns it about x
// only. Were the point left behind in the world, the lever arm would grow
// along −x and so would a torque about z, −F v t.
TEST(WrenchScheduler, AWorldPointIsFixedInTheBodyWhenTheWrenchFirstActs) {
  WorldSettings settings;
  settings.dt = kDt;
  settings.gravity = Vec3::Zero();
  World world(settings);
  BodyDef def;
  def.name = "slider";
  def.shape = BoxShape{Vec3(0.1, 0.2, 0.3)};
  def.mass = 2.0;
  def.linearVelocity = Vec3(1.0, 0.0, 0.0);
  ASSERT_TRUE(world.createBody(def).ok());
  WrenchScheduler scheduler;
  WrenchRequest r = push("c", "slider", 0.0, WrenchMode::Duration, 51, 100);
  r.force = Vec3(0.0, 0.5, 0.0);
  r.point = Vec3(0.05, 0.0, 0.2);  // where the centre will be at the start of step 51, plus 0.2 z
  scheduler.add(r);
  run(world, scheduler, 50);
  EXPECT_EQ(world.body(world.findBody("slider")).angularMomentum(), Vec3::Zero());
  run(world, scheduler, 1);  // step 51: the point is fixed in the body
  ASSERT_EQ(scheduler.activeCount(), 1);
  EXPECT_EQ(scheduler.active()[0].pointFrame, WrenchFrame::ShapeFrame);
  EXPECT_LT((scheduler.active()[0].point - Vec3(0.0, 0.0, 0.2)).norm(), 1e-12);
  run(world, scheduler, 99);
  const BodyView body = world.body(world.findBody("slider"));
  EXPECT_LT((body.linearMomentum() - Vec3(2.0, 0.5 * 100 * kDt, 0.0)).norm(), 1e-14);
  EXPECT_LT(body.angularMomentum().x(), -0.9 * 0.2 * 0.5 * 100 * kDt);  // about −0.2 F T
  // Zero but for the rounding of the captured point (the old world-fixed
  // point gave L_z = −F v T²/2 = −2.5e-3 N·m·s here).
  EXPECT_LT(std::abs(body.angularMomentum().y()), 1e-15);
  EXPECT_LT(std::abs(body.angularMomentum().z()), 1e-15);
}

// Body-frame points and vectors are in the frame the body is given in (its
// shape frame), not in the principal frame. Two equal spheres 0.5 m apart
// along the compound's x: the centre of mass is at (0.25, 0, 0) there and
// the principal frame is turned and shifted against the shape frame.
TEST(WrenchScheduler, BodyFramePointsAndVectorsAreInTheShapeFrame) {
  WorldSettings settings;
  settings.dt = kDt;
  settings.gravity = Vec3::Zero();
  settings.integrator = IntegratorKind::SemiImplicitEuler;  // the load at the start of the step
  World world(settings);
  BodyDef def;
  def.name = "dumbbell";
  CompoundShape compound;
  compound.parts.push_back({SphereShape{0.1}, Vec3::Zero(), Quaternion::identity(), std::nullopt});
  compound.parts.push_back(
      {SphereShape{0.1}, Vec3(0.5, 0, 0), Quaternion::identity(), std::nullopt});
  def.shape = compound;
  def.orientation = Quaternion::fromRollPitchYaw(0.3, -0.6, 1.2);  // shape -> world
  ASSERT_TRUE(world.createBody(def).ok());
  const BodyId id = world.findBody("dumbbell");
  ASSERT_GT((world.body(id).description().shapeTranslation).norm(), 0.2);
  const Quaternion shapeToWorld = def.orientation;

  // A body-frame force through the centre of mass (shape point (0.25, 0, 0)).
  WrenchScheduler scheduler;
  WrenchRequest through = push("c", "dumbbell", 0.0, WrenchMode::OneStep, 1);
  through.frame = WrenchFrame::ShapeFrame;
  through.pointFrame = WrenchFrame::ShapeFrame;
  through.force = Vec3(0.0, 1.0, 0.0);
  through.point = Vec3(0.25, 0.0, 0.0);
  scheduler.add(through);
  run(world, scheduler, 1);
  const Vec3 worldForce = shapeToWorld.rotate(through.force);
  EXPECT_LT((world.body(id).linearMomentum() - kDt * worldForce).norm(), 1e-15);
  EXPECT_LT(world.body(id).angularMomentum().norm(), 1e-15);

  // A world-frame force at the first sphere's centre, the shape origin: its
  // lever arm is −0.25 along the shape's x.
  const BodyView body = world.body(id);
  const Vec3 lever = body.rotation() * body.description().shapeToBodyPoint(Vec3::Zero());
  EXPECT_LT((lever - shapeToWorld.rotate(Vec3(-0.25, 0, 0))).norm(), 1e-12);  // not turned
  const Vec3 l0 = body.angularMomentum();
  WrenchRequest atOrigin = push("c", "dumbbell", 0.0, WrenchMode::OneStep, 2);
  atOrigin.pointFrame = WrenchFrame::ShapeFrame;
  atOrigin.force = Vec3(0.0, 0.0, 3.0);
  atOrigin.point = Vec3::Zero();
  scheduler.add(atOrigin);
  run(world, scheduler, 1);
  EXPECT_LT((world.body(id).angularMomentum() - l0 - kDt * lever.cross(atOrigin.force)).norm(),
            1e-15);
}

}  // namespace
}  // namespace rbsim
