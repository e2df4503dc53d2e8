// Validation of wrench messages and paging of state messages.
#include <gtest/gtest.h>

#include <cmath>

#include "bridge/wire_convert.h"
#include "config/config_loader.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

World makeWorld(int count) {
  WorldSettings settings;
  settings.dt = 0.001;
  World world(settings);
  for (int i = 0; i < count; ++i) {
    BodyDef def;
    def.name = "body_" + std::to_string(i);
    def.shape = SphereShape{0.1};
    def.position = Vec3(i, 0, 0);
    EXPECT_TRUE(world.createBody(def).ok());
  }
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  EXPECT_TRUE(world.createBody(ground).ok());
  return world;
}

rbsim::wrench_t goodWrench() {
  rbsim::wrench_t w{};
  w.client = "test";
  w.seq = 7;
  w.body = "body_0";
  w.frame = rbsim::wrench_t::FRAME_WORLD;
  w.mode = rbsim::wrench_t::MODE_DURATION;
  w.force[0] = 1.0;
  w.duration = 0.0104;
  w.apply_at_step = -1;
  return w;
}

TEST(WireConvert, AcceptsAGoodWrenchAndRoundsTheDuration) {
  const World world = makeWorld(2);
  const auto request = wrenchRequestFrom(goodWrench(), world, 11, WrenchLimits{});
  ASSERT_TRUE(request.ok()) << request.error().message;
  EXPECT_EQ(request->firstStep, 11);
  EXPECT_EQ(request->durationSteps, 10);
  EXPECT_EQ(request->mode, WrenchMode::Duration);
  EXPECT_EQ(request->force, Vec3(1, 0, 0));
}

TEST(WireConvert, RejectsBadWrenchesWithReasons) {
  const World world = makeWorld(2);
  const auto reason = [&](rbsim::wrench_t w) {
    const auto r = wrenchRequestFrom(w, world, 11, WrenchLimits{});
    return r.ok() ? std::string("accepted") : r.error().message;
  };
  auto w = goodWrench();
  w.body = "nobody";
  EXPECT_NE(reason(w).find("unknown body"), std::string::npos);
  w = goodWrench();
  w.force[1] = std::nan("");
  EXPECT_NE(reason(w).find("finite"), std::string::npos);
  w = goodWrench();
  w.apply_at_step = 10;
  EXPECT_NE(reason(w).find("in the past"), std::string::npos);
  w = goodWrench();
  w.force[0] = 2e6;
  EXPECT_NE(reason(w).find("exceeds"), std::string::npos);
  w = goodWrench();
  w.mode = 9;
  EXPECT_NE(reason(w).find("mode"), std::string::npos);
  w = goodWrench();
  w.frame = 5;
  EXPECT_NE(reason(w).find("frame"), std::string::npos);
  w = goodWrench();
  w.point_frame = 3;  // 2 is POINT_FRAME_CENTER_OF_MASS
  EXPECT_NE(reason(w).find("unknown point_frame 3"), std::string::npos);
  w = goodWrench();
  w.duration = 0.0;
  EXPECT_NE(reason(w).find("duration"), std::string::npos);
  w = goodWrench();
  w.body = "ground";
  EXPECT_NE(reason(w).find("static"), std::string::npos);
  w = goodWrench();
  w.point[0] = 5000.0;
  EXPECT_NE(reason(w).find("from the centre of mass"), std::string::npos);
  // Clear with no body is fine, and ignores the (bad) force.
  w = goodWrench();
  w.mode = rbsim::wrench_t::MODE_CLEAR;
  w.body = "";
  w.force[0] = std::nan("");
  EXPECT_EQ(reason(w), "accepted");
}

