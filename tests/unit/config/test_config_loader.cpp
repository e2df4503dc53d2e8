// The YAML config loader: every field of the schema, its defaults, and an
// error message (file:line:column: key path: what) for each kind of mistake.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "config/config_loader.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

const std::filesystem::path kDataDir = std::filesystem::path(rbsim::test_support::kTestDataDir) / "config";
// The repository's config/ directory, next to tests/.
const std::filesystem::path kRepoConfigDir =
    (std::filesystem::path(rbsim::test_support::kTestDataDir) / ".." / ".." / "config").lexically_normal();

// Raw string literals in these tests start with a newline so that the YAML
// lines up on the page; drop it, so that the line after R"( is line 1.
std::string yaml(std::string_view text) {
  if (!text.empty() && text.front() == '\n') text.remove_prefix(1);
  return std::string(text);
}

Expected<WorldDef> parse(std::string_view text) {
  return parseWorldConfig(yaml(text), "test.yaml", kDataDir.string());
}

// The error message for a config that must be rejected.
std::string errorOf(std::string_view text) {
  const Expected<WorldDef> world = parse(text);
  if (world.ok()) {
    ADD_FAILURE() << "accepted:\n" << yaml(text);
    return "";
  }
  return world.error().message;
}

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.starts_with(prefix);
}
bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void expectVec3(const Vec3& actual, double x, double y, double z) {
  EXPECT_DOUBLE_EQ(actual.x(), x);
  EXPECT_DOUBLE_EQ(actual.y(), y);
  EXPECT_DOUBLE_EQ(actual.z(), z);
}

void expectQuaternion(const Quaternion& actual, const Quaternion& expected) {
  EXPECT_NEAR(actual.w, expected.w, 1e-15);
  EXPECT_NEAR(actual.x, expected.x, 1e-15);
  EXPECT_NEAR(actual.y, expected.y, 1e-15);
  EXPECT_NEAR(actual.z, expected.z, 1e-15);
}

// ---------------------------------------------------------------- valid worlds

TEST(ConfigLoader, FullWorldFieldByField) {
  const Expected<WorldDef> world = loadWorldConfig((kDataDir / "full_world.yaml").string());
  ASSERT_TRUE(world.ok()) << world.error().message;

  const WorldSettings& settings = world->settings;
  EXPECT_DOUBLE_EQ(settings.dt, 0.002);
  expectVec3(settings.gravity, 0.0, -1.62, 0.5);
  EXPECT_EQ(settings.integrator, IntegratorKind::ExplicitEuler);
  EXPECT_DOUBLE_EQ(settings.linearDamping, 0.1);
  EXPECT_DOUBLE_EQ(settings.angularDamping, 0.2);

  const ContactConfig& contact = settings.contact;
  EXPECT_TRUE(contact.enabled);
  EXPECT_EQ(contact.model, ContactModel::Penalty);
  EXPECT_TRUE(contact.backtracking);
  EXPECT_EQ(contact.solver.velocityIterations, 25);
  EXPECT_EQ(contact.solver.positionIterations, 3);
  EXPECT_DOUBLE_EQ(contact.penaltyStiffness, 2.0e4);
  EXPECT_DOUBLE_EQ(contact.penaltyDamping, 150.0);
  EXPECT_DOUBLE_EQ(contact.penaltyFrictionDamping, 900.0);
  EXPECT_EQ(contact.penaltyLaw, PenaltyLaw::Unclamped);
  EXPECT_DOUBLE_EQ(contact.defaultMaterial.restitution, 0.25);
  EXPECT_DOUBLE_EQ(contact.defaultMaterial.friction, 0.4);
  EXPECT_DOUBLE_EQ(contact.defaultMaterial.staticCoefficient(), 0.7);
  EXPECT_DOUBLE_EQ(contact.solver.restitutionThreshold, 0.3);
  EXPECT_DOUBLE_EQ(contact.detection.margin, 0.01);
  EXPECT_DOUBLE_EQ(contact.solver.linearSlop, 0.001);
  EXPECT_DOUBLE_EQ(contact.solver.baumgarte, 0.3);
  EXPECT_FALSE(contact.solver.warmStarting);
  EXPECT_DOUBLE_EQ(contact.classificationEpsilon, 0.002);
  EXPECT_FALSE(contact.sleeping);
  EXPECT_DOUBLE_EQ(contact.sleepLinearVelocity, 0.02);
  EXPECT_DOUBLE_EQ(contact.sleepTime, 1.5);
  EXPECT_EQ(contact.solver.kind, ContactSolverKind::SoftStep);
  EXPECT_EQ(contact.solver.substeps, 6);
  EXPECT_DOUBLE_EQ(contact.solver.contactHertz, 400.0);
  EXPECT_DOUBLE_EQ(contact.solver.contactDampingRatio, 5.0);

  ASSERT_EQ(world->bodies.size(), 6u);
  const BodyDef& floor = world->bodies[0];
  EXPECT_EQ(floor.name, "floor");
  EXPECT_TRUE(floor.isStatic);
  ASSERT_TRUE(std::holds_alternative<PlaneShape>(floor.shape));
  expectVec3(std::get<PlaneShape>(floor.shape).normal, 0.0, 0.0, 1.0);  // normalised
  EXPECT_DOUBLE_EQ(std::get<PlaneShape>(floor.shape).offset, -1.5);
  expectVec3(floor.position, 0.0, 0.0, -1.0);

  const BodyDef& ball = world->bodies[1];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_FALSE(ball.isStatic);
  ASSERT_TRUE(std::holds_alternative<SphereShape>(ball.shape));
  EXPECT_DOUBLE_EQ(std::get<SphereShape>(ball.shape).radius, 0.25);
  ASSERT_TRUE(ball.mass.has_value());
  EXPECT_DOUBLE_EQ(*ball.mass, 3.5);
  EXPECT_FALSE(ball.density.has_value());
  expectVec3(ball.position, 1.0, 2.0, 3.0);
  expectQuaternion(ball.orientation, Quaternion::identity());
  expectVec3(ball.linearVelocity, 0.5, -0.5, 1.5);
  expectVec3(ball.angularVelocity, 0.0, 0.0, 6.25);
  ASSERT_TRUE(ball.linearDamping.has_value());
  EXPECT_DOUBLE_EQ(*ball.linearDamping, 0.01);
  EXPECT_FALSE(ball.angularDamping.has_value());
  EXPECT_EQ(ball.material.restitution, 0.9);
  EXPECT_EQ(ball.material.friction, 0.2);
  EXPECT_FALSE(ball.material.staticFriction.has_value());
  EXPECT_TRUE(ball.continuousCollision);
  // Resolved against the defaults: μs follows the body's μk when only μk is given.
  const Material resolved = resolveMaterial(ball.material, contact.defaultMaterial);
  EXPECT_DOUBLE_EQ(resolved.staticCoefficient(), 0.2);
  EXPECT_FALSE(world->bodies[2].continuousCollision);

  const BodyDef& crate = world->bodies[2];
  EXPECT_EQ(crate.name, "crate");
  EXPECT_FALSE(crate.isStatic);
  ASSERT_TRUE(std::holds_alternative<BoxShape>(crate.shape));
  expectVec3(std::get<BoxShape>(crate.shape).halfExtents, 0.1, 0.2, 0.3);
  EXPECT_FALSE(crate.mass.has_value());
  ASSERT_TRUE(crate.density.has_value());
  EXPECT_DOUBLE_EQ(*crate.density, 500.0);
  expectQuaternion(crate.orientation, Quaternion{0.0, 0.0, 0.0, 1.0});  // normalised
  EXPECT_FALSE(crate.linearDamping.has_value());
  ASSERT_TRUE(crate.angularDamping.has_value());
  EXPECT_DOUBLE_EQ(*crate.angularDamping, 0.5);

  const BodyDef& can = world->bodies[3];
  ASSERT_TRUE(std::holds_alternative<CylinderShape>(can.shape));
  EXPECT_DOUBLE_EQ(std::get<CylinderShape>(can.shape).radius, 0.2);
  EXPECT_DOUBLE_EQ(std::get<CylinderShape>(can.shape).halfLength, 0.4);
  expectQuaternion(can.orientation, Quaternion::fromRollPitchYaw(0.1, 0.2, 0.3));

  const BodyDef& pill = world->bodies[4];
  ASSERT_TRUE(std::holds_alternative<CapsuleShape>(pill.shape));
  EXPECT_DOUBLE_EQ(std::get<CapsuleShape>(pill.shape).radius, 0.05);
  EXPECT_DOUBLE_EQ(std::get<CapsuleShape>(pill.shape).halfLength, 0.15);
  EXPECT_DOUBLE_EQ(*pill.mass, 0.2);

  const BodyDef& wedge = world->bodies[5];
  ASSERT_TRUE(std::holds_alternative<MeshShape>(wedge.shape));
  const MeshShape& mesh = std::get<MeshShape>(wedge.shape);
  EXPECT_EQ(mesh.file, (kDataDir / "meshes" / "tetra.obj").lexically_normal().string());
  ASSERT_NE(mesh.mesh, nullptr);
  EXPECT_EQ(mesh.mesh->vertices.size(), 4u);
  EXPECT_EQ(mesh.mesh->triangles.size(), 4u);
  EXPECT_DOUBLE_EQ(*wedge.density, 1200.0);
  expectVec3(wedge.position, -1.0, -2.0, -3.0);
}

