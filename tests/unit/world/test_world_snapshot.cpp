// Checkpoints of the world: a world restored from its snapshot continues
// bit-identically (contacts, warm starting and sleeping included), and bad
// snapshot data is refused with a message, never misread.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <span>
#include <vector>

#include "meshio/mesh_io.h"
#include "rbsim/physics/world.h"
#include "scenes/scene_random.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

WorldSettings pileSettings() {
  WorldSettings settings;
  settings.dt = 1e-3;
  settings.contact.defaultMaterial.friction = 0.6;
  settings.contact.defaultMaterial.restitution = 0.1;
  return settings;
}

// A pile of boxes with a few of every other shape, dropped on the ground;
// one body removed so that the slot table has a hole.
World makePile() {
  World world(pileSettings());
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  EXPECT_TRUE(world.createBody(ground).ok());
  auto cube = loadMesh(std::string(rbsim::test_support::kTestDataDir) + "/meshes/cube.obj");
  EXPECT_TRUE(cube.ok());
  const auto mesh = std::make_shared<const TriangleMesh>(std::move(cube).value());
  scenes::SceneRandom random(0x5eedu);
  for (int i = 0; i < 36; ++i) {
    const int layer = i / 9, column = i % 9;
    BodyDef def;
    def.name = "body" + std::to_string(i);
    switch (i % 9) {
      case 4: def.shape = SphereShape{0.1}; break;
      case 5: def.shape = CapsuleShape{0.07, 0.08}; break;
      case 7: def.shape = CylinderShape{0.09, 0.08}; break;
      case 8: def.shape = MeshShape{"cube.obj", mesh}; def.mass = 0.8; break;
      case 6: {  // a compound: a rod between a denser ball and a turned capsule
        CompoundShape dumbbell;
        dumbbell.parts.push_back({BoxShape{Vec3(0.08, 0.02, 0.02)}, Vec3::Zero(), Quaternion::identity(), {}});
        dumbbell.parts.push_back({SphereShape{0.04}, Vec3(0.1, 0, 0), Quaternion::identity(), 3000.0});
        dumbbell.parts.push_back({CapsuleShape{0.03, 0.03}, Vec3(-0.1, 0, 0),
                                  Quaternion::fromAxisAngle(Vec3::UnitX(), 0.3), {}});
        def.shape = dumbbell;
        break;
      }
      default: def.shape = BoxShape{Vec3(0.1, 0.09, 0.08)};
    }
    def.position = Vec3((column % 3 - 1) * 0.23 + random.uniform(-0.01, 0.01),
                        (column / 3 - 1) * 0.23 + random.uniform(-0.01, 0.01), 0.15 + 0.24 * layer);
    def.orientation = Quaternion::fromAxisAngle(Vec3(random.uniform(-1, 1), random.uniform(-1, 1), 1.0),
                                                random.uniform(-0.2, 0.2));
    def.material.restitution = i % 5 == 0 ? std::optional<double>(0.4) : std::nullopt;
    def.continuousCollision = i == 3;
    EXPECT_TRUE(world.createBody(def).ok()) << def.name;
  }
  EXPECT_TRUE(world.removeBody(world.findBody("body13")));
  return world;
}

// Pushes one body now and then, so that sleeping islands wake up again.
void stepWithPushes(World& world, int steps) {
  for (int i = 0; i < steps; ++i) {
    if (world.stepCount() % 250 == 0) {
      const BodyId id = world.findBody("body20");
      world.applyWrench(id, {Vec3(30.0, 0.0, 40.0), Vec3::Zero(), world.body(id).position() + Vec3(0, 0, 0.05),
                             Wrench::Frame::World});
    }
    world.step();
  }
}

