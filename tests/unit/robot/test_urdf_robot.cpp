// Robots from URDF (robot/urdf_robot.h): each test description loads with
// the bodies, joints, limits and mass properties worked out by hand from
// its file, and every mistake that matters is refused with the file and
// the line.

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "rbsim/physics/world.h"
#include "robot/urdf_robot.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

const std::string kUrdfDir = std::string(rbsim::test_support::kTestDataDir) + "/urdf";
constexpr double kPi = 3.14159265358979323846;

RobotFiles filesFor(const std::string& name) {
  RobotFiles files;
  files.sourceName = name;
  files.packagePaths = {kUrdfDir + "/packages"};
  return files;
}

RobotModel load(const std::string& file, RobotPlacement placement = {}) {
  if (placement.name.empty()) placement.name = "r";
  Expected<RobotModel> robot = loadRobot(kUrdfDir + "/" + file, placement, filesFor(file));
  if (!robot) {
    ADD_FAILURE() << robot.error().message;
    return {};
  }
  return std::move(*robot);
}

std::string errorOf(const std::string& xml, RobotPlacement placement = {}) {
  if (placement.name.empty()) placement.name = "r";
  Expected<RobotModel> robot = buildRobot(xml, placement, filesFor("bad.urdf"));
  if (robot) {
    ADD_FAILURE() << "accepted:\n" << xml;
    return "";
  }
  return robot.error().message;
}

const BodyDef* bodyNamed(const RobotModel& robot, const std::string& name) {
  for (const BodyDef& body : robot.bodies)
    if (body.name == name) return &body;
  ADD_FAILURE() << "no body " << name;
  return nullptr;
}

const NamedJointDef* jointNamed(const RobotModel& robot, const std::string& name) {
  for (const NamedJointDef& joint : robot.joints)
    if (joint.def.name == name) return &joint;
  ADD_FAILURE() << "no joint " << name;
  return nullptr;
}