TEST(WireConvert, PointFrameIsReadApartFromTheForceFrame) {
  const World world = makeWorld(4);  // body_3 at (3, 0, 0)
  auto w = goodWrench();
  w.body = "body_3";
  w.frame = rbsim::wrench_t::FRAME_WORLD;
  w.point_frame = rbsim::wrench_t::FRAME_BODY;
  w.point[0] = 0.1;
  const auto request = wrenchRequestFrom(w, world, 11, WrenchLimits{});
  ASSERT_TRUE(request.ok()) << request.error().message;
  EXPECT_EQ(request->frame, WrenchFrame::World);
  EXPECT_EQ(request->pointFrame, WrenchFrame::ShapeFrame);
  EXPECT_EQ(request->point, Vec3(0.1, 0, 0));
  // The lever-arm limit measures from the centre of mass in either frame.
  WrenchLimits limits;
  limits.maxLeverArm = 2.0;
  w.point[0] = 2.5;  // 2.5 m from the centre in the body, 0.5 m from it as a world point
  EXPECT_FALSE(wrenchRequestFrom(w, world, 11, limits).ok());
  w.point_frame = rbsim::wrench_t::FRAME_WORLD;
  EXPECT_TRUE(wrenchRequestFrom(w, world, 11, limits).ok());
  w.frame = rbsim::wrench_t::FRAME_BODY;
  const auto bodyForce = wrenchRequestFrom(w, world, 11, limits);
  ASSERT_TRUE(bodyForce.ok());
  EXPECT_EQ(bodyForce->frame, WrenchFrame::ShapeFrame);
  EXPECT_EQ(bodyForce->pointFrame, WrenchFrame::World);
}

TEST(WireConvert, LargeStatesArePagedUnderOneDatagram) {
  const World world = makeWorld(2000);
  const auto pages = worldStatePages(world, 42, 3);
  ASSERT_GT(pages.size(), 1u);
  int32_t next = 0;
  for (std::size_t i = 0; i < pages.size(); ++i) {
    const auto& page = pages[i];
    EXPECT_LE(static_cast<std::size_t>(page.getEncodedSize()), kMaxPagePayloadBytes);
    EXPECT_EQ(page.page, static_cast<int32_t>(i));
    EXPECT_EQ(page.num_pages, static_cast<int32_t>(pages.size()));
    EXPECT_EQ(page.total_bodies, 2001);
    EXPECT_EQ(page.first_body_index, next);
    EXPECT_EQ(page.num_bodies, static_cast<int32_t>(page.bodies.size()));
    EXPECT_EQ(page.world_revision, 3);
    next += page.num_bodies;
  }
  EXPECT_EQ(next, 2001);
  // Every body once, in creation order, with its serial id.
  EXPECT_EQ(pages.front().bodies.front().name, "body_0");
  EXPECT_EQ(pages.front().bodies.front().id, 1);
  EXPECT_EQ(pages.back().bodies.back().name, "ground");
  EXPECT_EQ(pages.back().bodies.back().id, 2001);
  EXPECT_EQ(pages.front().bodies[5].position[0], 5.0);
  EXPECT_EQ(pages.front().bodies[5].orientation[0], 1.0);  // w first
}

TEST(WireConvert, SmallStateIsOnePage) {
  const World world = makeWorld(3);
  const auto pages = worldStatePages(world, 0, 1);
  ASSERT_EQ(pages.size(), 1u);
  EXPECT_EQ(pages[0].num_pages, 1);
  EXPECT_EQ(pages[0].num_bodies, 4);
}

TEST(WireConvert, WorldDescriptionCarriesShapesAndMasses) {
  const World world = makeWorld(1);
  const auto pages = worldDescriptionPages(world, 0, 1);
  ASSERT_EQ(pages.size(), 1u);
  const auto& sphere = pages[0].bodies[0];
  EXPECT_EQ(sphere.shape_type, "sphere");
  EXPECT_EQ(sphere.radius, 0.1);
  EXPECT_NEAR(sphere.mass, 1000.0 * 4.0 / 3.0 * M_PI * 1e-3, 1e-12);
  EXPECT_NEAR(sphere.inertia[0], 0.4 * sphere.mass * 0.01, 1e-15);
  const auto& ground = pages[0].bodies[1];
  EXPECT_EQ(ground.shape_type, "plane");
  EXPECT_TRUE(ground.is_static);
  EXPECT_EQ(ground.plane_normal[2], 1.0);
}

