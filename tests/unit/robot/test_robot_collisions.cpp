// Collision filtering in world files (config/collision_filter_config.h): a
// body's collision_group and collision_mask, and a robot's self_collision,
// disable_collisions and link_collision. folded_arm.urdf folds back onto its
// base so that every link overlaps it: 'upper' is joined to the base,
// 'fore' and 'tool' are not. Which pairs touch after a step says what the
// filters did; mistakes point at the world file's line, column and key.

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <utility>

#include "config/config_loader.h"
#include "rbsim/physics/world.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

const std::string kUrdfDir = std::string(rbsim::test_support::kTestDataDir) + "/urdf";

Expected<WorldDef> parse(const std::string& yaml) { return parseWorldConfig(yaml, "w.yaml", kUrdfDir); }

std::string errorOf(const std::string& yaml) {
  const Expected<WorldDef> world = parse(yaml);
  if (world.ok()) {
    ADD_FAILURE() << "accepted:\n" << yaml;
    return "";
  }
  return world.error().message;
}

using NamePairs = std::set<std::pair<std::string, std::string>>;

// The pairs of bodies in contact after one weightless step of the world.
NamePairs touchingAfterAStep(const std::string& yaml) {
  Expected<WorldDef> def = parse("world: {gravity: [0, 0, 0]}\n" + yaml);
  if (!def) {
    ADD_FAILURE() << def.error().message;
    return {};
  }
  Expected<World> world = World::fromDef(*def);
  if (!world) {
    ADD_FAILURE() << world.error().message;
    return {};
  }
  world->step();
  const auto nameOf = [&](int32_t serial) {
    for (const BodyView body : world->bodies())
      if (body.serial() == serial) return body.name();
    return std::string("?");
  };
  NamePairs pairs;
  for (const SolvedManifold& m : world->contacts()) {
    std::string a = nameOf(m.serialA), b = nameOf(m.serialB);
    if (b < a) std::swap(a, b);
    pairs.emplace(a, b);
  }
  return pairs;
}

const std::string kArm = "robots:\n  - name: arm\n    urdf: folded_arm.urdf\n    fixed_base: true\n";

TEST(RobotCollisions, ARobotsLinksDoNotCollideWithEachOtherByDefault) {
  EXPECT_EQ(touchingAfterAStep(kArm), NamePairs{});
  EXPECT_EQ(touchingAfterAStep(kArm + "    self_collision: false\n"), NamePairs{});
  // Its links still collide with the rest of the world.
  EXPECT_EQ(touchingAfterAStep(kArm + "bodies:\n  - {name: block, position: [0, 0, 0.1],\n"
                                      "     shape: {type: box, half_extents: [0.35, 0.05, 0.05]}}\n"),
            (NamePairs{{"arm/base", "block"}, {"arm/fore", "block"}, {"arm/tool", "block"}, {"arm/upper", "block"}}));
}

TEST(RobotCollisions, SelfCollisionOnLeavesOutJoinedLinksOnly) {
  // 'upper' overlaps the base as much as 'fore' and 'tool' do, but a joint joins them.
  EXPECT_EQ(touchingAfterAStep(kArm + "    self_collision: true\n"),
            (NamePairs{{"arm/base", "arm/fore"}, {"arm/base", "arm/tool"}}));
}

TEST(RobotCollisions, DisableCollisionsRemovesPairsWithSelfCollisionOn) {
  EXPECT_EQ(touchingAfterAStep(kArm + "    self_collision: true\n    disable_collisions: [[tool, base]]\n"),
            (NamePairs{{"arm/base", "arm/fore"}}));
  EXPECT_EQ(touchingAfterAStep(kArm + "    self_collision: true\n"
                                      "    disable_collisions: [[base, fore], [base, tool], [upper, tool]]\n"),
            NamePairs{});
}

TEST(RobotCollisions, LinkFiltersSetTheLinksGroupsAndMasks) {
  // fore in group 2, which the base's mask leaves out; tool keeps the defaults.
  const std::string yaml = kArm + "    self_collision: true\n"
                                  "    link_collision: {fore: {group: 2}, base: {mask: 0xFFFFFFFD}}\n";
  EXPECT_EQ(touchingAfterAStep(yaml), (NamePairs{{"arm/base", "arm/tool"}}));
  const Expected<WorldDef> def = parse(yaml);
  ASSERT_TRUE(def.ok()) << def.error().message;
  const auto body = [&](const std::string& name) {
    return *std::find_if(def->bodies.begin(), def->bodies.end(), [&](const BodyDef& b) { return b.name == name; });
  };
  EXPECT_EQ(body("arm/fore").collisionFilter, (CollisionFilter{2, CollisionFilter::kAllBits}));
  EXPECT_EQ(body("arm/base").collisionFilter, (CollisionFilter{1, 0xFFFFFFFDu}));
  EXPECT_EQ(body("arm/tool").collisionFilter, CollisionFilter{});
}