bool reportHas(const RobotModel& robot, const std::string& text) {
  for (const std::string& line : robot.report)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

std::string reportText(const RobotModel& robot) {
  std::string all;
  for (const std::string& line : robot.report) all += line + "\n";
  return all;
}

void expectMatrixNear(const Mat3& actual, const Mat3& expected, double tolerance) {
  EXPECT_LT((actual - expected).cwiseAbs().maxCoeff(), tolerance) << "actual\n" << actual << "\nexpected\n" << expected;
}

// A link with a 1 kg box, for descriptions written inline.
std::string boxLink(const std::string& name, const std::string& inertialExtra = "") {
  return "<link name=\"" + name + "\"><inertial>" + inertialExtra +
         "<mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial>"
         "<collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision></link>\n";
}

std::string robotXml(const std::string& inside) { return "<?xml version=\"1.0\"?>\n<robot name=\"t\">\n" + inside + "</robot>\n"; }

TEST(UrdfRobot, APendulumIsAStaticBaseAndABobOnAHinge) {
  RobotPlacement placement;
  placement.name = "pendulum";
  placement.position = {0, 0, 2};
  const RobotModel robot = load("pendulum.urdf", placement);
  ASSERT_EQ(robot.bodies.size(), 2u);
  const BodyDef& base = robot.bodies[0];
  EXPECT_EQ(base.name, "pendulum/base");
  EXPECT_TRUE(base.isStatic) << "a root without mass is static";
  EXPECT_EQ(base.position, Vec3(0, 0, 2));
  ASSERT_TRUE(std::holds_alternative<BoxShape>(base.shape));
  EXPECT_EQ(std::get<BoxShape>(base.shape).halfExtents, Vec3::Constant(0.05));

  const BodyDef& bob = robot.bodies[1];
  EXPECT_EQ(bob.name, "pendulum/bob");
  EXPECT_FALSE(bob.isStatic);
  EXPECT_EQ(*bob.mass, 1.0);
  EXPECT_EQ(*bob.centerOfMass, Vec3(1, 0, 0));
  EXPECT_EQ(*bob.inertia, Mat3(Vec3::Constant(0.001).asDiagonal()));
  EXPECT_EQ(bob.position, Vec3(0, 0, 2)) << "the link's frame is at the joint";
  ASSERT_TRUE(std::holds_alternative<CompoundShape>(bob.shape)) << "one collision away from the frame: a placed part";
  const CompoundShape& parts = std::get<CompoundShape>(bob.shape);
  ASSERT_EQ(parts.parts.size(), 1u);
  EXPECT_EQ(parts.parts[0].position, Vec3(1, 0, 0));
  EXPECT_EQ(std::get<SphereShape>(parts.parts[0].shape).radius, 0.05);

  ASSERT_EQ(robot.joints.size(), 1u);
  const NamedJointDef& swing = robot.joints[0];
  EXPECT_EQ(swing.def.name, "pendulum/swing");
  EXPECT_EQ(swing.def.type, JointType::Revolute);
  EXPECT_FALSE(swing.def.limit.enabled) << "continuous";
  EXPECT_EQ(swing.bodyA, "pendulum/base");
  EXPECT_EQ(swing.bodyB, "pendulum/bob");
  EXPECT_EQ(swing.def.anchor, Vec3(0, 0, 2));
  EXPECT_EQ(swing.def.axis, Vec3(0, 1, 0));
  EXPECT_NE(swing.source.find("pendulum.urdf:21: joint 'swing'"), std::string::npos) << swing.source;
}

TEST(UrdfRobot, AnArmsMassPropertiesAreItsInertialsTurnedIntoTheLinkFrame) {
  RobotPlacement placement;
  placement.fixedBase = true;
  const RobotModel robot = load("two_link_arm.urdf", placement);
  ASSERT_EQ(robot.bodies.size(), 3u);
  EXPECT_TRUE(bodyNamed(robot, "r/base")->isStatic) << "fixed_base";
  EXPECT_FALSE(bodyNamed(robot, "r/base")->mass.has_value()) << "a static body takes no mass properties";
  // The tensor diag(0.0417, 0.001, 0.0425) in a frame turned a quarter
  // turn about z: the link's x is the inertial frame's −y, so
  // R diag(a, b, c) Rᵀ = diag(b, a, c).
  const BodyDef& upper = *bodyNamed(robot, "r/upper");
  EXPECT_EQ(*upper.mass, 2.0);
  EXPECT_LT((*upper.centerOfMass - Vec3(0.25, 0, 0)).norm(), 1e-15);
  expectMatrixNear(*upper.inertia, Vec3(0.001, 0.0417, 0.0425).asDiagonal().toDenseMatrix(), 1e-12);
  const BodyDef& fore = *bodyNamed(robot, "r/fore");
  expectMatrixNear(*fore.inertia, Vec3(0.0005, 0.0208, 0.021).asDiagonal().toDenseMatrix(), 1e-12);
  EXPECT_EQ(fore.position, Vec3(0.5, 0, 0.1));

  const JointDef& shoulder = jointNamed(robot, "r/shoulder")->def;
  EXPECT_EQ(shoulder.type, JointType::Revolute);
  EXPECT_TRUE(shoulder.limit.enabled);
  EXPECT_EQ(shoulder.limit.lower, -2.0);
  EXPECT_EQ(shoulder.limit.upper, 2.0);
  EXPECT_EQ(shoulder.damping, 0.1);
  EXPECT_EQ(shoulder.friction, 0.05);
  EXPECT_EQ(shoulder.anchor, Vec3(0, 0, 0.1));
  const JointDef& elbow = jointNamed(robot, "r/elbow")->def;
  EXPECT_EQ(elbow.limit.lower, -2.5);
  EXPECT_EQ(elbow.anchor, Vec3(0.5, 0, 0.1));
  EXPECT_EQ(elbow.damping, 0.0) << "no <dynamics>";
  // <limit effort velocity> bound each joint's actuator.
  EXPECT_EQ(shoulder.actuatorLimits.effort, 50.0);
  EXPECT_EQ(shoulder.actuatorLimits.rate, 3.0);
  EXPECT_EQ(elbow.actuatorLimits.effort, 20.0);

  // Without a fixed base the root has its own mass.
  const RobotModel free = load("two_link_arm.urdf");
  const BodyDef& base = *bodyNamed(free, "r/base");
  EXPECT_FALSE(base.isStatic);
  EXPECT_EQ(*base.mass, 5.0);
  ASSERT_TRUE(std::holds_alternative<CylinderShape>(base.shape));
  EXPECT_EQ(std::get<CylinderShape>(base.shape).halfLength, 0.1) << "URDF gives the whole length";
}

TEST(UrdfRobot, InitialJointPositionsPlaceTheLinksThroughTheChain) {
  RobotPlacement placement;
  placement.position = {1, 2, 3};
  placement.orientation = Quaternion::fromAxisAngle(Vec3::UnitZ(), kPi / 2);
  placement.fixedBase = true;
  placement.jointPositions = {{"shoulder", 0.3}, {"elbow", -0.5}};
  const RobotModel robot = load("two_link_arm.urdf", placement);
  // By hand: the shoulder's frame is 0.1 m above the base; the upper link
  // turns 0.3 about y, so the elbow is at (0.5 cos 0.3, 0, 0.1 − 0.5 sin
  // 0.3) in the base's frame, which the placement turns by a quarter about
  // z ((x, y, z) -> (−y, x, z)) and moves by (1, 2, 3).
  const BodyDef& upper = *bodyNamed(robot, "r/upper");
  EXPECT_LT((upper.position - Vec3(1, 2, 3.1)).norm(), 1e-15);
  const BodyDef& fore = *bodyNamed(robot, "r/fore");
  const Vec3 elbow(1.0, 2.0 + 0.5 * std::cos(0.3), 3.0 + 0.1 - 0.5 * std::sin(0.3));
  EXPECT_LT((fore.position - elbow).norm(), 1e-12) << fore.position.transpose();
  // The forearm is turned by 0.3 − 0.5 about the arm's y, which is the
  // world's −x after the placement.
  const Mat3 expected = Quaternion::fromAxisAngle(Vec3::UnitZ(), kPi / 2).toRotationMatrix() *
                        Quaternion::fromAxisAngle(Vec3::UnitY(), -0.2).toRotationMatrix();
  expectMatrixNear(fore.orientation.toRotationMatrix(), expected, 1e-12);
  const JointDef& elbowJoint = jointNamed(robot, "r/elbow")->def;
  EXPECT_LT((elbowJoint.anchor - elbow).norm(), 1e-12);
  EXPECT_LT((elbowJoint.axis - Vec3(-1, 0, 0)).norm(), 1e-15);
  EXPECT_EQ(elbowJoint.position, -0.5) << "the joint reads its initial position there";
  EXPECT_EQ(jointNamed(robot, "r/shoulder")->def.position, 0.3);
}

TEST(UrdfRobot, AWheeledBaseHasFourWheelsOnAxlesAndItsMasslessLaserMergedIntoTheChassis) {
  const RobotModel robot = load("wheeled_base.urdf");
  ASSERT_EQ(robot.bodies.size(), 5u) << reportText(robot);
  const BodyDef& chassis = *bodyNamed(robot, "r/chassis");
  EXPECT_FALSE(chassis.isStatic);
  EXPECT_EQ(*chassis.mass, 10.0) << "the laser has no mass";
  ASSERT_TRUE(std::holds_alternative<CompoundShape>(chassis.shape));
  const CompoundShape& parts = std::get<CompoundShape>(chassis.shape);
  ASSERT_EQ(parts.parts.size(), 2u) << "the chassis's box and the laser's";
  EXPECT_LT((parts.parts[1].position - Vec3(0.4, 0, 0.125)).norm(), 1e-15);
  EXPECT_EQ(std::get<BoxShape>(parts.parts[1].shape).halfExtents, Vec3::Constant(0.025));
  EXPECT_TRUE(reportHas(robot, "link 'laser' merged into 'chassis'")) << reportText(robot);

  for (const char* wheel : {"front_left", "front_right", "rear_left", "rear_right"}) {
    SCOPED_TRACE(wheel);
    const BodyDef& body = *bodyNamed(robot, std::string("r/") + wheel);
    // diag(a, a, c) about the cylinder's z, turned onto y: diag(a, c, a).
    const double a = (3 * 0.01 + 0.0025) / 12, c = 0.005;
    expectMatrixNear(*body.inertia, Vec3(a, c, a).asDiagonal().toDenseMatrix(), 1e-12);
    const NamedJointDef& axle = *jointNamed(robot, std::string("r/") + wheel + "_axle");
    EXPECT_EQ(axle.def.type, JointType::Revolute);
    EXPECT_FALSE(axle.def.limit.enabled);
    EXPECT_EQ(axle.def.damping, 0.01);
    EXPECT_EQ(axle.def.axis, Vec3(0, 1, 0));
    EXPECT_EQ(axle.bodyA, "r/chassis");
    EXPECT_EQ(body.position, axle.def.anchor);
  }
  EXPECT_EQ(jointNamed(robot, "r/front_right_axle")->def.anchor, Vec3(0.35, -0.35, -0.1));
}

TEST(UrdfRobot, MergingFixedLinksCombinesTheirMassesExactly) {
  const std::string xml = robotXml(
      boxLink("a") +
      "<link name=\"b\"><inertial><mass value=\"3\"/>"
      "<inertia ixx=\"0.2\" ixy=\"0\" ixz=\"0\" iyy=\"0.2\" iyz=\"0\" izz=\"0.2\"/></inertial>"
      "<collision><geometry><sphere radius=\"0.1\"/></geometry></collision></link>\n"
      "<joint name=\"weld\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/><origin xyz=\"1 0 0\"/></joint>\n");
  RobotPlacement apart;
  apart.name = "r";
  Expected<RobotModel> separate = buildRobot(xml, apart, filesFor("m.urdf"));
  ASSERT_TRUE(separate.ok()) << separate.error().message;
  EXPECT_EQ(separate->bodies.size(), 2u) << "kept apart unless asked";
  ASSERT_EQ(separate->joints.size(), 1u);
  EXPECT_EQ(separate->joints[0].def.type, JointType::Fixed);

  RobotPlacement merged = apart;
  merged.mergeFixedLinks = true;
  Expected<RobotModel> one = buildRobot(xml, merged, filesFor("m.urdf"));
  ASSERT_TRUE(one.ok()) << one.error().message;
  ASSERT_EQ(one->bodies.size(), 1u);
  EXPECT_TRUE(one->joints.empty());
  const BodyDef& body = one->bodies[0];
  // 1 kg at 0 and 3 kg at 1 m: 4 kg at 0.75 m; about y and z each adds
  // m d² = 1 · 0.75² + 3 · 0.25² = 0.75 to 0.1 + 0.2.
  EXPECT_EQ(*body.mass, 4.0);
  EXPECT_LT((*body.centerOfMass - Vec3(0.75, 0, 0)).norm(), 1e-15);
  expectMatrixNear(*body.inertia, Vec3(0.3, 1.05, 1.05).asDiagonal().toDenseMatrix(), 1e-12);
  ASSERT_TRUE(std::holds_alternative<CompoundShape>(body.shape));
  EXPECT_EQ(std::get<CompoundShape>(body.shape).parts.size(), 2u);
}

TEST(UrdfRobot, AnOpenPackagedMeshCollidesAsItsConvexHull) {
  const RobotModel robot = load("packaged_meshes.urdf");
  ASSERT_EQ(robot.bodies.size(), 1u);
  const CompoundShape& parts = std::get<CompoundShape>(robot.bodies[0].shape);
  ASSERT_EQ(parts.parts.size(), 2u);
  const MeshShape& box = std::get<MeshShape>(parts.parts[0].shape);
  ASSERT_TRUE(box.mesh);
  ASSERT_EQ(box.mesh->vertices.size(), 8u) << "the open box's hull is its cube";
  EXPECT_EQ(box.mesh->triangles.size(), 12u);
  Vec3 lower, upper;
  usedVertexBounds(*box.mesh, lower, upper);
  EXPECT_LT((lower - Vec3(0.2, 0.4, 0.6)).norm(), 1e-15) << "scaled by 0.2";
  EXPECT_LT((upper - Vec3(0.6, 0.8, 1.0)).norm(), 1e-15);
  EXPECT_TRUE(validateClosedMesh(*box.mesh, "hull").ok()) << "the hull bounds a solid";
  EXPECT_TRUE(reportHas(robot, "open_box.obj' (10 triangles, open:")) << reportText(robot);
  EXPECT_EQ(std::get<MeshShape>(parts.parts[1].shape).mesh->vertices.size(), 4u);
  EXPECT_EQ(parts.parts[1].position, Vec3(0, 0, 0.5));
}

// A link whose collision mesh is a UV sphere of radius 0.1 m (`rings`
// latitude rings of `segments` vertices and the poles), written as OBJ next
// to the URDF in a temporary directory.
std::string writeSphereRobot(int rings, int segments) {
  const std::string directory = ::testing::TempDir();
  std::ofstream obj(directory + "/sphere_link.obj");
  obj << "v 0 0 0.1\nv 0 0 -0.1\n";
  for (int i = 1; i <= rings; ++i) {
    const double polar = kPi * i / (rings + 1);
    for (int j = 0; j < segments; ++j) {
      const double azimuth = 2.0 * kPi * j / segments;
      obj << "v " << 0.1 * std::sin(polar) * std::cos(azimuth) << " "
          << 0.1 * std::sin(polar) * std::sin(azimuth) << " " << 0.1 * std::cos(polar) << "\n";
    }
  }
  const auto at = [&](int ring, int j) { return 3 + (ring - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    obj << "f 1 " << at(1, j) << " " << at(1, j + 1) << "\n";
    obj << "f 2 " << at(rings, j + 1) << " " << at(rings, j) << "\n";
    for (int i = 1; i < rings; ++i) {
      obj << "f " << at(i, j) << " " << at(i + 1, j) << " " << at(i + 1, j + 1) << "\n";
      obj << "f " << at(i, j) << " " << at(i + 1, j + 1) << " " << at(i, j + 1) << "\n";
    }
  }
  return R"(<robot name="ball"><link name="ball">
      <inertial><mass value="2"/><inertia ixx="0.008" iyy="0.008" izz="0.008" ixy="0" ixz="0" iyz="0"/></inertial>
      <collision><geometry><mesh filename=")" +
         directory + R"(/sphere_link.obj"/></geometry></collision></link></robot>)";
}

TEST(UrdfRobot, ACollisionHullIsSimplifiedWithinTheToleranceAndTheReportSaysHowFar) {
  const std::string xml = writeSphereRobot(18, 24);  // 434 vertices
  const auto meshOf = [](const RobotModel& robot) {
    const BodyDef& body = robot.bodies.at(0);
    const auto* compound = std::get_if<CompoundShape>(&body.shape);
    const MeshShape& mesh = compound ? std::get<MeshShape>(compound->parts.at(0).shape)
                                     : std::get<MeshShape>(body.shape);
    return mesh.mesh;
  };
  RobotPlacement exact;
  exact.name = "r";
  exact.hullTolerance = 0.0;
  exact.hullMaxVertices = 100000;
  Expected<RobotModel> full = buildRobot(xml, exact, filesFor("ball.urdf"));
  ASSERT_TRUE(full.ok()) << full.error().message;
  EXPECT_EQ(meshOf(*full)->vertices.size(), 434u);
  const std::string fullText = reportText(*full);
  EXPECT_NE(fullText.find("collides as its convex hull (434 vertices)"), std::string::npos) << fullText;

  RobotPlacement cooked = exact;
  cooked.hullTolerance = 0.002;
  Expected<RobotModel> simplified = buildRobot(xml, cooked, filesFor("ball.urdf"));
  ASSERT_TRUE(simplified.ok()) << simplified.error().message;
  const std::size_t kept = meshOf(*simplified)->vertices.size();
  EXPECT_LT(kept, 434u);
  const std::string text = reportText(*simplified);
  EXPECT_NE(text.find("collides as its convex hull (434 vertices, simplified to " + std::to_string(kept) +
                      " vertices, the full hull within "),
            std::string::npos)
      << text;
  // Every vertex of the full hull within 2 mm of the simplified hull's faces.
  // (The simplified mesh is a hull, wound outwards: its triangles' planes.)
  const TriangleMesh& hull = *meshOf(*simplified);
  for (const Vec3& v : meshOf(*full)->vertices) {
    double outside = -1.0;
    for (const auto& triangle : hull.triangles) {
      const Vec3& a = hull.vertices[static_cast<std::size_t>(triangle[0])];
      const Vec3 normal = (hull.vertices[static_cast<std::size_t>(triangle[1])] - a)
                              .cross(hull.vertices[static_cast<std::size_t>(triangle[2])] - a)
                              .normalized();
      outside = std::max(outside, normal.dot(v - a));
    }
    EXPECT_LE(outside, 0.002 + 1e-9);
  }
  // The mass properties are the description's, whatever the hull.
  EXPECT_EQ(simplified->bodies[0].mass, full->bodies[0].mass);
  EXPECT_EQ(simplified->bodies[0].inertia, full->bodies[0].inertia);
  EXPECT_EQ(simplified->bodies[0].centerOfMass, full->bodies[0].centerOfMass);

  RobotPlacement budget = exact;
  budget.hullTolerance = 0.0001;
  budget.hullMaxVertices = 40;
  Expected<RobotModel> capped = buildRobot(xml, budget, filesFor("ball.urdf"));
  ASSERT_TRUE(capped.ok()) << capped.error().message;
  EXPECT_LE(meshOf(*capped)->vertices.size(), 40u);
}

TEST(UrdfRobot, APackageIsFoundThroughRosPackagePathOrNamedWhenItIsNot) {
  RobotPlacement placement;
  placement.name = "r";
  RobotFiles files;
  files.sourceName = "packaged_meshes.urdf";
  ::unsetenv("ROS_PACKAGE_PATH");
  Expected<RobotModel> missing = loadRobot(kUrdfDir + "/packaged_meshes.urdf", placement, files);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("packaged_meshes.urdf:6: link 'bin': mesh "
                                         "'package://rbsim_test_parts/meshes/open_box.obj': package "
                                         "'rbsim_test_parts' not found"),
            std::string::npos)
      << missing.error().message;
  ::setenv("ROS_PACKAGE_PATH", ("/nonexistent:" + kUrdfDir + "/packages").c_str(), 1);
  Expected<RobotModel> found = loadRobot(kUrdfDir + "/packaged_meshes.urdf", placement, files);
  ::unsetenv("ROS_PACKAGE_PATH");
  EXPECT_TRUE(found.ok()) << found.error().message;
}

