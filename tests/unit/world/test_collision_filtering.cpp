// Collision filtering (rbsim/physics/collision_filter.h): groups and masks
// in Bullet's convention, bodies joined by a joint, pairs excluded one by
// one. Two overlapping boxes touch exactly when every rule lets them; the
// filters survive a snapshot, and a restored world steps on bit for bit.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rbsim/physics/world.h"

namespace rbsim {
namespace {

WorldSettings weightless() {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  settings.threads = 1;
  return settings;
}

BodyId addBox(World& world, const std::string& name, const Vec3& position,
              const CollisionFilter& filter = {}) {
  BodyDef def;
  def.name = name;
  def.shape = BoxShape{Vec3::Constant(0.5)};
  def.position = position;
  def.collisionFilter = filter;
  const Expected<BodyId> id = world.createBody(def);
  EXPECT_TRUE(id.ok()) << id.error().message;
  return id.ok() ? *id : BodyId{};
}

// Whether the last step's contacts hold the pair of a and b.
bool touching(const World& world, BodyId a, BodyId b) {
  const int32_t serialA = world.body(a).serial();
  const int32_t serialB = world.body(b).serial();
  for (const SolvedManifold& m : world.contacts())
    if ((m.serialA == serialA && m.serialB == serialB) || (m.serialA == serialB && m.serialB == serialA))
      return true;
  return false;
}

// Two unit boxes 0.1 m into each other, weightless: whether they touch
// after one step with these filters (and whether canCollide agrees).
bool overlappingBoxesTouch(const CollisionFilter& filterA, const CollisionFilter& filterB) {
  World world(weightless());
  const BodyId a = addBox(world, "a", Vec3::Zero(), filterA);
  const BodyId b = addBox(world, "b", Vec3(0, 0, 0.9), filterB);
  const bool allowed = world.canCollide(a, b);
  EXPECT_EQ(allowed, world.canCollide(b, a));
  world.step();
  EXPECT_EQ(touching(world, a, b), allowed);
  return touching(world, a, b);
}

TEST(CollisionFilters, DefaultsCollideWithEverything) {
  const CollisionFilter defaults;
  EXPECT_EQ(defaults.group, 1u);
  EXPECT_EQ(defaults.mask, 0xFFFFFFFFu);
  EXPECT_TRUE(overlappingBoxesTouch(defaults, defaults));
}

TEST(CollisionFilters, GroupsAndMasksMustAllowBothWays) {
  // A in group 2, B in group 4.
  const auto filter = [](uint32_t group, uint32_t mask) { return CollisionFilter{group, mask}; };
  // A's mask leaves out B's group (B would take A).
  EXPECT_FALSE(overlappingBoxesTouch(filter(2, ~4u), filter(4, CollisionFilter::kAllBits)));
  // B's mask leaves out A's group (A would take B).
  EXPECT_FALSE(overlappingBoxesTouch(filter(2, CollisionFilter::kAllBits), filter(4, ~2u)));
  // Each mask takes exactly the other's group.
  EXPECT_TRUE(overlappingBoxesTouch(filter(2, 4), filter(4, 2)));
  // Several bits: one shared bit either way is enough.
  EXPECT_TRUE(overlappingBoxesTouch(filter(2 | 8, 16 | 4), filter(4 | 1, 8)));
  // A group of 0 is in no category: nothing takes it.
  EXPECT_FALSE(overlappingBoxesTouch(filter(0, CollisionFilter::kAllBits), filter(1, CollisionFilter::kAllBits)));
}

TEST(CollisionFilters, AFilteredBodyStillRestsOnWhatItsMaskTakes) {
  // A box in group 2 that collides with the ground (group 1) but not with
  // another box of group 2 falls through that box onto the ground.
  WorldSettings settings = weightless();
  settings.gravity = Vec3(0, 0, -9.81);
  World world(settings);
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  const BodyId groundId = *world.createBody(ground);
  const BodyId lower = addBox(world, "lower", Vec3(0, 0, 0.5), {2, 1});
  const BodyId upper = addBox(world, "upper", Vec3(0, 0, 1.2), {2, 1});
  for (int i = 0; i < 1000; ++i) world.step();
  EXPECT_TRUE(touching(world, groundId, lower));
  EXPECT_TRUE(touching(world, groundId, upper));
  EXPECT_FALSE(touching(world, lower, upper));
  EXPECT_NEAR(world.body(upper).position().z(), 0.5, 0.01);  // inside the lower box, on the ground
}

TEST(CollisionFilters, AnExcludedPairNeverTouchesUntilTheExclusionIsTakenBack) {
  World world(weightless());
  const BodyId a = addBox(world, "a", Vec3::Zero());
  const BodyId b = addBox(world, "b", Vec3(0, 0, 0.9));
  const BodyId c = addBox(world, "c", Vec3(0, 0, -0.9));
  ASSERT_TRUE(world.setPairCollision(b, a, false).ok());
  EXPECT_FALSE(world.canCollide(a, b));
  EXPECT_TRUE(world.canCollide(a, c));
  ASSERT_EQ(world.excludedPairs().size(), 1u);
  EXPECT_EQ(world.excludedPairs()[0], std::make_pair(a, b));  // creation order
  world.step();
  EXPECT_FALSE(touching(world, a, b));
  EXPECT_TRUE(touching(world, a, c));

  ASSERT_TRUE(world.setPairCollision(a, b, true).ok());
  EXPECT_TRUE(world.excludedPairs().empty());
  world.step();
  EXPECT_TRUE(touching(world, a, b));

  EXPECT_FALSE(world.setPairCollision(a, a, false).ok());
  EXPECT_FALSE(world.setPairCollision(a, BodyId{}, false).ok());
  // Removing a body drops its exclusions.
  ASSERT_TRUE(world.setPairCollision(a, b, false).ok());
  ASSERT_TRUE(world.setPairCollision(b, c, false).ok());
  ASSERT_TRUE(world.removeBody(b).ok());
  EXPECT_TRUE(world.excludedPairs().empty());
}

TEST(CollisionFilters, JoinedBodiesCollideOnlyWithCollideConnected) {
  for (const bool collideConnected : {false, true}) {
    World world(weightless());
    const BodyId a = addBox(world, "a", Vec3::Zero());
    const BodyId b = addBox(world, "b", Vec3(0, 0, 0.9));
    JointDef hinge;
    hinge.name = "hinge";
    hinge.type = JointType::Revolute;
    hinge.bodyA = a;
    hinge.bodyB = b;
    hinge.anchor = Vec3(0, 0, 0.45);
    hinge.axis = Vec3::UnitY();
    hinge.collideConnected = collideConnected;
    const Expected<JointId> joint = world.createJoint(hinge);
    ASSERT_TRUE(joint.ok()) << joint.error().message;
    EXPECT_EQ(world.canCollide(a, b), collideConnected);
    world.step();
    EXPECT_EQ(touching(world, a, b), collideConnected);
    // Without the joint they touch.
    ASSERT_TRUE(world.removeJoint(*joint).ok());
    EXPECT_TRUE(world.canCollide(a, b));
    world.step();
    EXPECT_TRUE(touching(world, a, b));
  }
}

TEST(CollisionFilters, WorldDefExcludesNamedPairs) {
  WorldDef def;
  def.settings = weightless();
  for (const auto& [name, z] : {std::pair<std::string, double>{"a", 0.0}, {"b", 0.9}}) {
    BodyDef box;
    box.name = name;
    box.shape = BoxShape{Vec3::Constant(0.5)};
    box.position = Vec3(0, 0, z);
    def.bodies.push_back(box);
  }
  def.excludedPairs.push_back({"a", "b"});
  Expected<World> world = World::fromDef(def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_FALSE(world->canCollide(world->findBody("a"), world->findBody("b")));
  def.excludedPairs = {{"a", "nobody"}};
  const Expected<World> bad = World::fromDef(def);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("no body named 'nobody'"), std::string::npos) << bad.error().message;
}

// A small pile in which filters decide: boxes of two groups that pass
// through each other's group, two of them kept apart by an exclusion, a
// jointed pair; on the ground.
World filteredPile(int threads) {
  WorldSettings settings;
  settings.threads = threads;
  World world(settings);
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  EXPECT_TRUE(world.createBody(ground).ok());
  std::vector<BodyId> boxes;
  for (int i = 0; i < 12; ++i) {
    const uint32_t group = i % 2 == 0 ? 2u : 4u;
    const CollisionFilter filter{group, 1u | group};  // the ground and its own group
    boxes.push_back(addBox(world, "box" + std::to_string(i),
                           Vec3(0.3 * (i % 3), 0.2 * (i % 4), 0.6 + 0.8 * i), filter));
  }
  EXPECT_TRUE(world.setPairCollision(boxes[0], boxes[2], false).ok());
  JointDef hinge;
  hinge.name = "hinge";
  hinge.bodyA = boxes[4];
  hinge.bodyB = boxes[6];
  hinge.anchor = 0.5 * (world.body(boxes[4]).position() + world.body(boxes[6]).position());
  hinge.axis = Vec3::UnitX();
  EXPECT_TRUE(world.createJoint(hinge).ok());
  return world;
}

TEST(CollisionFilters, SnapshotKeepsFiltersAndARestoredWorldStepsOnBitForBit) {
  World world = filteredPile(1);
  for (int i = 0; i < 300; ++i) world.step();
  const Expected<std::vector<uint8_t>> bytes = world.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  Expected<World> restored = World::decodeSnapshot(*bytes, world.settings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  // Ids carry their world's tag: compare the pairs by name.
  const auto names = [](const World& w) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& [a, b] : w.excludedPairs()) out.emplace_back(w.body(a).name(), w.body(b).name());
    return out;
  };
  ASSERT_EQ(names(world).size(), 1u);
  EXPECT_EQ(names(restored.value()), names(world));
  for (int i = 0; i < world.bodyCount(); ++i)
    EXPECT_EQ(restored->bodyAt(i).description().collisionFilter, world.bodyAt(i).description().collisionFilter)
        << world.bodyAt(i).name();
  EXPECT_EQ(restored->bodyAt(1).description().collisionFilter, (CollisionFilter{2, 3}));
  for (int i = 0; i < 500; ++i) {
    world.step();
    restored->step();
  }
  EXPECT_EQ(restored->stateHash(), world.stateHash());
  // A removed body's exclusions are not saved (the reader would refuse a
  // serial that no body has).
  World lone(world.settings());
  const BodyId a = addBox(lone, "a", Vec3::Zero());
  const BodyId b = addBox(lone, "b", Vec3(3, 0, 0));
  ASSERT_TRUE(lone.setPairCollision(a, b, false).ok());
  ASSERT_TRUE(lone.removeBody(b).ok());  // drops the pair
  Expected<World> loneBack = World::decodeSnapshot(*lone.encodeSnapshot(), lone.settings());
  ASSERT_TRUE(loneBack.ok()) << loneBack.error().message;
  EXPECT_TRUE(loneBack->excludedPairs().empty());
}

TEST(CollisionFilters, FilteredWorldIsTheSameOnAnyThreadCount) {
  World one = filteredPile(1);
  World two = filteredPile(2);
  for (int i = 0; i < 800; ++i) {
    one.step();
    two.step();
  }
  EXPECT_EQ(one.stateHash(), two.stateHash());
  // The filters did their work: the excluded pair and the jointed pair
  // never touched, though both pairs lie in one column.
  EXPECT_FALSE(touching(one, one.findBody("box0"), one.findBody("box2")));
  EXPECT_FALSE(touching(one, one.findBody("box4"), one.findBody("box6")));
}

}  // namespace
}  // namespace rbsim
