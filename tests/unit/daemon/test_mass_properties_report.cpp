// `rbserver --mass-properties`: the JSON report against closed forms.
#include <gtest/gtest.h>

#include "daemon/mass_properties_report.h"

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

}  // namespace
}  // namespace rbsim