TEST(UrdfRobot, WhatIsNotUsedIsReportedByElementAndLine) {
  const RobotModel robot = load("two_link_arm.urdf");
  const std::string text = reportText(robot);
  // Visuals and materials are how the links are drawn (RobotModel::visuals).
  EXPECT_FALSE(reportHas(robot, "material 'orange'")) << text;
  EXPECT_FALSE(reportHas(robot, "'upper'/visual")) << text;
  EXPECT_TRUE(reportHas(robot, "link 'upper': drawn as box, colour (1, 0.5, 0, 1)")) << text;
  EXPECT_TRUE(reportHas(robot, "two_link_arm.urdf:58: joint 'elbow'/safety_controller")) << text;
  EXPECT_TRUE(reportHas(robot, "two_link_arm.urdf:60: transmission 'shoulder_transmission'")) << text;
  EXPECT_TRUE(reportHas(robot, "two_link_arm.urdf:64: gazebo")) << text;
  EXPECT_TRUE(reportHas(robot, "joint 'r/shoulder': actuator limits effort 50 N·m, rate 3 rad/s")) << text;
  EXPECT_TRUE(reportHas(robot, "joint 'r/elbow': revolute 'r/upper' -> 'r/fore', axis (0, 1, 0), limits [-2.5, 2.5]"))
      << text;
}