TEST(RobotCollisions, TheLoadReportSaysWhatSelfCollisionIs) {
  const Expected<Config> off = parseConfig(kArm, "w.yaml", kUrdfDir);
  ASSERT_TRUE(off.ok()) << off.error().message;
  const auto says = [](const std::vector<std::string>& report, const std::string& text) {
    return std::any_of(report.begin(), report.end(), [&](const std::string& line) { return line.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(says(off->robotReport, "robot 'arm': self-collision off")) << ::testing::PrintToString(off->robotReport);
  const Expected<Config> on = parseConfig(kArm + "    self_collision: true\n    disable_collisions: [[tool, base]]\n",
                                          "w.yaml", kUrdfDir);
  ASSERT_TRUE(on.ok()) << on.error().message;
  EXPECT_TRUE(says(on->robotReport, "robot 'arm': self-collision on, 1 pairs of its bodies excluded"))
      << ::testing::PrintToString(on->robotReport);
}

TEST(RobotCollisions, BodiesTakeGroupsAndMasks) {
  const std::string boxes =
      "bodies:\n"
      "  - {name: a, shape: {type: box, half_extents: [0.5, 0.5, 0.5]}, collision_group: 2, collision_mask: 5}\n"
      "  - {name: b, position: [0, 0, 0.9], shape: {type: box, half_extents: [0.5, 0.5, 0.5]},\n"
      "     collision_group: 0x4, collision_mask: 0xFFFFFFFF}\n";
  const Expected<WorldDef> def = parse(boxes);
  ASSERT_TRUE(def.ok()) << def.error().message;
  EXPECT_EQ(def->bodies[0].collisionFilter, (CollisionFilter{2, 5}));
  EXPECT_EQ(def->bodies[1].collisionFilter, (CollisionFilter{4, 0xFFFFFFFFu}));
  EXPECT_EQ(touchingAfterAStep(boxes), (NamePairs{{"a", "b"}}));  // 2 & 0xFFFFFFFF, 4 & 5
  // a's mask leaves out b's group.
  std::string apart = boxes;
  apart.replace(apart.find("collision_mask: 5"), 17, "collision_mask: 3");
  EXPECT_EQ(touchingAfterAStep(apart), NamePairs{});
  // b's mask leaves out a's group.
  std::string apartToo = boxes;
  apartToo.replace(apartToo.find("collision_mask: 0xFFFFFFFF"), 26, "collision_mask: 0xFFFFFFFD");
  EXPECT_EQ(touchingAfterAStep(apartToo), NamePairs{});
}

TEST(RobotCollisions, MistakesPointAtTheWorldFilesLineColumnAndKey) {
  const std::string box = "shape: {type: box, half_extents: [1, 1, 1]}";
  const auto expectError = [](const std::string& message, const std::string& expected) {
    EXPECT_NE(message.find(expected), std::string::npos) << message << "\nexpected: " << expected;
  };
  expectError(errorOf("bodies:\n  - {name: a, " + box + ", collision_group: -1}\n"),
              "w.yaml:2:77: bodies[0].collision_group: expected a whole number from 0 to 4294967295 (a set of 32 "
              "collision bits; 0x for hexadecimal), got \"-1\"");
  expectError(errorOf("bodies:\n  - {name: a, " + box + ", collision_mask: 4294967296}\n"),
              "w.yaml:2:76: bodies[0].collision_mask: expected a whole number from 0 to 4294967295");
  expectError(errorOf("bodies:\n  - {name: a, " + box + ", collision_group: 1.5}\n"),
              "w.yaml:2:77: bodies[0].collision_group: expected a whole number");
  expectError(errorOf("bodies:\n  - {name: a, " + box + ", collision_group: \"1\"}\n"),
              "bodies[0].collision_group: expected a whole number");
  expectError(errorOf("bodies:\n  - {name: a, " + box + ", collision_group: [1]}\n"),
              "bodies[0].collision_group: expected a whole number from 0 to 4294967295 (a set of 32 collision "
              "bits; 0x for hexadecimal), got a list");
  expectError(errorOf(kArm + "    disable_collisions: [[base, fore], [upper, tol]]\n"),
              "w.yaml:5:48: robots[0].disable_collisions[1][1]: the robot has no link named \"tol\" (nearest: "
              "\"tool\")");
  expectError(errorOf(kArm + "    disable_collisions: [[base, fore, tool]]\n"),
              "w.yaml:5:26: robots[0].disable_collisions[0]: expected a pair of link names [link_a, link_b], got a "
              "list of 3");
  expectError(errorOf(kArm + "    disable_collisions: [[fore, fore]]\n"),
              "robots[0].disable_collisions[0][1]: a link cannot be paired with itself");
  expectError(errorOf(kArm + "    link_collision:\n      forearm: {group: 2}\n"),
              "w.yaml:6:7: robots[0].link_collision.forearm: the robot has no link named \"forearm\" (nearest: "
              "\"fore\")");
  expectError(errorOf(kArm + "    link_collision: {fore: {group: 2, colour: red}}\n"),
              "robots[0].link_collision.fore.colour: unknown key; a link's collision filter has: group, mask");
  expectError(errorOf(kArm + "    link_collision: {fore: {mask: 0x1FFFFFFFF}}\n"),
              "robots[0].link_collision.fore.mask: expected a whole number from 0 to 4294967295");
  expectError(errorOf(kArm + "    self_collision: yes\n"), "robots[0].self_collision");
}

}  // namespace
}  // namespace rbsim