TEST(WorldSnapshot, RestoredPileContinuesBitIdentically) {
  World original = makePile();
  // The pile is chaotic (rolling capsules and cylinders keep parts of it
  // awake): step until part of it sleeps.
  stepWithPushes(original, 1400);
  while (original.sleepingBodyCount() == 0 && original.stepCount() < 6000) stepWithPushes(original, 100);
  ASSERT_GT(original.contactPointCount(), 40) << "the pile is in contact: warm starting matters";
  ASSERT_GT(original.sleepingBodyCount(), 0) << "some bodies are asleep";
  ASSERT_LT(original.sleepingBodyCount(), original.bodyCount() - 1) << "and some awake";

  const auto bytes = original.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  auto restored = World::decodeSnapshot(*bytes, pileSettings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  EXPECT_EQ(restored->stateHash(), original.stateHash());
  EXPECT_EQ(restored->sleepingBodyCount(), original.sleepingBodyCount());
  EXPECT_EQ(restored->lastSerial(), original.lastSerial());
  const auto again = restored->encodeSnapshot();
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*again, *bytes) << "a restored world saves to the same bytes";

  for (int i = 0; i < 600; ++i) {
    stepWithPushes(original, 1);
    stepWithPushes(*restored, 1);
    ASSERT_EQ(restored->stateHash(), original.stateHash()) << "step " << original.stepCount();
    ASSERT_EQ(restored->sleepingBodyCount(), original.sleepingBodyCount()) << "step " << original.stepCount();
  }
  EXPECT_EQ(*restored->encodeSnapshot(), *original.encodeSnapshot());

  // Bodies created after the restore get the same slots, generations and
  // serials too; the restored world is a world of its own, whose ids the
  // original's are foreign to.
  BodyDef late;
  late.name = "late";
  late.shape = SphereShape{0.1};
  late.position = Vec3(3, 0, 1);
  const auto a = original.createBody(late), b = restored->createBody(late);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->index, b->index);
  EXPECT_EQ(a->generation, b->generation);
  EXPECT_EQ(original.body(*a).serial(), restored->body(*b).serial());
  EXPECT_FALSE(restored->isValid(*a));
  EXPECT_TRUE(restored->isValid(*b));
}

// Joints of every kind and actuation: a chain of boxes lying on the ground
// (the contact path), a wheel's motor, a servo's drive with damping and
// friction, a lamp on a rope, a leg in a cone, a weld; one joint removed
// so that the joint slot table has a hole.
World makeJointedWorld() {
  World world(pileSettings());
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  EXPECT_TRUE(world.createBody(ground).ok());
  const auto add = [&](const std::string& name, const Shape& shape, const Vec3& position) {
    BodyDef def;
    def.name = name;
    def.shape = shape;
    def.position = position;
    const auto id = world.createBody(def);
    EXPECT_TRUE(id.ok()) << name;
    return id.ok() ? *id : BodyId{};
  };
  const auto join = [&](JointDef def) {
    const auto id = world.createJoint(def);
    EXPECT_TRUE(id.ok()) << (id.ok() ? "" : id.error().message);
    return id.ok() ? *id : JointId{};
  };
  BodyId previous;
  for (int i = 0; i < 5; ++i) {
    const BodyId link = add("link" + std::to_string(i), BoxShape{Vec3(0.1, 0.04, 0.04)}, Vec3(0.2 * i, 0, 0.3));
    if (i > 0) {
      JointDef hinge;
      hinge.name = "chain" + std::to_string(i);
      hinge.bodyA = previous;
      hinge.bodyB = link;
      hinge.anchor = Vec3(0.2 * i - 0.1, 0, 0.3);
      hinge.axis = Vec3(0, 1, 0);
      hinge.limit = {true, -0.5, 0.5};
      join(hinge);
    }
    previous = link;
  }
  JointDef wheel;
  wheel.name = "axle";
  wheel.bodyB = add("wheel", CylinderShape{0.2, 0.05}, Vec3(-2, 0, 1));
  wheel.anchor = Vec3(-2, 0, 1);
  wheel.motor = {true, 4.0, 0.3};
  join(wheel);
  JointDef servo;
  servo.name = "servo";
  servo.bodyB = add("arm", BoxShape{Vec3(0.3, 0.03, 0.03)}, Vec3(0.3, -2, 1));
  servo.anchor = Vec3(0, -2, 1);
  servo.axis = Vec3(0, 1, 0);
  servo.drive.enabled = true;
  servo.drive.target = 0.4;
  servo.drive.frequency = 2.0;
  servo.drive.dampingRatio = 0.3;
  servo.damping = 0.01;
  servo.friction = 0.02;
  join(servo);
  JointDef rope;
  rope.name = "rope";
  rope.type = JointType::Distance;
  rope.bodyB = add("lamp", SphereShape{0.1}, Vec3(2.3, 0, 1.5));
  rope.anchor = Vec3(2, 0, 2);
  rope.anchorB = Vec3(2.3, 0, 1.5);
  rope.limit = {true, 0.0, 0.9};
  join(rope);
  JointDef hip;
  hip.name = "hip";
  hip.type = JointType::Spherical;
  hip.bodyB = add("leg", CapsuleShape{0.05, 0.3}, Vec3(0, 2, 1.15));
  hip.anchor = Vec3(0, 2, 1.5);
  hip.axis = Vec3(0, 0, -1);
  hip.coneAngle = 0.4;
  join(hip);
  const JointId spare = join([&] {
    JointDef weld;
    weld.name = "spare";
    weld.type = JointType::Fixed;
    weld.bodyA = world.findBody("leg");
    weld.bodyB = world.findBody("lamp");
    weld.anchor = Vec3(1, 1, 1.3);
    return weld;
  }());
  EXPECT_TRUE(world.removeJoint(spare).ok());
  EXPECT_TRUE(world.setBodyVelocities(world.findBody("leg"), Vec3(0.5, 0, 0), Vec3(0, 1.5, 0)).ok());
  return world;
}