// How links look: each <visual> beside its body, in the body's shape frame
// (the top link's frame), with its size, mesh (by URL under the viewer's
// mesh route), scale and colour; visuals that cannot be drawn are reported.
TEST(UrdfRobot, VisualsComeWithTheirShapesMeshesAndColours) {
  RobotPlacement placement;
  placement.name = "v";
  RobotFiles files = filesFor("visual_arm.urdf");
  files.meshRoute = kWorldMeshRoute;
  files.meshRouteDirectory = kUrdfDir;
  Expected<RobotModel> loaded = loadRobot(kUrdfDir + "/visual_arm.urdf", placement, files);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const RobotModel& robot = *loaded;
  const std::string text = reportText(robot);
  ASSERT_EQ(robot.bodies.size(), 2u) << text;
  ASSERT_EQ(robot.visuals.size(), 2u) << text;

  const std::vector<Visual>& base = robot.visuals.at("v/base");
  ASSERT_EQ(base.size(), 1u);
  EXPECT_EQ(base[0].kind, Visual::Kind::Box);
  EXPECT_TRUE(base[0].halfExtents.isApprox(Vec3(0.2, 0.1, 0.05)));
  EXPECT_TRUE(base[0].position.isApprox(Vec3(0, 0, 0.05)));
  EXPECT_TRUE(base[0].hasColor);  // the robot's material "teal", by name
  EXPECT_NEAR(base[0].rgba[0], 0.0, 1e-6);
  EXPECT_NEAR(base[0].rgba[1], 0.5, 1e-6);
  EXPECT_NEAR(base[0].rgba[2], 0.5, 1e-6);
  EXPECT_NEAR(base[0].rgba[3], 1.0, 1e-6);

  // The arm's own two drawable visuals, then the merged tip's sphere; the
  // .ply and the missing mesh are left out and reported.
  const std::vector<Visual>& arm = robot.visuals.at("v/arm");
  ASSERT_EQ(arm.size(), 3u) << text;
  const Visual& mesh = arm[0];
  EXPECT_EQ(mesh.kind, Visual::Kind::Mesh);
  EXPECT_EQ(mesh.meshFile, "package://rbsim_test_parts/meshes/tetrahedron.stl");
  EXPECT_EQ(mesh.meshUrl, "world/packages/rbsim_test_parts/meshes/tetrahedron.stl");
  EXPECT_TRUE(mesh.scale.isApprox(Vec3(2, 2, 0.5)));
  EXPECT_TRUE(mesh.position.isApprox(Vec3(0.1, 0, 0.2)));
  // rpy (0, 0, pi/2): x of the visual along y of the link.
  EXPECT_TRUE(mesh.orientation.rotate(Vec3::UnitX()).isApprox(Vec3::UnitY(), 1e-9));
  EXPECT_TRUE(mesh.hasColor);  // inline
  EXPECT_NEAR(mesh.rgba[0], 1.0, 1e-6);
  EXPECT_NEAR(mesh.rgba[1], 0.0, 1e-6);
  EXPECT_NEAR(mesh.rgba[2], 1.0, 1e-6);
  EXPECT_NEAR(mesh.rgba[3], 0.8, 1e-6);
  const Visual& cylinder = arm[1];
  EXPECT_EQ(cylinder.kind, Visual::Kind::Cylinder);
  EXPECT_DOUBLE_EQ(cylinder.radius, 0.03);
  EXPECT_DOUBLE_EQ(cylinder.halfLength, 0.2);
  EXPECT_TRUE(cylinder.hasColor);  // "teal" by name in a link's second visual
  EXPECT_NEAR(cylinder.rgba[1], 0.5, 1e-6);
  const Visual& tip = arm[2];
  EXPECT_EQ(tip.kind, Visual::Kind::Sphere);
  EXPECT_DOUBLE_EQ(tip.radius, 0.05);
  EXPECT_TRUE(tip.position.isApprox(Vec3(0, 0, 0.4)));  // the tip's frame in the arm's
  EXPECT_FALSE(tip.hasColor);

  EXPECT_TRUE(reportHas(robot, "link 'arm': drawn as mesh 'package://rbsim_test_parts/meshes/tetrahedron.stl' "
                               "(served as world/packages/rbsim_test_parts/meshes/tetrahedron.stl), colour (1, 0, 1, 0.8)"))
      << text;
  EXPECT_TRUE(reportHas(robot, "link 'arm': a <visual> is not drawn: mesh 'package://rbsim_test_parts/meshes/arm.ply'"))
      << text;
  EXPECT_TRUE(reportHas(robot, "link 'arm': a <visual> is not drawn:")) << text;
  EXPECT_TRUE(reportHas(robot, "missing.stl")) << text;
  EXPECT_FALSE(reportHas(robot, "not used")) << text;
  // Drawing is not physics: the bodies are what they are without visuals.
  EXPECT_EQ(shapeTypeName(robot.bodies[1].shape), std::string("cylinder"));
}