TEST(ConfigLoader, DefaultsForEverythingLeftOut) {
  const Expected<WorldDef> world = parse(R"(
bodies:
  - name: only
    shape: {type: sphere, radius: 1}
)");
  ASSERT_TRUE(world.ok()) << world.error().message;
  const WorldSettings defaults;
  EXPECT_DOUBLE_EQ(world->settings.dt, defaults.dt);
  expectVec3(world->settings.gravity, 0.0, 0.0, -9.81);
  EXPECT_EQ(world->settings.integrator, IntegratorKind::SemiImplicitEuler);
  EXPECT_DOUBLE_EQ(world->settings.linearDamping, 0.0);
  EXPECT_DOUBLE_EQ(world->settings.angularDamping, 0.0);

  ASSERT_EQ(world->bodies.size(), 1u);
  const BodyDef& body = world->bodies[0];
  EXPECT_FALSE(body.mass.has_value());
  EXPECT_FALSE(body.density.has_value());
  EXPECT_FALSE(body.isStatic);
  expectVec3(body.position, 0.0, 0.0, 0.0);
  expectQuaternion(body.orientation, Quaternion::identity());
  expectVec3(body.linearVelocity, 0.0, 0.0, 0.0);
  expectVec3(body.angularVelocity, 0.0, 0.0, 0.0);
  EXPECT_FALSE(body.linearDamping.has_value());
  EXPECT_FALSE(body.angularDamping.has_value());
}

TEST(ConfigLoader, WorldWithoutBodiesIsEmpty) {
  const Expected<WorldDef> world = parse("world: {dt: 0.01}\n");
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_DOUBLE_EQ(world->settings.dt, 0.01);
  EXPECT_TRUE(world->bodies.empty());
}

TEST(ConfigLoader, EveryIntegratorName) {
  for (const auto& [name, kind] : std::vector<std::pair<std::string, IntegratorKind>>{
           {"explicit_euler", IntegratorKind::ExplicitEuler},
           {"semi_implicit_euler", IntegratorKind::SemiImplicitEuler},
           {"rk4", IntegratorKind::Rk4}}) {
    const Expected<WorldDef> world = parse("world: {integrator: " + name + "}\n");
    ASSERT_TRUE(world.ok()) << world.error().message;
    EXPECT_EQ(world->settings.integrator, kind) << name;
  }
}

