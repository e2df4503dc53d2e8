// `rbserver --mass-properties`: the JSON report against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "daemon/mass_properties_report.h"
#include "robot/urdf_robot.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

TEST(MassPropertiesReport, BoxInTheShapeFrame) {
  World world;
  BodyDef def;
  def.name = "crate \"A\"";
  def.shape = BoxShape{Vec3(0.5, 1.0, 1.5)};
  def.mass = 12.0;
  def.orientation = Quaternion::fromRollPitchYaw(0.3, 0.2, 0.1);  // the shape frame is reported
  ASSERT_TRUE(world.createBody(def).ok());
  const std::string json = massPropertiesJson(world);
  // I = m/3 (b² + c², a² + c², a² + b²) for half extents a, b, c.
  EXPECT_NE(json.find("\"name\": \"crate \\\"A\\\"\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"mass\": 12,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"volume\": 6,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"inertia\": [[13, 0, 0], [0, 10, 0], [0, 0, 5]]"), std::string::npos) << json;
  EXPECT_NE(json.find("\"principal_moments\": [13, 10, 5]"), std::string::npos) << json;
  EXPECT_NE(json.find("\"principal_axes\": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]"), std::string::npos)
      << json;
}

TEST(MassPropertiesReport, GivenMassPropertiesAreReportedAsGiven) {
  World world;
  BodyDef def;
  def.name = "plate";
  def.shape = SphereShape{0.5};  // collides as a ball, weighs as a plate
  def.mass = 4.0;
  def.inertia = Mat3(Vec3(1.0, 2.0, 3.0).asDiagonal());
  def.centerOfMass = Vec3(0.25, 0.0, -0.5);
  ASSERT_TRUE(world.createBody(def).ok());
  BodyDef computed;
  computed.name = "ball";
  computed.shape = SphereShape{0.5};
  computed.position = Vec3(3, 0, 0);
  ASSERT_TRUE(world.createBody(computed).ok());
  const std::string json = massPropertiesJson(world);
  const std::size_t ball = json.find("\"name\": \"ball\"");
  ASSERT_NE(ball, std::string::npos) << json;
  const std::string plate = json.substr(0, ball);
  EXPECT_NE(plate.find("\"source\": \"given\","), std::string::npos) << json;
  EXPECT_NE(plate.find("\"mass\": 4,"), std::string::npos) << json;
  EXPECT_NE(plate.find("\"center_of_mass\": [0.25, 0, -0.5],"), std::string::npos) << json;
  EXPECT_NE(plate.find("\"inertia\": [[1, 0, 0], [0, 2, 0], [0, 0, 3]]"), std::string::npos)
      << json;
  EXPECT_NE(plate.find("\"principal_moments\": [1, 2, 3]"), std::string::npos) << json;
  EXPECT_NE(json.substr(ball).find("\"source\": \"shape\","), std::string::npos) << json;
}

// A fixed base whose URDF says <mass value="0"/> (the KUKA iiwa's link 0,
// reported as 6.24 kg from its mesh before): static, mass 0, while the load
// report still lists its collision mesh. A base with no <inertial> is the same.
TEST(MassPropertiesReport, AStaticRobotBaseReportsNoMassWhateverItsMeshWeighs) {
  for (const std::string inertial : {std::string("<inertial><mass value=\"0\"/>"
                                                 "<inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/>"
                                                 "</inertial>"),
                                     std::string()}) {
    const std::string urdf =
        "<robot name=\"iiwa_like\">"
        "<link name=\"link_0\">" + inertial +
        "<collision><geometry><mesh filename=\"cube.obj\"/></geometry></collision></link>"
        "<link name=\"link_1\"><inertial><mass value=\"4\"/>"
        "<inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial>"
        "<collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision></link>"
        "<joint name=\"joint_1\" type=\"revolute\"><parent link=\"link_0\"/><child link=\"link_1\"/>"
        "<origin xyz=\"2 3 6\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>"
        "</joint></robot>";
    RobotPlacement placement;
    placement.name = "arm";
    placement.fixedBase = true;
    RobotFiles files;
    files.sourceName = "iiwa_like.urdf";
    files.directory = std::string(test_support::kTestDataDir) + "/meshes";
    const Expected<RobotModel> robot = buildRobot(urdf, placement, files);
    ASSERT_TRUE(robot.ok()) << robot.error().message;
    World world;
    for (const BodyDef& body : robot->bodies) ASSERT_TRUE(world.createBody(body).ok()) << body.name;
    const std::string json = massPropertiesJson(world);
    const std::size_t base = json.find("\"name\": \"arm/link_0\"");
    const std::size_t link1 = json.find("\"name\": \"arm/link_1\"");
    ASSERT_NE(base, std::string::npos) << json;
    ASSERT_NE(link1, std::string::npos) << json;
    const std::string baseEntry = json.substr(base, link1 - base);
    EXPECT_NE(baseEntry.find("\"shape\": \"mesh\""), std::string::npos) << baseEntry;
    EXPECT_NE(baseEntry.find("\"static\": true"), std::string::npos) << baseEntry;
    EXPECT_NE(baseEntry.find("\"source\": \"static\""), std::string::npos) << baseEntry;
    EXPECT_NE(baseEntry.find("\"mass\": 0,"), std::string::npos) << baseEntry;
    EXPECT_NE(baseEntry.find("\"volume\": 8,"), std::string::npos) << baseEntry;  // the 2 m cube's
    EXPECT_NE(baseEntry.find("\"inertia\": [[0, 0, 0], [0, 0, 0], [0, 0, 0]]"), std::string::npos) << baseEntry;
    EXPECT_NE(baseEntry.find("\"principal_moments\": [0, 0, 0]"), std::string::npos) << baseEntry;
    // The moving link keeps its URDF's numbers.
    EXPECT_NE(json.substr(link1).find("\"mass\": 4,"), std::string::npos) << json;
    // The load report still lists the base's collision shape.
    EXPECT_TRUE(std::any_of(robot->report.begin(), robot->report.end(), [](const std::string& line) {
      return line == "body 'arm/link_0': static, shape mesh";
    })) << ::testing::PrintToString(robot->report);
  }
}

TEST(MassPropertiesReport, AStaticBoxReportsNoMass) {
  World world;
  BodyDef def;
  def.name = "table";
  def.shape = BoxShape{Vec3(1.0, 0.5, 0.25)};
  def.isStatic = true;
  ASSERT_TRUE(world.createBody(def).ok());
  const std::string json = massPropertiesJson(world);
  EXPECT_NE(json.find("\"source\": \"static\","), std::string::npos) << json;
  EXPECT_NE(json.find("\"mass\": 0,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"volume\": 1,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"center_of_mass\": [0, 0, 0],"), std::string::npos) << json;
}

}  // namespace
}  // namespace rbsim