// A visual mesh outside the directory the viewer serves gets no URL (the
// viewer then draws the collision shape), and says so.
TEST(UrdfRobot, AVisualMeshOutsideTheServedDirectoryHasNoUrl) {
  RobotPlacement placement;
  placement.name = "v";
  RobotFiles files = filesFor("visual_arm.urdf");
  files.meshRoute = kWorldMeshRoute;
  files.meshRouteDirectory = kUrdfDir + "/packages/rbsim_test_parts/elsewhere";
  Expected<RobotModel> robot = loadRobot(kUrdfDir + "/visual_arm.urdf", placement, files);
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  EXPECT_EQ(robot->visuals.at("v/arm")[0].kind, Visual::Kind::Mesh);
  EXPECT_EQ(robot->visuals.at("v/arm")[0].meshUrl, "");
  files.meshRouteDirectory = kUrdfDir + "/packages/rbsim_test_parts";
  robot = loadRobot(kUrdfDir + "/visual_arm.urdf", placement, files);
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  EXPECT_EQ(robot->visuals.at("v/arm")[0].meshUrl, "world/meshes/tetrahedron.stl");
  // Without a route (a tool that draws nothing): no URLs at all.
  robot = loadRobot(kUrdfDir + "/visual_arm.urdf", placement, filesFor("visual_arm.urdf"));
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  EXPECT_EQ(robot->visuals.at("v/arm")[0].meshUrl, "");
  EXPECT_TRUE(reportHas(*robot, "outside the directory the viewer serves")) << reportText(*robot);
}