TEST(ConfigLoader, ThreadsDefaultToOnePerCoreAndTakeAWholeCount) {
  const Expected<WorldDef> byDefault = parse("world: {dt: 0.01}\n");
  ASSERT_TRUE(byDefault.ok()) << byDefault.error().message;
  EXPECT_EQ(byDefault->settings.threads, 0);
  const Expected<WorldDef> two = parse("world: {threads: 2}\n");
  ASSERT_TRUE(two.ok()) << two.error().message;
  EXPECT_EQ(two->settings.threads, 2);
  EXPECT_EQ(errorOf("world: {threads: 1.5}\n"),
            "test.yaml:1:18: world.threads: expected a whole number (0: one per core)");
  EXPECT_NE(errorOf("world: {threads: -1}\n").find("test.yaml:1:18: world.threads"), std::string::npos);
  EXPECT_NE(errorOf("world: {threads: 1000}\n").find("test.yaml:1:18: world.threads"), std::string::npos);
}

TEST(ConfigLoader, RollPitchYawIsAboutFixedAxesXThenYThenZ) {
  const Expected<WorldDef> world = parse(R"(
bodies:
  - name: yawed
    shape: {type: sphere, radius: 1}
    rpy: [0, 0, 1.5707963267948966]
  - name: tilted
    shape: {type: sphere, radius: 1}
    rpy: [0.3, -0.2, 2.5]
)");
  ASSERT_TRUE(world.ok()) << world.error().message;
  // 90 degrees of yaw turns the body's x axis onto the world's y axis.
  const Vec3 xAxis = world->bodies[0].orientation.rotate(Vec3::UnitX());
  EXPECT_NEAR(xAxis.x(), 0.0, 1e-15);
  EXPECT_NEAR(xAxis.y(), 1.0, 1e-15);
  expectQuaternion(world->bodies[1].orientation, Quaternion::fromRollPitchYaw(0.3, -0.2, 2.5));
}

TEST(ConfigLoader, QuaternionIsWxyzAndNormalised) {
  const Expected<WorldDef> world = parse(R"(
bodies:
  - name: b
    shape: {type: sphere, radius: 1}
    orientation: [1, 1, 0, 0]
)");
  ASSERT_TRUE(world.ok()) << world.error().message;
  const double h = std::sqrt(0.5);
  expectQuaternion(world->bodies[0].orientation, Quaternion{h, h, 0.0, 0.0});
}

TEST(ConfigLoader, MeshPathIsRelativeToTheConfigFile) {
  const std::string path = (kDataDir / "nested" / "relative_mesh.yaml").string();
  const Expected<WorldDef> world = loadWorldConfig(path);
  ASSERT_TRUE(world.ok()) << world.error().message;
  const MeshShape& mesh = std::get<MeshShape>(world->bodies[0].shape);
  EXPECT_EQ(mesh.file, (kDataDir / "meshes" / "tetra.obj").lexically_normal().string());
  EXPECT_EQ(mesh.mesh->triangles.size(), 4u);
}

TEST(ConfigLoader, CompoundOfShapesWithPosesAndDensities) {
  const Expected<WorldDef> world = parse(R"(
bodies:
  - name: dumbbell
    shape:
      type: compound
      shapes:
        - {shape: {type: box, half_extents: [0.5, 0.05, 0.05]}, position: [0, 0, 0], orientation: [2, 0, 0, 0]}
        - {shape: {type: sphere, radius: 0.1}, position: [0.5, 0, 0], density: 7800}
        - {shape: {type: capsule, radius: 0.05, half_length: 0.2}, position: [-0.5, 0, 0], rpy: [0, 1.5708, 0]}
        - shape: {type: mesh, file: meshes/tetra.obj}
          position: [0, 1, 0]
    mass: 3.0
)");
  ASSERT_TRUE(world.ok()) << world.error().message;
  const BodyDef& body = world->bodies[0];
  ASSERT_TRUE(std::holds_alternative<CompoundShape>(body.shape));
  EXPECT_EQ(shapeTypeName(body.shape), "compound");
  EXPECT_DOUBLE_EQ(*body.mass, 3.0);
  const std::vector<CompoundPart>& parts = std::get<CompoundShape>(body.shape).parts;
  ASSERT_EQ(parts.size(), 4u);

  ASSERT_TRUE(std::holds_alternative<BoxShape>(parts[0].shape));
  expectVec3(std::get<BoxShape>(parts[0].shape).halfExtents, 0.5, 0.05, 0.05);
  expectVec3(parts[0].position, 0.0, 0.0, 0.0);
  expectQuaternion(parts[0].orientation, Quaternion::identity());  // normalised
  EXPECT_FALSE(parts[0].density.has_value());

  ASSERT_TRUE(std::holds_alternative<SphereShape>(parts[1].shape));
  EXPECT_DOUBLE_EQ(std::get<SphereShape>(parts[1].shape).radius, 0.1);
  expectVec3(parts[1].position, 0.5, 0.0, 0.0);
  ASSERT_TRUE(parts[1].density.has_value());
  EXPECT_DOUBLE_EQ(*parts[1].density, 7800.0);

  ASSERT_TRUE(std::holds_alternative<CapsuleShape>(parts[2].shape));
  EXPECT_DOUBLE_EQ(std::get<CapsuleShape>(parts[2].shape).halfLength, 0.2);
  expectQuaternion(parts[2].orientation, Quaternion::fromRollPitchYaw(0.0, 1.5708, 0.0));

  // Mesh parts resolve their file against the config's directory, like mesh bodies.
  ASSERT_TRUE(std::holds_alternative<MeshShape>(parts[3].shape));
  EXPECT_EQ(std::get<MeshShape>(parts[3].shape).file,
            (kDataDir / "meshes" / "tetra.obj").lexically_normal().string());
  expectVec3(parts[3].position, 0.0, 1.0, 0.0);
}

