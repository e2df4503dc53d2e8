// Mass properties given as data in a world file: `center_of_mass` and
// `inertia` (with `mass`), and an error naming file:line:column for each
// way they can be wrong.

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <string_view>

#include "config/config_loader.h"

namespace rbsim {
namespace {

Expected<WorldDef> parse(const std::string& body) {
  return parseWorldConfig("bodies:\n  - name: plate\n" + body, "cad.yaml", "");
}

std::string errorOf(const std::string& body) {
  const Expected<WorldDef> world = parse(body);
  if (world.ok()) {
    ADD_FAILURE() << "accepted:\n" << body;
    return "";
  }
  return world.error().message;
}

TEST(GivenMassProperties, FullTensorAndCentreOfMass) {
  const Expected<WorldDef> world = parse(
      "    shape: {type: box, half_extents: [0.5, 0.5, 0.1]}\n"
      "    mass: 3.5\n"
      "    center_of_mass: [0.1, -0.2, 0.05]\n"
      "    inertia: [[0.4, -0.01, 0.02], [-0.01, 0.5, 0.0], [0.02, 0.0, 0.8]]\n");
  ASSERT_TRUE(world.ok()) << world.error().message;
  const BodyDef& def = world->bodies[0];
  EXPECT_EQ(def.mass, 3.5);
  ASSERT_TRUE(def.centerOfMass.has_value());
  EXPECT_EQ(*def.centerOfMass, Vec3(0.1, -0.2, 0.05));
  ASSERT_TRUE(def.inertia.has_value());
  Mat3 expected;
  expected << 0.4, -0.01, 0.02, -0.01, 0.5, 0.0, 0.02, 0.0, 0.8;
  EXPECT_EQ(*def.inertia, expected);  // the numbers as written, bit for bit
}

TEST(GivenMassProperties, DiagonalTensorWithoutCentreOfMass) {
  const Expected<WorldDef> world =
      parse("    shape: {type: sphere, radius: 0.2}\n    mass: 1\n    inertia: [1, 2, 3]\n");
  ASSERT_TRUE(world.ok()) << world.error().message;
  const BodyDef& def = world->bodies[0];
  ASSERT_TRUE(def.inertia.has_value());
  EXPECT_EQ(*def.inertia, Mat3(Vec3(1, 2, 3).asDiagonal()));
  EXPECT_FALSE(def.centerOfMass.has_value());  // the config frame's origin
}

TEST(GivenMassProperties, SpawnYamlGoesThroughTheSameRules) {
  const auto noBodies = [](const std::string&) { return std::optional<bool>(); };
  const Expected<SpawnDef> good = parseSpawnDef(
      "{name: s, shape: {type: sphere, radius: 1}, mass: 2, inertia: [1, 1, 1.5]}", "spawn_yaml", "", noBodies);
  ASSERT_TRUE(good.ok()) << good.error().message;
  EXPECT_TRUE(good->bodies.at(0).inertia.has_value());
  const Expected<SpawnDef> bad = parseSpawnDef(
      "{name: s, shape: {type: sphere, radius: 1}, mass: 2, inertia: [1, 1, 3]}", "spawn_yaml", "", noBodies);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(
      bad.error().message,
      "spawn_yaml:1:63: inertia: no rigid body has these principal moments (1, 1, 3) kg·m²: each "
      "must be at most the sum of the other two");
}

TEST(GivenMassPropertiesErrors, NotFinite) {
  EXPECT_EQ(
      errorOf("    shape: {type: sphere, radius: 1}\n    mass: 1\n    inertia: [1, .nan, 1]\n"),
      "cad.yaml:5:18: bodies[0].inertia[1]: expected a finite number, got \".nan\"");
  EXPECT_EQ(errorOf("    shape: {type: sphere, radius: 1}\n    mass: 1\n"
                    "    inertia: [[1, 0, 0], [0, 1, 0], [0, 0, .inf]]\n"),
            "cad.yaml:5:44: bodies[0].inertia[2][2]: expected a finite number, got \".inf\"");
  EXPECT_EQ(errorOf("    shape: {type: sphere, radius: 1}\n    mass: 1\n    inertia: [1, 1, 1]\n"
                    "    center_of_mass: [0, -.inf, 0]\n"),
            "cad.yaml:6:25: bodies[0].center_of_mass[1]: expected a finite number, got \"-.inf\"");
}

TEST(GivenMassPropertiesErrors, Shape) {
  EXPECT_EQ(
      errorOf("    shape: {type: sphere, radius: 1}\n    mass: 1\n    inertia: [1, 1]\n"),
      "cad.yaml:5:14: bodies[0].inertia: expected [Ixx, Iyy, Izz] or [[Ixx, Ixy, Ixz], [Ixy, Iyy, "
      "Iyz], [Ixz, Iyz, Izz]] (kg·m²), got a list of 2 items");
}

TEST(GivenMassPropertiesErrors, Asymmetric) {
  EXPECT_EQ(errorOf("    shape: {type: sphere, radius: 1}\n    mass: 1\n"
                    "    inertia: [[1, 0.1, 0], [0.2, 1, 0], [0, 0, 1]]\n"),
            "cad.yaml:5:14: bodies[0].inertia: the inertia tensor must be symmetric: Ixy is "
            "0.10000000000000001 "
            "above the diagonal and 0.20000000000000001 below it");
}

TEST(GivenMassPropertiesErrors, NotPositiveDefinite) {
  // Eigenvalues 0 and 2 in the x-y block: a tensor only a line could have.
  const std::string message = errorOf(
      "    shape: {type: sphere, radius: 1}\n    mass: 1\n"
      "    inertia: [[1, 1, 0], [1, 1, 0], [0, 0, 2]]\n");
  EXPECT_EQ(message.rfind(
                "cad.yaml:5:14: bodies[0].inertia: the inertia tensor must be positive definite: "
                "its principal moments are (",
                0),
            0u)
      << message;
  EXPECT_EQ(errorOf("    shape: {type: sphere, radius: 1}\n    mass: 1\n    inertia: [1, -2, 3]\n"),
            "cad.yaml:5:14: bodies[0].inertia: the inertia tensor must be positive definite: its "
            "principal "
            "moments are (1, -2, 3) kg·m²");
}

TEST(GivenMassPropertiesErrors, TriangleInequality) {
  EXPECT_EQ(
      errorOf("    shape: {type: sphere, radius: 1}\n    mass: 1\n    inertia: [1, 2, 3.001]\n"),
      "cad.yaml:5:14: bodies[0].inertia: no rigid body has these principal moments (1, 2, "
      "3.0009999999999999) "
      "kg·m²: each must be at most the sum of the other two");
  // Equality is a flat body: allowed.
  EXPECT_TRUE(
      parse("    shape: {type: sphere, radius: 1}\n    mass: 1\n    inertia: [1, 2, 3]\n").ok());
}

TEST(GivenMassPropertiesErrors, InertiaWithoutMass) {
  EXPECT_EQ(errorOf("    shape: {type: sphere, radius: 1}\n    inertia: [1, 1, 1]\n"),
            "cad.yaml:4:5: bodies[0].inertia: inertia needs the body's mass with it (mass: kg, not "
            "density)");
  EXPECT_EQ(
      errorOf("    shape: {type: sphere, radius: 1}\n    density: 10\n    inertia: [1, 1, 1]\n"),
      "cad.yaml:5:5: bodies[0].inertia: inertia needs the body's mass with it (mass: kg, not "
      "density)");
}

TEST(GivenMassPropertiesErrors, CentreOfMassWithoutInertia) {
  EXPECT_EQ(
      errorOf(
          "    shape: {type: sphere, radius: 1}\n    mass: 1\n    center_of_mass: [0, 0, 0.1]\n"),
      "cad.yaml:5:5: bodies[0].center_of_mass: center_of_mass needs inertia and mass with it (the "
      "rule "
      "of URDF's <inertial>); without them the shape gives the mass properties");
}

TEST(GivenMassPropertiesErrors, StaticBody) {
  EXPECT_EQ(
      errorOf("    static: true\n    shape: {type: box, half_extents: [1, 1, 1]}\n    mass: 1\n"
              "    inertia: [1, 1, 1]\n"),
      "cad.yaml:6:5: bodies[0].inertia: a static body has no mass properties; remove inertia (or "
      "static: true)");
  EXPECT_EQ(errorOf("    static: true\n    shape: {type: box, half_extents: [1, 1, 1]}\n"
                    "    center_of_mass: [0, 0, 1]\n"),
            "cad.yaml:5:5: bodies[0].center_of_mass: a static body has no mass properties; remove "
            "center_of_mass (or static: true)");
}

}  // namespace
}  // namespace rbsim