TEST(WorldSnapshot, RestoredJointsContinueBitIdentically) {
  World original = makeJointedWorld();
  for (int i = 0; i < 700; ++i) original.step();
  ASSERT_GT(original.contactPointCount(), 0) << "the chain lies on the ground";
  const auto bytes = original.encodeSnapshot();
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  auto restored = World::decodeSnapshot(*bytes, pileSettings());
  ASSERT_TRUE(restored.ok()) << restored.error().message;
  ASSERT_EQ(restored->jointCount(), original.jointCount());
  EXPECT_EQ(*restored->encodeSnapshot(), *bytes) << "a restored world saves to the same bytes";
  const auto sameJoints = [&] {
    for (int j = 0; j < original.jointCount(); ++j) {
      const JointState a = original.jointStateAt(j), b = restored->jointStateAt(j);
      if (a.name != b.name || a.position != b.position || a.rate != b.rate || a.force != b.force ||
          a.torque != b.torque || a.axisEffort != b.axisEffort || a.atLimit != b.atLimit)
        return false;
    }
    return true;
  };
  EXPECT_TRUE(sameJoints());
  for (int i = 0; i < 600; ++i) {
    original.step();
    restored->step();
    ASSERT_EQ(restored->stateHash(), original.stateHash()) << "step " << original.stepCount();
    ASSERT_TRUE(sameJoints()) << "step " << original.stepCount();
  }
  // Joints made after the restore get the same slots and generations.
  JointDef late;
  late.name = "late";
  late.type = JointType::Spherical;
  late.bodyB = original.findBody("link0");
  late.anchor = Vec3(-0.1, 0, 0.3);
  const auto a = original.createJoint(late);
  late.bodyB = restored->findBody("link0");
  const auto b = restored->createJoint(late);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->index, b->index);
  EXPECT_EQ(a->generation, b->generation);
}