TEST(ConfigLoader, ABodyThatCollidesWithNothing) {
  const Expected<WorldDef> world = parse(R"(
bodies:
  - {name: link, shape: {type: box, half_extents: [0.1, 0.2, 0.3]}, mass: 2, collides: false}
  - {name: solid, shape: {type: sphere, radius: 0.1}, collides: true}
  - {name: plain, shape: {type: sphere, radius: 0.1}}
)");
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_FALSE(world->bodies[0].collides);
  EXPECT_TRUE(world->bodies[1].collides);
  EXPECT_TRUE(world->bodies[2].collides) << "the default";
  // A spawned body (SPAWN's spawn_yaml) takes the key too.
  const Expected<BodyDef> spawned = parseBodyDef(
      "{name: ghost, shape: {type: sphere, radius: 0.1}, collides: false}", "spawn", kDataDir.string());
  ASSERT_TRUE(spawned.ok()) << spawned.error().message;
  EXPECT_FALSE(spawned->collides);
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: link
    shape: {type: sphere, radius: 0.1}
    collides: no
)"),
            "test.yaml:4:15: bodies[0].collides: expected true or false, got \"no\"");
  EXPECT_EQ(errorOf(R"(
bodies:
  - {name: link, shape: {type: sphere, radius: 0.1}, collides: 0}
)"),
            "test.yaml:2:64: bodies[0].collides: expected true or false, got \"0\"");
}

TEST(ConfigLoader, OneBodyForSpawning) {
  const Expected<BodyDef> body = parseBodyDef(yaml(R"(
name: probe
shape: {type: box, half_extents: [1, 2, 3]}
position: [4, 5, 6]
mass: 7
)"),
                                              "spawn", kDataDir.string());
  ASSERT_TRUE(body.ok()) << body.error().message;
  EXPECT_EQ(body->name, "probe");
  expectVec3(std::get<BoxShape>(body->shape).halfExtents, 1.0, 2.0, 3.0);
  expectVec3(body->position, 4.0, 5.0, 6.0);
  EXPECT_DOUBLE_EQ(*body->mass, 7.0);
}

TEST(ConfigLoader, OneCompoundBodyForSpawning) {
  const Expected<BodyDef> body = parseBodyDef(
      "name: pair\nshape: {type: compound, shapes: [{shape: {type: sphere, radius: 0.1}},\n"
      "  {shape: {type: box, half_extents: [0.1, 0.1, 0.1]}, position: [0.3, 0, 0]}]}\n",
      "spawn", "");
  ASSERT_TRUE(body.ok()) << body.error().message;
  ASSERT_TRUE(std::holds_alternative<CompoundShape>(body->shape));
  EXPECT_EQ(std::get<CompoundShape>(body->shape).parts.size(), 2u);

  const Expected<BodyDef> nested = parseBodyDef(
      "name: n\nshape: {type: compound, shapes: [{shape: {type: compound, shapes: []}}]}\n",
      "spawn", "");
  ASSERT_FALSE(nested.ok());
  EXPECT_EQ(nested.error().message,
            "spawn:2:49: shape.shapes[0].shape.type: a compound cannot contain a compound; list "
            "its parts here instead");
}

TEST(ConfigLoader, OneBodyErrorsHaveBodyRelativePaths) {
  const Expected<BodyDef> body =
      parseBodyDef("name: x\nshape: {type: sphere, radius: -2}\n", "spawn", "");
  ASSERT_FALSE(body.ok());
  EXPECT_EQ(body.error().message,
            "spawn:2:31: shape.radius: expected a positive number, got \"-2\"");

  const Expected<BodyDef> world = parseBodyDef("world: {dt: 0.1}\n", "spawn", "");
  ASSERT_FALSE(world.ok());
  EXPECT_PRED2(startsWith, world.error().message, "spawn:1:1: world: unknown key; a body has: ");
}

TEST(ConfigLoader, ShippedWorldsLoad) {
  std::vector<std::filesystem::path> files = {kRepoConfigDir / "default.yaml"};
  for (const auto& entry : std::filesystem::directory_iterator(kRepoConfigDir / "worlds")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  }
  ASSERT_GE(files.size(), 3u);
  for (const std::filesystem::path& file : files) {
    const Expected<WorldDef> world = loadWorldConfig(file.string());
    ASSERT_TRUE(world.ok()) << world.error().message;
    EXPECT_FALSE(world->bodies.empty()) << file;
  }
}

TEST(ConfigLoader, DefaultWorldShowsEveryShape) {
  const Expected<WorldDef> world = loadWorldConfig((kRepoConfigDir / "default.yaml").string());
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_DOUBLE_EQ(world->settings.dt, 0.001);
  std::vector<std::string> types;
  for (const BodyDef& body : world->bodies) types.push_back(shapeTypeName(body.shape));
  for (const char* type : {"sphere", "box", "cylinder", "capsule", "mesh", "plane", "compound"}) {
    EXPECT_NE(std::find(types.begin(), types.end(), type), types.end()) << type;
  }
}

// ---------------------------------------------------------------- errors

TEST(ConfigLoaderErrors, BriefExampleNegativeRadius) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape:
      type: sphere
      radius: -1
)"),
            "test.yaml:5:15: bodies[0].shape.radius: expected a positive number, got \"-1\"");
}

TEST(ConfigLoaderErrors, YamlSyntaxErrorHasTheParserPosition) {
  EXPECT_EQ(errorOf(R"(
world:
  dt: 0.01
   gravity: [0, 0, -1]
)"),
            "test.yaml:3:11: YAML syntax error: illegal map value");
  EXPECT_PRED2(startsWith, errorOf("world: {dt: [0.001}\n"), "test.yaml:1:19: YAML syntax error: ");
}

TEST(ConfigLoaderErrors, UnknownKeys) {
  EXPECT_EQ(errorOf("world: {dt: 0.01}\ncolour: red\n"),
            "test.yaml:2:1: colour: unknown key; the top level has: world, bodies, robots, joints, contact, sensors, lcm, "
            "server, limits");
  EXPECT_EQ(errorOf("world: {dt: 0.01, gravty: [0, 0, -1]}\n"),
            "test.yaml:1:19: world.gravty: unknown key; the world has: dt, gravity, integrator, "
            "damping, threads");
  EXPECT_EQ(errorOf("world: {damping: {linear: 1, angle: 2}}\n"),
            "test.yaml:1:30: world.damping.angle: unknown key; damping has: linear, angular");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    colour: red
)"),
            "test.yaml:4:5: bodies[0].colour: unknown key; a body has: name, shape, mass, "
            "density, center_of_mass, inertia, position, orientation, rpy, linear_velocity, "
            "angular_velocity, static, damping, material, ccd, collides, collision_group, collision_mask");
  // Keys of another shape type are unknown too.
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1, half_length: 2}
)"),
            "test.yaml:3:38: bodies[0].shape.half_length: unknown key; a sphere shape has: type, "
            "radius");
}