TEST(UrdfRobot, AMimicJointFollowsItsLeaderInTheWorld) {
  // The right finger mimics the left (multiplier 1): its joint follows
  // 'g/left_slide', is made after it, starts where the coupling puts it,
  // and in a world a drive on the leader moves both fingers together.
  RobotPlacement placement;
  placement.name = "g";
  placement.fixedBase = true;
  placement.jointPositions = {{"left_slide", 0.01}};
  const RobotModel robot = load("gripper_mimic.urdf", placement);
  const NamedJointDef* right = jointNamed(robot, "g/right_slide");
  ASSERT_NE(right, nullptr);
  EXPECT_TRUE(right->def.mimic.enabled);
  EXPECT_EQ(right->def.mimic.leader, "g/left_slide");
  EXPECT_EQ(right->def.mimic.multiplier, 1.0);
  EXPECT_EQ(right->def.mimic.offset, 0.0);
  EXPECT_EQ(right->def.position, 0.01) << "placed by its leader's position";
  EXPECT_LT(jointNamed(robot, "g/left_slide") - robot.joints.data(), right - robot.joints.data()) << "leader first";
  EXPECT_TRUE(reportHas(robot, "follows 'g/left_slide' (× 1 + 0)")) << reportText(robot);
  const BodyDef* finger = bodyNamed(robot, "g/finger_right");
  ASSERT_NE(finger, nullptr);
  EXPECT_NEAR(finger->position.x(), 0.03 - 0.01, 1e-15) << "moved 0.01 m along its axis, -x";

  WorldDef world;
  world.settings.gravity = Vec3(0, 0, -9.81);
  world.bodies = robot.bodies;
  world.joints = robot.joints;
  Expected<World> made = World::fromDef(world);
  ASSERT_TRUE(made.ok()) << made.error().message;
  const JointId left = made->findJoint("g/left_slide"), rightJoint = made->findJoint("g/right_slide");
  JointDrive drive;
  drive.enabled = true;
  drive.target = -0.015;
  drive.stiffness = 100.0;
  drive.damping = 2.0;
  ASSERT_TRUE(made->setJointDrive(left, drive).ok());
  const Expected<bool> refused = made->setJointDrive(rightJoint, drive);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("follows joint 'g/left_slide' (mimic)"), std::string::npos);
  double worst = 0.0;
  for (int k = 0; k < 1000; ++k) {
    made->step();
    worst = std::max(worst, std::abs(made->jointState(rightJoint).position - made->jointState(left).position));
  }
  EXPECT_LT(worst, 1e-9) << "m";
  EXPECT_NEAR(made->jointState(left).position, -0.015, 1e-3);
}

TEST(UrdfRobot, AMimicMustFollowAMovingJointThatExists) {
  const std::string links = boxLink("base") + boxLink("a") + boxLink("b");
  const auto joints = [](const std::string& mimic, const std::string& typeA = "revolute") {
    return "<joint name=\"ja\" type=\"" + typeA +
           "\"><parent link=\"base\"/><child link=\"a\"/><axis xyz=\"0 0 1\"/>"
           "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n"
           "<joint name=\"jb\" type=\"revolute\"><parent link=\"base\"/><child link=\"b\"/><axis xyz=\"0 0 1\"/>"
           "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>" +
           mimic + "</joint>\n";
  };
  EXPECT_NE(errorOf(robotXml(links + joints("<mimic joint=\"nobody\"/>"))).find("joint 'jb': <mimic joint='nobody'>: the robot has no such joint"),
            std::string::npos);
  EXPECT_NE(errorOf(robotXml(links + joints("<mimic joint=\"ja\"/>", "fixed")))
                .find("<mimic>: a revolute, continuous or prismatic joint follows another such joint ('ja' is fixed"),
            std::string::npos);
  RobotPlacement placement;
  placement.jointPositions = {{"jb", 0.2}};
  EXPECT_NE(errorOf(robotXml(links + joints("<mimic joint=\"ja\" multiplier=\"2\"/>")), placement)
                .find("joint_positions: joint 'jb' follows joint 'ja' (<mimic>): give its leader's position"),
            std::string::npos);
}

TEST(UrdfRobot, AZeroPoseBeyondALimitIsKeptAndReported) {
  // As Unitree A1's calves: limits [-2.696534, -0.916298], zero pose at 0.
  const std::string xml = robotXml(boxLink("thigh") + boxLink("calf") +
                                   "<joint name=\"calf_joint\" type=\"revolute\"><parent link=\"thigh\"/>"
                                   "<child link=\"calf\"/><axis xyz=\"0 1 0\"/>"
                                   "<limit lower=\"-2.696534\" upper=\"-0.916298\" effort=\"33.5\" velocity=\"21\"/>"
                                   "</joint>\n");
  RobotPlacement placement;
  placement.name = "a1";
  Expected<RobotModel> robot = buildRobot(xml, placement, filesFor("a1.urdf"));
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  EXPECT_EQ(jointNamed(*robot, "a1/calf_joint")->def.position, 0.0);
  EXPECT_TRUE(reportHas(*robot, "joint 'a1/calf_joint' starts at 0, 0.916298 rad above its upper limit -0.916298: "
                                "the limit brings it back over its first steps"))
      << reportText(*robot);
}