TEST(WireConvert, SpawnedCompoundRoundTripsInTheWorldDescription) {
  // A spawn_yaml as rbserver receives it: parsed by the config loader, then
  // created, described and sent.
  const std::string yaml =
      "name: lever\n"
      "shape:\n"
      "  type: compound\n"
      "  shapes:\n"
      "    - {shape: {type: box, half_extents: [0.5, 0.05, 0.05]}}\n"
      "    - {shape: {type: sphere, radius: 0.1}, position: [0.5, 0, 0], density: 7800}\n"
      "    - {shape: {type: capsule, radius: 0.05, half_length: 0.2}, position: [-0.5, 0, 0],\n"
      "       rpy: [0, 1.5707963267948966, 0]}\n"
      "    - {shape: {type: mesh, file: meshes/tetra.obj}, position: [0, 0.3, 0]}\n"
      "position: [1, 2, 3]\n";
  const Expected<BodyDef> def =
      parseBodyDef(yaml, "spawn", std::string(rbsim::test_support::kTestDataDir) + "/config");
  ASSERT_TRUE(def.ok()) << def.error().message;
  World world;
  const BodyId id = *world.createBody(*def);
  const BodyView body = world.body(id);

  const auto pages = worldDescriptionPages(world, 0, 1);
  ASSERT_EQ(pages.size(), 1u);
  std::vector<uint8_t> bytes(static_cast<std::size_t>(pages[0].getEncodedSize()));
  ASSERT_EQ(pages[0].encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  rbsim::world_t decoded;
  ASSERT_EQ(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  ASSERT_EQ(decoded.num_bodies, 1);
  const rbsim::body_description_t& lever = decoded.bodies[0];
  EXPECT_EQ(lever.shape_type, "compound");
  EXPECT_EQ(lever.mass, body.mass());
  EXPECT_EQ(lever.inertia[1], body.dynamics().inertiaBody.y());
  // The shape frame's placement in body space, as for a mesh.
  const BodyDescription& d = body.description();
  for (int k = 0; k < 3; ++k) EXPECT_EQ(lever.shape_position[k], d.shapeTranslation[k]);
  const Quaternion placement{lever.shape_orientation[0], lever.shape_orientation[1],
                             lever.shape_orientation[2], lever.shape_orientation[3]};
  EXPECT_LE((placement.toRotationMatrix() - d.shapeRotation).cwiseAbs().maxCoeff(), 1e-12);

  ASSERT_EQ(lever.num_parts, 4);
  ASSERT_EQ(lever.parts.size(), 4u);
  const auto& bar = lever.parts[0];
  EXPECT_EQ(bar.shape_type, "box");
  EXPECT_EQ(bar.half_extents[0], 0.5);
  EXPECT_EQ(bar.half_extents[1], 0.05);
  EXPECT_EQ(bar.orientation[0], 1.0);
  const auto& ball = lever.parts[1];
  EXPECT_EQ(ball.shape_type, "sphere");
  EXPECT_EQ(ball.radius, 0.1);
  EXPECT_EQ(ball.position[0], 0.5);
  const auto& handle = lever.parts[2];
  EXPECT_EQ(handle.shape_type, "capsule");
  EXPECT_EQ(handle.radius, 0.05);
  EXPECT_EQ(handle.half_length, 0.2);
  EXPECT_EQ(handle.position[0], -0.5);
  EXPECT_NEAR(handle.orientation[0], std::sqrt(0.5), 1e-15);  // a quarter turn about y
  EXPECT_NEAR(handle.orientation[2], std::sqrt(0.5), 1e-15);
  const auto& wedge = lever.parts[3];
  EXPECT_EQ(wedge.shape_type, "mesh");
  EXPECT_EQ(wedge.num_vertices, 4);
  EXPECT_EQ(wedge.num_triangles, 4);
  EXPECT_EQ(wedge.position[1], 0.3);
  EXPECT_NE(wedge.mesh_file.find("tetra.obj"), std::string::npos);
  // Shapes that are not compounds carry no parts.
  EXPECT_EQ(worldDescriptionPages(makeWorld(1), 0, 1)[0].bodies[0].num_parts, 0);
}

TEST(WireConvert, GivenMassPropertiesAreFlaggedAndRebuildable) {
  // A body whose mass properties came from CAD: world_t says so, and the
  // centre of mass and tensor in the shape frame follow from its fields
  // (body_description_t.lcm gives the formulas).
  const std::string yaml =
      "{name: bracket, shape: {type: box, half_extents: [0.2, 0.1, 0.05]}, mass: 2.5,\n"
      " center_of_mass: [0.05, -0.02, 0.01],\n"
      " inertia: [[0.02, -0.003, 0.001], [-0.003, 0.03, 0.002], [0.001, 0.002, 0.04]]}";
  const Expected<BodyDef> def = parseBodyDef(yaml, "spawn", "");
  ASSERT_TRUE(def.ok()) << def.error().message;
  World world;
  ASSERT_TRUE(world.createBody(*def).ok());
  BodyDef computed;
  computed.name = "plain";
  computed.shape = BoxShape{Vec3(0.2, 0.1, 0.05)};
  computed.mass = 2.5;
  computed.position = Vec3(3, 0, 0);
  ASSERT_TRUE(world.createBody(computed).ok());

  const auto pages = worldDescriptionPages(world, 0, 1);
  std::vector<uint8_t> bytes(static_cast<std::size_t>(pages[0].getEncodedSize()));
  ASSERT_EQ(pages[0].encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  rbsim::world_t decoded;
  ASSERT_EQ(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  ASSERT_EQ(decoded.num_bodies, 2);
  const rbsim::body_description_t& bracket = decoded.bodies[0];
  EXPECT_TRUE(bracket.mass_properties_given);
  EXPECT_FALSE(decoded.bodies[1].mass_properties_given);
  EXPECT_EQ(bracket.mass, 2.5);
  const Quaternion placement{bracket.shape_orientation[0], bracket.shape_orientation[1],
                             bracket.shape_orientation[2], bracket.shape_orientation[3]};
  const Mat3 r = placement.toRotationMatrix();
  const Vec3 shapePosition(bracket.shape_position[0], bracket.shape_position[1],
                           bracket.shape_position[2]);
  const Vec3 center = -(r.transpose() * shapePosition);
  EXPECT_LT((center - *def->centerOfMass).norm(), 1e-15);
  const Vec3 moments(bracket.inertia[0], bracket.inertia[1], bracket.inertia[2]);
  const Mat3 tensor = r.transpose() * moments.asDiagonal() * r;
  EXPECT_LT((tensor - *def->inertia).cwiseAbs().maxCoeff(), 1e-15);
}

}  // namespace
}  // namespace rbsim

namespace rbsim {
namespace {

TEST(WireConvert, ContactsOfABoxRestingOnTheGround) {
  World world;
  BodyDef ground;
  ground.name = "ground";
  ground.shape = PlaneShape{};
  ground.isStatic = true;
  ASSERT_TRUE(world.createBody(ground).ok());
  BodyDef box;
  box.name = "box";
  box.shape = BoxShape{Vec3::Constant(0.1)};
  box.position = Vec3(0, 0, 0.1);
  ASSERT_TRUE(world.createBody(box).ok());
  for (int i = 0; i < 200; ++i) world.step();
  const auto pages = contactPages(world, 7);
  ASSERT_EQ(pages.size(), 1u);
  EXPECT_EQ(pages[0].step, 200);
  ASSERT_EQ(pages[0].num_contacts, 4);
  EXPECT_EQ(pages[0].total_contacts, 4);
  double totalImpulse = 0.0;
  for (const auto& c : pages[0].contacts) {
    EXPECT_EQ(c.body_a, 1);  // ground, then the box: normal from ground to box
    EXPECT_EQ(c.body_b, 2);
    EXPECT_EQ(c.normal[2], 1.0);
    EXPECT_EQ(c.classification, rbsim::contact_t::RESTING);
    EXPECT_NEAR(c.position[2], 0.0, 1e-3);
    totalImpulse += c.normal_impulse;
  }
  // At rest the contacts carry the weight: Σ j = m g dt.
  const double weight = world.body(world.findBody("box")).mass() * 9.81;
  EXPECT_NEAR(totalImpulse, weight * world.settings().dt, 1e-6 * weight);
}

}  // namespace
}  // namespace rbsim