TEST(ConfigLoaderErrors, ServerSectionsAreLeftToTheServer) {
  // lcm, server and limits belong to rbserver, which checks them itself.
  const Expected<WorldDef> world = parse(R"(
lcm: {url: "udpm://239.255.76.67:7667?ttl=0", anything: [1, 2]}
server:
limits: {max_bodies: 10}
)");
  EXPECT_TRUE(world.ok()) << world.error().message;
}

TEST(ConfigLoaderErrors, BadContactSettings) {
  EXPECT_EQ(errorOf("contact: 3\n"), "test.yaml:1:10: contact: expected a mapping, got \"3\"");
  EXPECT_EQ(errorOf("contact: {model: springs}\n"),
            "test.yaml:1:18: contact.model: expected impulse or penalty, got \"springs\"");
  EXPECT_EQ(errorOf("contact: {solver: box2d}\n"),
            "test.yaml:1:19: contact.solver: expected sequential_impulses or soft_step, got \"box2d\"");
  EXPECT_EQ(errorOf("contact: {substeps: 0}\n"), "test.yaml:1:21: contact.substeps: expected at least 1 sub-step");
  EXPECT_NE(errorOf("contact: {substeps: 2.5}\n").find("whole number"), std::string::npos);
  EXPECT_NE(errorOf("contact: {contact_hertz: 0}\n").find("contact.contact_hertz"), std::string::npos);
  EXPECT_NE(errorOf("contact: {contact_damping_ratio: -1}\n").find("contact.contact_damping_ratio"),
            std::string::npos);
  EXPECT_EQ(errorOf("contact: {penalty_law: soft}\n"),
            "test.yaml:1:24: contact.penalty_law: expected clamped or unclamped, got \"soft\"");
  EXPECT_EQ(errorOf("contact: {friction: 0.5, static_friction: 0.2}\n"),
            "test.yaml:1:43: contact.static_friction: static_friction must not be below friction");
  EXPECT_NE(errorOf("contact: {restitution: 1.5}\n").find("contact.restitution"), std::string::npos);
  EXPECT_NE(errorOf("contact: {iterations: 2.5}\n").find("whole number"), std::string::npos);
  EXPECT_NE(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    material: {bounce: 1}
)").find("bodies[0].material.bounce: unknown key"),
            std::string::npos);
}

TEST(ConfigLoaderErrors, DuplicateBodyName) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
  - name: b
    shape: {type: sphere, radius: 1}
  - name: a
    shape: {type: sphere, radius: 1}
)"),
            "test.yaml:6:11: bodies[2].name: duplicate body name \"a\" (also the name of "
            "bodies[0])");
}

TEST(ConfigLoaderErrors, DuplicateKey) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1, radius: 2}
)"),
            "test.yaml:3:38: bodies[0].shape.radius: duplicate key (first given on line 3)");
  EXPECT_EQ(errorOf("world: {dt: 0.1}\nworld: {dt: 0.2}\n"),
            "test.yaml:2:1: world: duplicate key (first given on line 1)");
}

TEST(ConfigLoaderErrors, WrongTypes) {
  EXPECT_EQ(errorOf("world: {dt: fast}\n"),
            "test.yaml:1:13: world.dt: expected a positive number, got \"fast\"");
  EXPECT_EQ(errorOf("bodies: {name: a}\n"),
            "test.yaml:1:9: bodies: expected a list, got a mapping");
  EXPECT_EQ(errorOf("world: [1, 2]\n"),
            "test.yaml:1:8: world: expected a mapping, got a list of 2 items");
  EXPECT_EQ(errorOf("world: {gravity: [0, -9.81]}\n"),
            "test.yaml:1:18: world.gravity: expected a list of 3 numbers, got a list of 2 items");
  EXPECT_EQ(errorOf("world: {gravity: 9.81}\n"),
            "test.yaml:1:18: world.gravity: expected a list of 3 numbers, got \"9.81\"");
  EXPECT_EQ(errorOf("world: {integrator: [rk4]}\n"),
            "test.yaml:1:21: world.integrator: expected a string, got a list of 1 item");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    mass: "2"
)"),
            "test.yaml:4:11: bodies[0].mass: expected a positive number, got the string \"2\"");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    static: yes
)"),
            "test.yaml:4:13: bodies[0].static: expected true or false, got \"yes\"");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: sphere
)"),
            "test.yaml:3:12: bodies[0].shape: expected a mapping, got \"sphere\"");
  EXPECT_EQ(errorOf("bodies: [7]\n"), "test.yaml:1:10: bodies[0]: expected a mapping, got \"7\"");
}

TEST(ConfigLoaderErrors, MissingRequiredKeys) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - shape: {type: sphere, radius: 1}
)"),
            "test.yaml:2:5: bodies[0].name: missing required key");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
)"),
            "test.yaml:2:5: bodies[0].shape: missing required key");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {radius: 1}
)"),
            "test.yaml:3:12: bodies[0].shape.type: missing required key");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: capsule, radius: 1}
)"),
            "test.yaml:3:12: bodies[0].shape.half_length: missing required key");
}

TEST(ConfigLoaderErrors, EmptyValuePointsAtItsKey) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape:
      type: sphere
      radius:
)"),
            "test.yaml:5:7: bodies[0].shape.radius: expected a positive number, got nothing");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name:
    shape: {type: sphere, radius: 1}
)"),
            "test.yaml:2:5: bodies[0].name: expected a string, got nothing");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: ""
    shape: {type: sphere, radius: 1}
)"),
            "test.yaml:2:11: bodies[0].name: expected a non-empty name");
}

TEST(ConfigLoaderErrors, NotFinite) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: .nan}
)"),
            "test.yaml:3:35: bodies[0].shape.radius: expected a finite number, got \".nan\"");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    position: [0, -.inf, 0]
)"),
            "test.yaml:4:19: bodies[0].position[1]: expected a finite number, got \"-.inf\"");
  EXPECT_EQ(errorOf("world: {gravity: [0, 0, nan]}\n"),
            "test.yaml:1:25: world.gravity[2]: expected a finite number, got \"nan\"");
}

