// The stacking benchmark's pyramid (bench/stacks/stack_scenes.h: Box2D's
// large pyramid made of the anchors' cubes), small enough for the suite: it
// must stand by the solver alone, without sleeping. The world is built from
// the benchmark's own plain-data scene, so the test and bench_stacks_rbsim
// simulate the same bodies.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rbsim/physics/world.h"
#include "stack_scenes.h"
#include "unit/solver/contact_test_worlds.h"

namespace rbsim {
namespace {

namespace sb = bench::stacks;

TEST(PyramidScene, IsBox2dsLargePyramidOfTheAnchorsCubes) {
  sb::Scene s;
  ASSERT_TRUE(sb::makeScene("pyramid", 0, s));
  EXPECT_EQ(s.n, 90);
  ASSERT_EQ(s.bodies.size(), 4095u);  // 90 + 89 + … + 1
  EXPECT_FALSE(s.sleep) << "the solver alone must hold it";
  EXPECT_EQ(s.steps, 10000);
  EXPECT_DOUBLE_EQ(s.dt, 1e-3);
  const sb::BodySpec& top = s.bodies[static_cast<size_t>(s.track)];
  EXPECT_DOUBLE_EQ(top.position[0], 0.0);
  EXPECT_NEAR(top.position[2], 17.9, 1e-12);
  EXPECT_DOUBLE_EQ(top.mass, 8.0);
  EXPECT_NEAR(top.inertia, 8.0 * 2 * 0.04 / 12, 1e-15);
  // The bottom row rests on the ground; neighbours in a row exactly touch;
  // each row is shifted by half a cube, so each cube rests on two.
  EXPECT_DOUBLE_EQ(s.bodies[0].position[2], 0.1);
  EXPECT_NEAR(s.bodies[1].position[0] - s.bodies[0].position[0], 0.2, 1e-12);
  EXPECT_NEAR(s.bodies[90].position[0] - s.bodies[0].position[0], 0.1, 1e-12);
  EXPECT_NEAR(s.bodies[90].position[2] - s.bodies[0].position[2], 0.2, 1e-12);
  for (const sb::BodySpec& b : s.bodies) EXPECT_EQ(b.position[1], 0.0);
}

struct PyramidRun {
  double topDriftMax = 0;   // m: the top cube's largest horizontal excursion
  double topDz = 0;         // m: its height change at the end
  double anyMoveMax = 0;    // m: the largest displacement of any cube at the end
  double deepest = 0;       // m: the deepest contact over the run
  double fastest = 0;       // m/s: the fastest cube at the end
  double finalEnergy = 0;   // J
};

// Builds the benchmark's pyramid with `base` cubes at the bottom in a world
// set as bench_stacks_rbsim sets it (friction 0.5, no restitution, no
// sleeping, the solver's defaults) and steps it for `steps` steps.
PyramidRun standPyramid(int base, int steps) {
  sb::Scene s;
  EXPECT_TRUE(sb::makeScene("pyramid", base, s));
  WorldSettings settings = testing::contactSettings(sb::kRestitution, sb::kFriction);
  settings.dt = s.dt;
  settings.gravity = Vec3(0, 0, s.gravity);
  settings.contact.sleeping = false;
  World world(settings);
  std::vector<BodyId> ids;
  for (const sb::BodySpec& b : s.bodies) {
    BodyDef def;
    def.name = "box" + std::to_string(ids.size());
    def.shape = BoxShape{Vec3::Constant(b.half)};
    def.mass = b.mass;
    def.position = Vec3(b.position[0], b.position[1], b.position[2]);
    ids.push_back(*world.createBody(def));
  }
  // After the cubes, as bench_stacks_rbsim does: the order of the bodies is
  // the solver's order, and so the test steps the benchmark's very world.
  testing::addGround(world);
  const BodyId top = ids[static_cast<size_t>(s.track)];
  const Vec3 start = world.body(top).position();
  PyramidRun r;
  for (int i = 0; i < steps; ++i) {
    world.step();
    const Vec3 d = world.body(top).position() - start;
    r.topDriftMax = std::max(r.topDriftMax, std::hypot(d.x(), d.y()));
    r.deepest = std::max(r.deepest, testing::deepestContact(world));
  }
  r.topDz = world.body(top).position().z() - start.z();
  for (size_t i = 0; i < ids.size(); ++i) {
    const sb::Vec3& p0 = s.bodies[i].position;
    const Vec3 moved = world.body(ids[i]).position() - Vec3(p0[0], p0[1], p0[2]);
    r.anyMoveMax = std::max(r.anyMoveMax, moved.norm());
    r.fastest = std::max(r.fastest, world.body(ids[i]).linearVelocity().norm());
  }
  r.finalEnergy = world.totalKineticEnergy();
  return r;
}

// Issue 16's criterion on a pyramid the suite can afford: base 20 (210
// cubes, 4.0 m tall) for 2 s, about 4.5 s in Release. An unoptimised build
// steps some 185 times slower (14 min for it), so there, as in Box2D's own
// benchmarks, the pyramid is smaller: base 10 (55 cubes). The top cube
// drifts less than 1 mm, and so does every other cube (none slides out or
// sinks). At the end it is at rest: no cube moves visibly (1 mm/s), and the
// kinetic energy is below 1e-5 J, that of the whole base-20 pyramid
// (1680 kg) sliding at 0.11 mm/s. A sequential-impulse solver does not hold
// 2360 contact points exactly still (friction micro-slips now and then, and
// settles again: rbsim's base-20 pyramid has 1.6e-8 J at 1 s, 2.0e-6 J at
// 2 s, 1e-22 J at 8 s; Bullet's, the same cubes and solver family, 3.1e-6 J
// at 2 s), so the bound is on motion one could see, not on numerical zero.
// bench_stacks_rbsim --scene pyramid --n 20 --steps 2000 steps this very
// world (same bodies, same order) and reports the same figures.
#ifdef NDEBUG
constexpr int kTestBase = 20;
#else
constexpr int kTestBase = 10;
#endif

TEST(Pyramid, StandsTwoSecondsWithoutSleeping) {
  const PyramidRun r = standPyramid(kTestBase, 2000);
  EXPECT_LT(r.topDriftMax, 1e-3) << "the top cube drifted sideways";
  EXPECT_LT(std::abs(r.topDz), 1e-3) << "the top cube sank or rose";
  EXPECT_LT(r.anyMoveMax, 1e-3) << "a cube moved";
  EXPECT_LT(r.deepest, 1e-3);
  EXPECT_LT(r.fastest, 1e-3) << "a cube is still moving at the end";
  EXPECT_LT(r.finalEnergy, 1e-5) << "the pyramid is still moving at the end";
}

#ifdef RBSIM_TEST_SOFT_STEP
// Issue 38's criterion for the soft-step solver: the pyramid stands 10 s
// with its top within a tenth of a millimetre (base 20 in Release, base 10
// in Debug), at rest at the end. (Sub-steps hold it where sequential
// impulses let the top wander 0.2 mm in 2 s, which their own test allows.)
TEST(Pyramid, StandsTenSecondsWithItsTopWithinATenthOfAMillimetre) {
  const PyramidRun r = standPyramid(kTestBase, 10000);
  EXPECT_LT(r.topDriftMax, 1e-4) << "the top cube drifted sideways";
  EXPECT_LT(std::abs(r.topDz), 1e-4) << "the top cube sank or rose";
  EXPECT_LT(r.anyMoveMax, 1e-3) << "a cube moved";
  EXPECT_LT(r.fastest, 1e-3) << "a cube is still moving at the end";
  EXPECT_LT(r.finalEnergy, 1e-9) << "the pyramid is still moving at the end";
}
#endif

}  // namespace
}  // namespace rbsim