TEST(UrdfRobot, BrokenDescriptionsAreRefusedWithTheFileAndLine) {
  const std::string arm = boxLink("a") + boxLink("b");
  const auto joint = [](const std::string& type, const std::string& extra = "") {
    return "<joint name=\"j\" type=\"" + type + "\"><parent link=\"a\"/><child link=\"b\"/>" + extra + "</joint>\n";
  };
  EXPECT_NE(errorOf("<robot name=\"t\">\n<link name=\"a\">\n</robot>").find("bad.urdf:2: not well-formed XML"),
            std::string::npos);
  EXPECT_NE(errorOf("<model name=\"t\"/>").find("bad.urdf:1: a URDF's root element is <robot>, not <model>"),
            std::string::npos);
  EXPECT_NE(errorOf(robotXml(arm + joint("planar"))).find("bad.urdf:5: joint 'j': planar joints are not supported"),
            std::string::npos);
  EXPECT_NE(errorOf(robotXml(arm + joint("continuous", "<axis xyz=\"0 0 0\"/>"))).find("joint 'j': its <axis> is zero"),
            std::string::npos);
  // A link without mass that moves.
  const std::string massless = boxLink("a") + "<link name=\"b\"/>\n" + joint("continuous", "<axis xyz=\"0 0 1\"/>");
  EXPECT_NE(errorOf(robotXml(massless)).find("bad.urdf:4: link 'b': has no mass (no <inertial>, or mass 0) but moves on "
                                            "continuous joint 'j'"),
            std::string::npos)
      << errorOf(robotXml(massless));
  // An inertia no body has (the triangle inequality broken).
  const std::string badInertia =
      "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" "
      "izz=\"0.1\"/></inertial></link>\n";
  EXPECT_NE(errorOf(robotXml(badInertia)).find("bad.urdf:3: link 'a': its <inertia> is not one a rigid body can have"),
            std::string::npos)
      << errorOf(robotXml(badInertia));
  // A non-positive size.
  const std::string flat =
      "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" "
      "izz=\"0.1\"/></inertial><collision><geometry><sphere radius=\"-1\"/></geometry></collision></link>\n";
  EXPECT_NE(errorOf(robotXml(flat)).find("link 'a': a collision sphere's radius must be > 0, got -1"), std::string::npos)
      << errorOf(robotXml(flat));
  // A joint whose link the robot does not have is refused before urdfdom,
  // which would leak its half-built tree (found by fuzz_urdf_robot).
  const std::string missing = errorOf(robotXml(boxLink("a") + joint("revolute", "<axis xyz=\"0 0 1\"/>")));
  EXPECT_NE(missing.find("joint 'j': its child link 'b' is not a link of the robot"), std::string::npos) << missing;
  // urdfdom's own objections come through, with the line of the joint or
  // link they name.
  const std::string noLimits = errorOf(robotXml(arm + joint("revolute", "<axis xyz=\"0 0 1\"/>")));
  EXPECT_NE(noLimits.find("bad.urdf:5: not a valid URDF: Joint [j] is of type REVOLUTE but it does not specify limits"),
            std::string::npos)
      << noLimits;
}

// What is not yet a URDF (a xacro program, or values left for roslaunch)
// is refused with what to do and where, before urdfdom, whose own messages
// say neither ("No link elements found", "Unable to parse component").
TEST(UrdfRobot, XacroFilesAndSubstitutionsAreRefusedWithTheCommandThatExpandsThem) {
  RobotPlacement placement;
  placement.name = "r";
  RobotFiles xacroFiles = filesFor("robots/arm.urdf.xacro");
  const std::string xacro =
      "<?xml version=\"1.0\"?>\n<robot name=\"arm\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
      "  <xacro:include filename=\"$(find arm)/urdf/arm.xacro\"/>\n</robot>\n";
  Expected<RobotModel> byName = buildRobot(xacro, placement, xacroFiles);
  ASSERT_FALSE(byName.ok());
  EXPECT_EQ(byName.error().message,
            "robots/arm.urdf.xacro:3: a xacro file (<xacro:include>), not a URDF: expand it first: "
            "`xacro robots/arm.urdf.xacro > arm.urdf`");
  // Named .urdf but holding xacro elements: still a xacro file.
  const std::string elements = errorOf(xacro);
  EXPECT_NE(elements.find("bad.urdf:3: a xacro file (<xacro:include>), not a URDF: expand it first"),
            std::string::npos)
      << elements;
  // The namespace alone is no xacro: xacro's output keeps it (bullet3's iiwa).
  Expected<RobotModel> expanded = buildRobot(
      "<robot name=\"a\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n<link name=\"a\"/>\n</robot>",
      placement, filesFor("expanded.urdf"));
  EXPECT_TRUE(expanded.ok()) << expanded.error().message;
  // Named .xacro without the namespace.
  Expected<RobotModel> plainXacro =
      buildRobot("<robot name=\"a\">\n<link name=\"a\"/>\n</robot>", placement, filesFor("base.xacro"));
  ASSERT_FALSE(plainXacro.ok());
  EXPECT_NE(plainXacro.error().message.find("base.xacro:1: a xacro file (by its name), not a URDF: expand it first: "
                                            "`xacro base.xacro > base.urdf`"),
            std::string::npos)
      << plainXacro.error().message;

  // Clearpath Husky's style: a value left for roslaunch.
  const std::string optenv = errorOf(
      "<robot name=\"husky\">\n<link name=\"base\"/>\n<link name=\"top\"/>\n"
      "<joint name=\"mount\" type=\"fixed\"><parent link=\"base\"/><child link=\"top\"/>\n"
      "  <origin xyz=\"$(optenv HUSKY_TOP_X 0.0) 0 0.2\"/></joint>\n</robot>");
  EXPECT_NE(optenv.find("bad.urdf:5: <origin> xyz=\"$(optenv HUSKY_TOP_X 0.0) 0 0.2\" holds the substitution "
                        "'$(optenv HUSKY_TOP_X 0.0)', which only roslaunch or xacro expand"),
            std::string::npos)
      << optenv;
  const std::string expression = errorOf(
      "<robot name=\"r\">\n<link name=\"a\">\n<collision><geometry><box size=\"${width} 1 1\"/>"
      "</geometry></collision></link>\n</robot>");
  EXPECT_NE(expression.find("bad.urdf:3: <box> size=\"${width} 1 1\" holds the substitution '${width}'"),
            std::string::npos)
      << expression;
}