TEST(ConfigLoaderErrors, SizesOutOfRange) {
  const auto body = [](const std::string& shape) {
    return "bodies:\n  - name: a\n    shape: " + shape + "\n";
  };
  EXPECT_EQ(errorOf(body("{type: sphere, radius: 0}")),
            "test.yaml:3:35: bodies[0].shape.radius: expected a positive number, got \"0\"");
  EXPECT_EQ(errorOf(body("{type: sphere, radius: 2e6}")),
            "test.yaml:3:35: bodies[0].shape.radius: expected a positive number no larger than "
            "1e+06, got \"2e6\"");
  EXPECT_EQ(errorOf(body("{type: box, half_extents: [1, 0, 1]}")),
            "test.yaml:3:42: bodies[0].shape.half_extents[1]: expected a positive number, got "
            "\"0\"");
  EXPECT_EQ(
      errorOf(body("{type: cylinder, radius: 1, half_length: -0.5}")),
      "test.yaml:3:53: bodies[0].shape.half_length: expected a positive number, got \"-0.5\"");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    position: [0, 0, 1e7]
)"),
            "test.yaml:4:22: bodies[0].position[2]: expected a number between -1e+06 and 1e+06, "
            "got \"1e7\"");
  EXPECT_EQ(errorOf("world: {dt: 0}\n"),
            "test.yaml:1:13: world.dt: expected a positive number, got \"0\"");
  EXPECT_EQ(errorOf("world: {dt: 2}\n"),
            "test.yaml:1:13: world.dt: expected a positive number no larger than 1, got \"2\"");
  EXPECT_EQ(errorOf("world: {damping: {linear: -0.1}}\n"),
            "test.yaml:1:27: world.damping.linear: expected a non-negative number, got \"-0.1\"");
}

TEST(ConfigLoaderErrors, MassAndDensity) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    density: 1000
    mass: 2
)"),
            "test.yaml:5:5: bodies[0].mass: give mass or density, not both");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    mass: -2
)"),
            "test.yaml:4:11: bodies[0].mass: expected a positive number, got \"-2\"");
}

TEST(ConfigLoaderErrors, Orientation) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    orientation: [1, 0, 0, 0]
    rpy: [0, 0, 1]
)"),
            "test.yaml:5:5: bodies[0].rpy: give orientation or rpy, not both");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    orientation: [0, 0, 0, 0]
)"),
            "test.yaml:4:18: bodies[0].orientation: expected a non-zero quaternion (w, x, y, z)");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 1}
    orientation: [0, 0, 1]
)"),
            "test.yaml:4:18: bodies[0].orientation: expected a list of 4 numbers, got a list of "
            "3 items");
}

TEST(ConfigLoaderErrors, Integrator) {
  EXPECT_EQ(errorOf("world:\n  integrator: verlet\n"),
            "test.yaml:2:15: world.integrator: expected one of explicit_euler, "
            "semi_implicit_euler, rk4, got \"verlet\"");
}

TEST(ConfigLoaderErrors, ShapeType) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: cone, radius: 1}
)"),
            "test.yaml:3:19: bodies[0].shape.type: expected one of sphere, box, cylinder, "
            "capsule, mesh, plane, compound, trimesh, heightfield, got \"cone\"");
}

TEST(ConfigLoaderErrors, Plane) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: floor
    shape: {type: plane}
)"),
            "test.yaml:3:19: bodies[0].shape.type: a plane is only allowed on a static body (add "
            "static: true)");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: floor
    static: true
    shape: {type: plane, normal: [0, 0, 0]}
)"),
            "test.yaml:4:34: bodies[0].shape.normal: expected a non-zero normal vector");
}

TEST(ConfigLoaderErrors, Compound) {
  EXPECT_EQ(
      errorOf(R"(
bodies:
  - name: a
    shape: {type: compound, shapes: []}
)"),
      "test.yaml:3:37: bodies[0].shape.shapes: expected at least one part shape in a compound");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape: {type: compound}
)"),
            "test.yaml:3:12: bodies[0].shape.shapes: missing required key");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape:
      type: compound
      shapes:
        - shape: {type: sphere, radius: 1}
        - shape: {type: compound, shapes: [{shape: {type: sphere, radius: 1}}]}
)"),
            "test.yaml:7:25: bodies[0].shape.shapes[1].shape.type: a compound cannot contain a "
            "compound; list its parts here instead");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    static: true
    shape:
      type: compound
      shapes:
        - shape: {type: plane}
)"),
            "test.yaml:7:25: bodies[0].shape.shapes[0].shape.type: a plane cannot be part of a "
            "compound (a half-space has no finite mass); make it a static body of its own");
  // Bad part poses and sizes, with the same messages as for bodies.
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape:
      type: compound
      shapes:
        - {shape: {type: sphere, radius: 1}, orientation: [0, 0, 0, 0]}
)"),
            "test.yaml:6:59: bodies[0].shape.shapes[0].orientation: expected a non-zero "
            "quaternion (w, x, y, z)");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape:
      type: compound
      shapes:
        - {shape: {type: sphere, radius: 1}, orientation: [1, 0, 0, 0], rpy: [0, 0, 1]}
)"),
            "test.yaml:6:73: bodies[0].shape.shapes[0].rpy: give orientation or rpy, not both");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape:
      type: compound
      shapes:
        - {shape: {type: sphere, radius: 1}, position: [0, .nan, 0]}
)"),
            "test.yaml:6:60: bodies[0].shape.shapes[0].position[1]: expected a finite number, got "
            "\".nan\"");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape:
      type: compound
      shapes:
        - {shape: {type: box, half_extents: [1, -1, 1]}, density: 0}
)"),
            "test.yaml:6:49: bodies[0].shape.shapes[0].shape.half_extents[1]: expected a positive "
            "number, got \"-1\"");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape:
      type: compound
      shapes:
        - {shape: {type: sphere, radius: 1}, density: 0}
)"),
            "test.yaml:6:55: bodies[0].shape.shapes[0].density: expected a positive number, got "
            "\"0\"");
  EXPECT_PRED2(
      startsWith, errorOf(R"(
bodies:
  - name: a
    shape:
      type: compound
      shapes:
        - {shape: {type: sphere, radius: 1}, mass: 2}
)"),
      "test.yaml:6:46: bodies[0].shape.shapes[0].mass: unknown key; a compound part has: ");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: a
    shape:
      type: compound
      shapes:
        - {position: [0, 0, 0]}
)"),
            "test.yaml:6:11: bodies[0].shape.shapes[0].shape: missing required key");
}