TEST(WorldSnapshot, CorruptJointsAreRefusedWithAMessage) {
  World world = makeJointedWorld();
  const auto bytes = world.encodeSnapshot();
  ASSERT_TRUE(bytes.ok());
  // Every truncation is refused, never misread.
  for (std::size_t cut = bytes->size() - 1; cut > bytes->size() - 2000; cut -= 7) {
    const auto decoded = World::decodeSnapshot(std::span(bytes->data(), cut), pileSettings());
    ASSERT_FALSE(decoded.ok()) << "cut at " << cut;
  }
  // The rope renamed "axle", the wheel's joint's name: a duplicate.
  std::vector<uint8_t> duplicate = *bytes;
  const std::string rope = "rope", axle = "axle";
  const auto at = std::search(duplicate.begin(), duplicate.end(), rope.begin(), rope.end());
  ASSERT_NE(at, duplicate.end());
  std::copy(axle.begin(), axle.end(), at);
  const auto renamed = World::decodeSnapshot(duplicate, pileSettings());
  ASSERT_FALSE(renamed.ok());
  EXPECT_NE(renamed.error().message.find("('axle'): empty or duplicate name"), std::string::npos)
      << renamed.error().message;
  // A joint's body slot pointing at nothing.
  World small(pileSettings());
  BodyDef ball;
  ball.name = "ball";
  ball.shape = SphereShape{0.1};
  const BodyId id = *small.createBody(ball);
  JointDef pin;
  pin.name = "pin";
  pin.type = JointType::Spherical;
  pin.bodyB = id;
  ASSERT_TRUE(small.createJoint(pin).ok());
  std::vector<uint8_t> dangling = *small.encodeSnapshot();
  // The joint's body b slot index is the i32 right after its type byte and
  // body a's 8 bytes: find "pin" and step over its 3 bytes.
  const std::string pinName = "pin";
  const auto name = std::search(dangling.begin(), dangling.end(), pinName.begin(), pinName.end());
  ASSERT_NE(name, dangling.end());
  const auto slot = name + 3 + 1 + 8;
  ASSERT_EQ(*slot, 1);
  *slot = 9;
  const auto refused = World::decodeSnapshot(dangling, pileSettings());
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("joint 0 ('pin'): body_b"), std::string::npos) << refused.error().message;
}

TEST(WorldSnapshot, TruncatedOrCorruptDataIsRefusedWithAMessage) {
  World world = makePile();
  stepWithPushes(world, 300);
  const auto bytes = world.encodeSnapshot();
  ASSERT_TRUE(bytes.ok());
  const std::span<const uint8_t> all(*bytes);

  for (std::size_t size = 0; size < bytes->size(); size += 1 + size / 7) {
    const auto cut = World::decodeSnapshot(all.first(size), pileSettings());
    ASSERT_FALSE(cut.ok()) << "a snapshot cut at " << size << " bytes was accepted";
    EXPECT_NE(cut.error().message.find("world snapshot"), std::string::npos);
  }
  const auto cut = World::decodeSnapshot(all.first(bytes->size() / 2), pileSettings());
  EXPECT_NE(cut.error().message.find("truncated"), std::string::npos) << cut.error().message;

  std::vector<uint8_t> longer = *bytes;
  longer.push_back(0);
  EXPECT_FALSE(World::decodeSnapshot(longer, pileSettings()).ok());

  std::vector<uint8_t> corrupt = *bytes;
  corrupt[0] ^= 0xFF;
  EXPECT_NE(World::decodeSnapshot(corrupt, pileSettings()).error().message.find("magic"), std::string::npos);
  corrupt = *bytes;
  corrupt[4] = 99;
  EXPECT_NE(World::decodeSnapshot(corrupt, pileSettings()).error().message.find("version 99"),
            std::string::npos);

  WorldSettings other = pileSettings();
  other.dt = 2e-3;
  const auto mismatch = World::decodeSnapshot(*bytes, other);
  ASSERT_FALSE(mismatch.ok());
  EXPECT_NE(mismatch.error().message.find("dt"), std::string::npos) << mismatch.error().message;

  // Random byte flips anywhere: refused or accepted, never a crash.
  scenes::SceneRandom random(7);
  for (int trial = 0; trial < 300; ++trial) {
    corrupt = *bytes;
    const auto at = static_cast<std::size_t>(random.uniform(0.0, 1.0) * static_cast<double>(corrupt.size()));
    corrupt[std::min(at, corrupt.size() - 1)] ^= static_cast<uint8_t>(1 + trial % 255);
    (void)World::decodeSnapshot(corrupt, pileSettings());
  }
}

}  // namespace
}  // namespace rbsim