// Joints that make no tree are refused before urdfdom builds its links:
// urdfdom would link them into a loop of shared pointers never freed.
TEST(UrdfRobot, JointsThatMakeNoTreeAreRefusedWithTheirLines) {
  const auto joint = [](const std::string& name, const std::string& parent, const std::string& child) {
    return "<joint name=\"" + name + "\" type=\"fixed\"><parent link=\"" + parent + "\"/><child link=\"" + child +
           "\"/></joint>\n";
  };
  const std::string links = boxLink("a") + boxLink("b") + boxLink("c");
  EXPECT_NE(errorOf(robotXml(links + joint("j", "b", "b"))).find("bad.urdf:6: joint 'j': joins link 'b' to itself"),
            std::string::npos);
  const std::string twoParents = errorOf(robotXml(links + joint("j1", "a", "c") + joint("j2", "b", "c")));
  EXPECT_NE(twoParents.find("bad.urdf:7: joint 'j2': link 'c' is already the child of joint 'j1' (line 6)"),
            std::string::npos)
      << twoParents;
  const std::string loop = errorOf(robotXml(links + joint("j1", "a", "b") + joint("j2", "b", "a")));
  EXPECT_NE(loop.find("the joints make a loop"), std::string::npos) << loop;
  // A loop hanging below a root: every link has a parent but c.
  const std::string hanging =
      errorOf(robotXml(links + boxLink("d") + joint("j1", "c", "d") + joint("j2", "a", "b") + joint("j3", "b", "a")));
  EXPECT_NE(hanging.find("the joints make a loop"), std::string::npos) << hanging;
}

// ur_description and other public descriptions use COLLADA for collision
// meshes too: the same tetrahedron as .dae and as .stl gives the same hull.
TEST(UrdfRobot, ACollisionMeshMayBeCollada) {
  RobotPlacement placement;
  placement.name = "r";
  const auto linkWith = [](const std::string& mesh) {
    return robotXml(
        "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" "
        "iyz=\"0\" izz=\"0.1\"/></inertial><collision><geometry><mesh filename=\"package://rbsim_test_parts/meshes/" +
        mesh + "\" scale=\"0.5 0.5 0.5\"/></geometry></collision></link>\n");
  };
  Expected<RobotModel> dae = buildRobot(linkWith("tetrahedron.dae"), placement, filesFor("dae.urdf"));
  ASSERT_TRUE(dae.ok()) << dae.error().message;
  Expected<RobotModel> stl = buildRobot(linkWith("tetrahedron.stl"), placement, filesFor("stl.urdf"));
  ASSERT_TRUE(stl.ok()) << stl.error().message;
  const TriangleMesh& fromDae = *std::get<MeshShape>(dae->bodies[0].shape).mesh;
  const TriangleMesh& fromStl = *std::get<MeshShape>(stl->bodies[0].shape).mesh;
  std::vector<Vec3> daeCorners = fromDae.vertices, stlCorners = fromStl.vertices;
  const auto lexicographic = [](const Vec3& p, const Vec3& q) {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  };
  std::sort(daeCorners.begin(), daeCorners.end(), lexicographic);
  std::sort(stlCorners.begin(), stlCorners.end(), lexicographic);
  EXPECT_EQ(daeCorners, stlCorners);
  EXPECT_EQ(daeCorners.size(), 4u);
  EXPECT_TRUE(reportHas(*dae, "link 'a': mesh 'package://rbsim_test_parts/meshes/tetrahedron.dae' (4 triangles, closed)"))
      << reportText(*dae);
}

// A format rbsim does not read is refused by its extension, with the link.
TEST(UrdfRobot, AnUnreadMeshFormatIsRefusedByName) {
  const std::string directory = ::testing::TempDir();
  std::ofstream(directory + "/part.3ds") << "not read";
  RobotPlacement placement;
  placement.name = "r";
  RobotFiles files = filesFor("3ds.urdf");
  files.directory = directory;
  const std::string xml = robotXml(
      "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" "
      "izz=\"0.1\"/></inertial><collision><geometry><mesh filename=\"part.3ds\"/></geometry></collision></link>\n");
  Expected<RobotModel> robot = buildRobot(xml, placement, files);
  ASSERT_FALSE(robot.ok());
  EXPECT_NE(robot.error().message.find("3ds.urdf:3: link 'a': "), std::string::npos) << robot.error().message;
  EXPECT_NE(robot.error().message.find("part.3ds: unsupported mesh format '.3ds' (expected .obj, .stl or .dae)"),
            std::string::npos)
      << robot.error().message;
}

TEST(UrdfRobot, JointPositionsMustNameMovingJointsWithinTheirLimits) {
  const auto errorWith = [](std::map<std::string, double, std::less<>> positions) {
    RobotPlacement placement;
    placement.name = "r";
    placement.jointPositions = std::move(positions);
    Expected<RobotModel> robot = loadRobot(kUrdfDir + "/two_link_arm.urdf", placement, filesFor("arm.urdf"));
    return robot.ok() ? std::string("accepted") : robot.error().message;
  };
  EXPECT_NE(errorWith({{"wrist", 0.1}}).find("joint_positions: the robot has no joint 'wrist'"), std::string::npos);
  EXPECT_NE(errorWith({{"elbow", 3.0}}).find("joint_positions: joint 'elbow' at 3 is outside its limits [-2.5, 2.5]"),
            std::string::npos);
  RobotPlacement placement;
  placement.name = "r";
  placement.jointPositions = {{"laser_mount", 0.1}};
  Expected<RobotModel> fixed = loadRobot(kUrdfDir + "/wheeled_base.urdf", placement, filesFor("base.urdf"));
  ASSERT_FALSE(fixed.ok());
  EXPECT_NE(fixed.error().message.find("joint_positions: joint 'laser_mount' is fixed"), std::string::npos);
}

}  // namespace
}  // namespace rbsim