TEST(ConfigLoaderErrors, StaticBodyCannotMove) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: wall
    static: true
    shape: {type: box, half_extents: [1, 1, 1]}
    angular_velocity: [0, 0, 1]
)"),
            "test.yaml:5:23: bodies[0].angular_velocity: a static body cannot move; expected [0, "
            "0, 0] or no angular_velocity");
}

TEST(ConfigLoaderErrors, MeshErrorsArePrefixedWithTheirPlaceInTheConfig) {
  const std::string missing = errorOf(R"(
bodies:
  - name: a
    shape: {type: mesh, file: meshes/no_such_file.obj}
)");
  EXPECT_PRED2(startsWith, missing, "test.yaml:3:31: bodies[0].shape.file: ");
  EXPECT_PRED2(contains, missing, "no_such_file.obj");

  const std::string open = errorOf(R"(
bodies:
  - name: a
    shape: {type: mesh, file: meshes/open_tetra.obj}
)");
  EXPECT_PRED2(startsWith, open, "test.yaml:3:31: bodies[0].shape.file: ");
  EXPECT_PRED2(contains, open, "open_tetra.obj");
}

TEST(ConfigLoader, TrimeshLoadsAnOpenSurfaceFromObjOrStl) {
  for (const char* file : {"meshes/ramp.obj", "meshes/ramp.stl"}) {
    const Expected<WorldDef> world = parse(std::string(R"(
bodies:
  - name: ramp
    static: true
    shape: {type: trimesh, file: )") + file + "}\n");
    ASSERT_TRUE(world.ok()) << file << ": " << world.error().message;
    const auto* trimesh = std::get_if<TriangleMeshShape>(&world->bodies[0].shape);
    ASSERT_NE(trimesh, nullptr) << file;
    EXPECT_EQ(trimesh->file, (kDataDir / file).lexically_normal().string());
    ASSERT_NE(trimesh->mesh, nullptr);
    ASSERT_EQ(trimesh->mesh->triangles.size(), 2u) << file;
    // Both files wind the ramp to face up the same way.
    const auto& t = trimesh->mesh->triangles[0];
    const auto& v = trimesh->mesh->vertices;
    const Vec3 normal = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
    EXPECT_GT(normal.z(), 0.0) << file;
  }
}

TEST(ConfigLoaderErrors, Trimesh) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: ramp
    shape: {type: trimesh, file: meshes/ramp.obj}
)"),
            "test.yaml:3:19: bodies[0].shape.type: a trimesh is only allowed on a static body "
            "(add static: true)");

  const std::string degenerate = errorOf(R"(
bodies:
  - name: ramp
    static: true
    shape: {type: trimesh, file: meshes/flat_ramp.obj}
)");
  EXPECT_PRED2(startsWith, degenerate, "test.yaml:4:34: bodies[0].shape.file: ");
  EXPECT_PRED2(contains, degenerate, "flat_ramp.obj");
  EXPECT_PRED2(contains, degenerate, "triangle 2 (vertices 0, 4, 1) is degenerate");

  const std::string missing = errorOf(R"(
bodies:
  - name: ramp
    static: true
    shape: {type: trimesh, file: meshes/no_such_ramp.obj}
)");
  EXPECT_PRED2(startsWith, missing, "test.yaml:4:34: bodies[0].shape.file: ");
  EXPECT_PRED2(contains, missing, "no_such_ramp.obj");

  EXPECT_PRED2(startsWith, errorOf(R"(
bodies:
  - name: c
    shape:
      type: compound
      shapes:
        - shape: {type: trimesh, file: meshes/ramp.obj}
)"),
               "test.yaml:6:25: bodies[0].shape.shapes[0].shape.type: a trimesh cannot be part of a compound");
}

// A heightfield is loaded as the trimesh of its grid (meshio/height_grid.h):
// samples centred on the body's origin, rows along +y, two up-facing
// triangles per cell.
TEST(ConfigLoader, HeightfieldFromInlineRowsNpyAndPng) {
  Expected<WorldDef> world = parse(R"(
bodies:
  - name: ground
    static: true
    shape: {type: heightfield, heights: [[0, 1, 2], [3, 4, 5]], cell_size: [0.5, 0.25], height_scale: 2, height_offset: -1}
)");
  ASSERT_TRUE(world.ok()) << world.error().message;
  auto* terrain = std::get_if<TriangleMeshShape>(&world->bodies[0].shape);
  ASSERT_NE(terrain, nullptr);
  EXPECT_EQ(terrain->file, "inline heights");
  ASSERT_EQ(terrain->mesh->vertices.size(), 6u);
  ASSERT_EQ(terrain->mesh->triangles.size(), 4u);
  EXPECT_EQ(terrain->mesh->vertices[0], Vec3(-0.5, -0.125, -1.0));
  EXPECT_EQ(terrain->mesh->vertices[5], Vec3(0.5, 0.125, 9.0));

  // [[0, .5, 1, 1.5], [2, 2.5, 3, 3.5], [4, 4.5, 5, 5.5]], square cells of 1 m.
  world = parse(R"(
bodies:
  - name: ground
    static: true
    shape: {type: heightfield, file: terrain/bumps.npy, cell_size: 1}
)");
  ASSERT_TRUE(world.ok()) << world.error().message;
  terrain = std::get_if<TriangleMeshShape>(&world->bodies[0].shape);
  ASSERT_NE(terrain, nullptr);
  EXPECT_EQ(terrain->file, (kDataDir / "terrain/bumps.npy").lexically_normal().string());
  ASSERT_EQ(terrain->mesh->vertices.size(), 12u);
  EXPECT_EQ(terrain->mesh->triangles.size(), 12u);
  EXPECT_EQ(terrain->mesh->vertices[0], Vec3(-1.5, -1.0, 0.0));
  EXPECT_EQ(terrain->mesh->vertices[11], Vec3(1.5, 1.0, 5.5));

  // A 16-bit PNG, 3 wide and 2 high, top row 0 65535 0: full scale is the
  // height scale, and the top row is the +y edge.
  world = parse(R"(
bodies:
  - name: ground
    static: true
    shape: {type: heightfield, file: terrain/checker16.png, cell_size: 2, height_scale: 0.3}
)");
  ASSERT_TRUE(world.ok()) << world.error().message;
  terrain = std::get_if<TriangleMeshShape>(&world->bodies[0].shape);
  ASSERT_NE(terrain, nullptr);
  ASSERT_EQ(terrain->mesh->vertices.size(), 6u);
  EXPECT_EQ(terrain->mesh->vertices[0], Vec3(-2, -1, 0.3));  // bottom row: 65535 0 65535
  EXPECT_EQ(terrain->mesh->vertices[1], Vec3(0, -1, 0.0));
  EXPECT_EQ(terrain->mesh->vertices[4], Vec3(0, 1, 0.3));  // top row: 0 65535 0
}

