// Robots spawned over LCM (command_t.spawn_yaml with a robots: list): they
// are made as a world file's robots are, and the sender, who is not
// trusted with the server's file system, reaches only files inside the
// spawn directory: the URDF, its package paths and every mesh it names.
// Refusals never name the host's directories.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "config/config_loader.h"
#include "rbsim/physics/world.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

namespace fs = std::filesystem;

const fs::path kUrdfData = fs::path(rbsim::test_support::kTestDataDir) / "urdf";

// A scratch spawn directory: robots/ with the test pendulum and the
// packaged-mesh robot and its package; a mesh outside it, and URDFs that
// try to reach it.
class SpawnRobots : public ::testing::Test {
 protected:
  void SetUp() override {
    m_base = fs::temp_directory_path() / ("rbsim_spawn_robots_" + std::to_string(::getpid()) + "_" +
                                          ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(m_base);
    m_root = m_base / "spawn";
    fs::create_directories(m_root / "robots");
    fs::copy_file(kUrdfData / "pendulum.urdf", m_root / "robots" / "pendulum.urdf");
    fs::copy_file(kUrdfData / "packaged_meshes.urdf", m_root / "robots" / "packaged_meshes.urdf");
    fs::copy(kUrdfData / "packages", m_root / "robots" / "packages", fs::copy_options::recursive);
    fs::copy_file(kUrdfData / "packages" / "rbsim_test_parts" / "meshes" / "tetrahedron.stl", m_base / "outside.stl");
    fs::copy_file(kUrdfData / "pendulum.urdf", m_base / "outside.urdf");
    fs::create_symlink(m_base / "outside.urdf", m_root / "robots" / "link_out.urdf");
    writeMeshRobot("climbs.urdf", "../../outside.stl");
    writeMeshRobot("absolute.urdf", (m_base / "outside.stl").string());
    writeMeshRobot("file_uri.urdf", "file://" + (m_base / "outside.stl").string());
    writeMeshRobot("inside.urdf", "packages/rbsim_test_parts/meshes/tetrahedron.stl");
  }
  void TearDown() override { fs::remove_all(m_base); }

  void writeMeshRobot(const std::string& name, const std::string& mesh) const {
    std::ofstream(m_root / "robots" / name)
        << "<robot name=\"m\"><link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" "
           "iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial><collision><geometry><mesh filename=\""
        << mesh << "\"/></geometry></collision></link></robot>\n";
  }

  Expected<SpawnDef> spawn(const std::string& yaml, const JointBodyLookup& existing = noBodies) const {
    return parseSpawnDef(yaml, "spawn_yaml", m_root.string(), existing);
  }
  // The refusal, which must not name the host's directories.
  std::string refusal(const std::string& yaml) const {
    const Expected<SpawnDef> made = spawn(yaml);
    if (made) return "(accepted)";
    EXPECT_EQ(made.error().message.find(m_base.string()), std::string::npos) << made.error().message;
    return made.error().message;
  }

  static std::optional<bool> noBodies(const std::string&) { return std::nullopt; }

  fs::path m_base, m_root;
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST_F(SpawnRobots, ARobotIsMadeAsAWorldFilesRobotIsAndMayBeJoinedToTheWorld) {
  const Expected<SpawnDef> made = spawn(
      "robots:\n"
      "  - {name: p, urdf: robots/pendulum.urdf, position: [0, 0, 2], fixed_base: true}\n"
      "  - {name: bin, urdf: robots/packaged_meshes.urdf, package_paths: [robots/packages], position: [3, 0, 1]}\n"
      "joints:\n"
      "  - {name: hold, type: fixed, body_a: world, body_b: bin/bin, anchor: [3, 0, 1]}\n");
  ASSERT_TRUE(made.ok()) << made.error().message;
  ASSERT_EQ(made->bodies.size(), 3u);
  EXPECT_EQ(made->bodies[0].name, "p/base");
  EXPECT_EQ(made->bodies[1].name, "p/bob");
  EXPECT_EQ(made->bodies[2].name, "bin/bin");
  ASSERT_EQ(made->joints.size(), 2u);
  EXPECT_EQ(made->joints[0].def.name, "p/swing");
  EXPECT_EQ(made->joints[1].def.name, "hold");
  EXPECT_FALSE(made->robotReport.empty());

  // It builds and steps: the spawn is a world's worth of bodies and joints.
  WorldDef def;
  def.bodies = made->bodies;
  def.joints = made->joints;
  Expected<World> world = World::fromDef(def);
  ASSERT_TRUE(world.ok()) << world.error().message;
  for (int k = 0; k < 10; ++k) world->step();
  EXPECT_LT(world->jointState(world->findJoint("hold")).error, 1e-9);
}

TEST_F(SpawnRobots, ItsBodiesMayNotTakeTheNamesOfTheWorlds) {
  const JointBodyLookup existing = [](const std::string& name) -> std::optional<bool> {
    return name == "p/bob" ? std::optional<bool>(true) : std::nullopt;
  };
  const Expected<SpawnDef> made = spawn("robots: [{name: p, urdf: robots/pendulum.urdf}]\n", existing);
  ASSERT_FALSE(made.ok());
  EXPECT_TRUE(contains(made.error().message, "makes a body named \"p/bob\", which the world already has"))
      << made.error().message;
}

TEST_F(SpawnRobots, TheUrdfMustLieInsideTheSpawnDirectory) {
  EXPECT_EQ(refusal("robots: [{name: p, urdf: ../outside.urdf}]"),
            "spawn_yaml:1:26: robots[0].urdf: file '../outside.urdf': '..' is not allowed in the paths of a spawn");
  const Expected<SpawnDef> absolute = spawn("robots: [{name: p, urdf: '" + (m_base / "outside.urdf").string() + "'}]");
  ASSERT_FALSE(absolute.ok());
  EXPECT_TRUE(contains(absolute.error().message, "robots[0].urdf: file '")) << absolute.error().message;
  EXPECT_TRUE(contains(absolute.error().message, "absolute paths are not allowed")) << absolute.error().message;
  EXPECT_TRUE(contains(refusal("robots: [{name: p, urdf: robots/link_out.urdf}]"),
                       "robots[0].urdf: file 'robots/link_out.urdf': resolves (through a symbolic link) to a file "
                       "outside the spawn mesh directory"));
  EXPECT_TRUE(contains(refusal("robots: [{name: p, urdf: robots/none.urdf}]"),
                       "robots[0].urdf: file 'robots/none.urdf': no such file in the spawn mesh directory"));
}

TEST_F(SpawnRobots, EveryMeshItNamesMustLieInsideToo) {
  EXPECT_TRUE(spawn("robots: [{name: m, urdf: robots/inside.urdf}]").ok()) << refusal("robots: [{name: m, urdf: robots/inside.urdf}]");
  EXPECT_TRUE(contains(refusal("robots: [{name: m, urdf: robots/climbs.urdf}]"), "link 'a': mesh '../../outside.stl'"));
  // Absolute paths (the sender's own words are all a refusal repeats).
  for (const std::string file : {"absolute.urdf", "file_uri.urdf"}) {
    SCOPED_TRACE(file);
    const Expected<SpawnDef> made = spawn("robots: [{name: m, urdf: robots/" + file + "}]");
    ASSERT_FALSE(made.ok());
    EXPECT_TRUE(contains(made.error().message, "link 'a': mesh '")) << made.error().message;
  }
}

TEST_F(SpawnRobots, PackagePathsStayInsideAndRosPackagePathIsNotConsulted) {
  EXPECT_TRUE(contains(
      refusal("robots: [{name: bin, urdf: robots/packaged_meshes.urdf, package_paths: [../robots/packages]}]"),
      "a spawned robot's package path must be relative to the spawn directory, with no '..'"));
  EXPECT_TRUE(contains(refusal("robots: [{name: bin, urdf: robots/packaged_meshes.urdf, package_paths: ['" +
                               (m_root / "robots" / "packages").string() + "']}]"),
                       "must be relative to the spawn directory"));
  // The package is on ROS_PACKAGE_PATH, but a sender may not use it.
  ::setenv("ROS_PACKAGE_PATH", (kUrdfData / "packages").c_str(), 1);
  const std::string why = refusal("robots: [{name: bin, urdf: robots/packaged_meshes.urdf}]");
  ::unsetenv("ROS_PACKAGE_PATH");
  EXPECT_TRUE(contains(why, "package 'rbsim_test_parts' not found in the package paths inside the spawn directory"))
      << why;
}

}  // namespace
}  // namespace rbsim