TEST(ConfigLoaderErrors, Heightfield) {
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: g
    shape: {type: heightfield, heights: [[0, 0], [0, 0]], cell_size: 1}
)"),
            "test.yaml:3:19: bodies[0].shape.type: a heightfield is only allowed on a static body "
            "(add static: true)");
  const std::string both = errorOf(R"(
bodies:
  - name: g
    static: true
    shape: {type: heightfield, file: terrain/bumps.npy, heights: [[0, 0], [0, 0]], cell_size: 1}
)");
  EXPECT_PRED2(startsWith, both, "test.yaml:4:19: bodies[0].shape.type: a heightfield takes exactly one of file");
  const std::string neither = errorOf(R"(
bodies:
  - name: g
    static: true
    shape: {type: heightfield, cell_size: 1}
)");
  EXPECT_PRED2(startsWith, neither, "test.yaml:4:19: bodies[0].shape.type: a heightfield takes exactly one of file");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: g
    static: true
    shape: {type: heightfield, heights: [[0, 0, 1], [0, 0]], cell_size: 1}
)"),
            "test.yaml:4:53: bodies[0].shape.heights[1]: expected 3 heights, as in the first row; got 2");
  EXPECT_EQ(errorOf(R"(
bodies:
  - name: g
    static: true
    shape: {type: heightfield, heights: [[0, 0, 1]], cell_size: 1}
)"),
            "test.yaml:4:41: bodies[0].shape.heights: expected at least 2 rows of heights (one cell)");
  EXPECT_PRED2(startsWith, errorOf(R"(
bodies:
  - name: g
    static: true
    shape: {type: heightfield, heights: [[0, 0], [0, 0]]}
)"),
               "test.yaml:4:12: bodies[0].shape");
  EXPECT_PRED2(contains, errorOf(R"(
bodies:
  - name: g
    static: true
    shape: {type: heightfield, heights: [[0, 0], [0, 0]], cell_size: [1, 0]}
)"),
               "bodies[0].shape.cell_size");
  const std::string notGrey = errorOf(R"(
bodies:
  - name: g
    static: true
    shape: {type: heightfield, file: meshes/ramp.obj, cell_size: 1}
)");
  EXPECT_PRED2(startsWith, notGrey, "test.yaml:4:38: bodies[0].shape.file: ");
  EXPECT_PRED2(contains, notGrey, ".png or .npy");
  EXPECT_PRED2(contains, errorOf(R"(
bodies:
  - name: g
    static: true
    shape: {type: heightfield, file: terrain/missing.npy, cell_size: 1}
)"),
               "missing.npy: cannot be opened");
  EXPECT_PRED2(contains, errorOf(R"(
bodies:
  - name: g
    static: true
    shape: {type: heightfield, heights: [[0, 0], [0, 1e300]], cell_size: 1, height_scale: 1e6}
)"),
               "bodies[0].shape");
}

TEST(ConfigLoaderErrors, WholeDocument) {
  EXPECT_EQ(errorOf(""), "test.yaml:1:1: expected a mapping, got an empty document");
  EXPECT_EQ(errorOf("# nothing but a comment\n"),
            "test.yaml:1:1: expected a mapping, got an empty document");
  EXPECT_EQ(errorOf("- 1\n- 2\n"), "test.yaml:1:1: expected a mapping, got a list of 2 items");
  EXPECT_EQ(errorOf("world: {dt: 0.1}\n---\nworld: {dt: 0.2}\n"),
            "test.yaml:3:1: expected one YAML document, found a second one");
}

TEST(ConfigLoaderErrors, MissingFile) {
  const std::string path = (kDataDir / "no_such_world.yaml").string();
  const Expected<WorldDef> world = loadWorldConfig(path);
  ASSERT_FALSE(world.ok());
  EXPECT_PRED2(startsWith, world.error().message, path + ": cannot read the config file: ");
}

// Found by tests/fuzz/fuzz_body_yaml (regressions/body_yaml/stray_comma_hang):
// yaml-cpp 0.7's LoadAll looped forever, allocating, on a stray token after
// a document, so a SPAWN's spawn_yaml could hang rbserver.
TEST(ConfigLoaderErrors, StrayTokenAfterTheDocumentIsAnErrorNotAHang) {
  for (const char* text : {"{name: a, shape: {type: sphere, radius: 1}},", "[a],", "'a',"}) {
    const Expected<BodyDef> body = parseBodyDef(text, "spawn_yaml", "");
    ASSERT_FALSE(body.ok()) << text;
    EXPECT_NE(body.error().message.find("spawn_yaml:1:"), std::string::npos) << body.error().message;
  }
  EXPECT_FALSE(parseWorldConfig("{world: {dt: 0.1}},", "test.yaml", "").ok());
}

}  // namespace
}  // namespace rbsim
