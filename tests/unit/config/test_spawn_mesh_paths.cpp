// Mesh files of bodies spawned over the network stay inside the spawn mesh
// directory: no absolute paths, no '..', no symbolic link leading out, only
// regular files. Config files given on the command line keep their freedom.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <string>

#include "config/config_loader.h"
#include "meshio/contained_path.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

namespace fs = std::filesystem;

const fs::path kConfigData = fs::path(rbsim::test_support::kTestDataDir) / "config";
const fs::path kOutsideMesh = fs::path(rbsim::test_support::kTestDataDir) / "meshes" / "cube.obj";

std::string spawnYaml(const std::string& file) {
  return "{name: spawned, shape: {type: mesh, file: '" + file + "'}, position: [0, 0, 1]}";
}

// A scratch spawn mesh directory with a mesh, links in and out, a FIFO.
class SpawnMeshDirectory : public ::testing::Test {
 protected:
  void SetUp() override {
    m_root = fs::temp_directory_path() /
             ("rbsim_spawn_paths_" + std::to_string(::getpid()) + "_" +
              ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(m_root);
    fs::create_directories(m_root / "meshes" / "deeper");
    fs::copy_file(kConfigData / "meshes" / "tetra.obj", m_root / "meshes" / "tetra.obj");
    fs::create_symlink("tetra.obj", m_root / "meshes" / "link_inside.obj");
    fs::create_symlink(kOutsideMesh, m_root / "meshes" / "link_outside.obj");
    fs::create_directory_symlink(kOutsideMesh.parent_path(), m_root / "outside_dir");
    ASSERT_EQ(::mkfifo((m_root / "meshes" / "pipe.obj").c_str(), 0600), 0);
  }
  void TearDown() override { fs::remove_all(m_root); }

  Expected<BodyDef> spawn(const std::string& file) const {
    const auto noBodies = [](const std::string&) { return std::optional<bool>(); };
    const Expected<SpawnDef> parsed = parseSpawnDef(spawnYaml(file), "spawn_yaml", m_root.string(), noBodies);
    if (!parsed) return parsed.error();
    return parsed->bodies.at(0);
  }
  // The rejection reason, which must not name the host's directories.
  std::string rejection(const std::string& file) const {
    const Expected<BodyDef> body = spawn(file);
    if (body) return "(accepted)";
    EXPECT_EQ(body.error().message.find(m_root.string()), std::string::npos) << body.error().message;
    return body.error().message;
  }

  fs::path m_root;
};

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(SpawnMeshDirectory, RelativePathsAndLinksThatStayInsideAreAccepted) {
  for (const std::string file : {"meshes/tetra.obj", "meshes/link_inside.obj", "./meshes/tetra.obj"}) {
    const Expected<BodyDef> body = spawn(file);
    ASSERT_TRUE(body.ok()) << file << ": " << body.error().message;
    const auto* mesh = std::get_if<MeshShape>(&body->shape);
    ASSERT_NE(mesh, nullptr);
    ASSERT_NE(mesh->mesh, nullptr);
    EXPECT_EQ(mesh->mesh->triangles.size(), 4u);
    EXPECT_EQ(mesh->file, file);  // as the sender named it, not the host's path
  }
}

TEST_F(SpawnMeshDirectory, AbsolutePathsAreRejectedEvenInsideTheDirectory) {
  const std::string inside = (m_root / "meshes" / "tetra.obj").string();
  const Expected<BodyDef> body = spawn(inside);
  ASSERT_FALSE(body.ok());
  EXPECT_TRUE(contains(body.error().message, "absolute paths are not allowed")) << body.error().message;
  EXPECT_TRUE(contains(rejection("/etc/passwd"), "absolute paths are not allowed"));
  // The YAML location of the offending key is in the message, like any config error.
  EXPECT_TRUE(contains(rejection("/etc/passwd"), "spawn_yaml:1:"));
  EXPECT_TRUE(contains(rejection("/etc/passwd"), "shape.file"));
}

TEST_F(SpawnMeshDirectory, DotDotIsRejectedWhereverItWouldLead) {
  EXPECT_TRUE(contains(rejection("../outside.obj"), "'..' is not allowed"));
  EXPECT_TRUE(contains(rejection("meshes/../meshes/tetra.obj"), "'..' is not allowed"));
  EXPECT_TRUE(contains(rejection("meshes/deeper/../../../../etc/passwd"), "'..' is not allowed"));
}

TEST_F(SpawnMeshDirectory, SymbolicLinksLeadingOutAreRejected) {
  EXPECT_TRUE(contains(rejection("meshes/link_outside.obj"), "outside the spawn mesh directory"));
  EXPECT_TRUE(contains(rejection("outside_dir/cube.obj"), "outside the spawn mesh directory"));
}

TEST_F(SpawnMeshDirectory, MissingFilesDirectoriesAndFifosAreRejected) {
  EXPECT_TRUE(contains(rejection("meshes/nothing.obj"), "no such file"));
  EXPECT_TRUE(contains(rejection("meshes/deeper"), "not a regular file"));
  // Opening a FIFO would block the server's only thread until a writer came.
  EXPECT_TRUE(contains(rejection("meshes/pipe.obj"), "not a regular file"));
  EXPECT_TRUE(contains(rejection(""), "mesh file path"));
}

TEST_F(SpawnMeshDirectory, TheRulesHoldForTheResolverAlone) {
  const Expected<std::string> inside = resolveContainedFile("meshes/link_inside.obj", m_root.string());
  ASSERT_TRUE(inside.ok()) << inside.error().message;
  EXPECT_EQ(*inside, fs::canonical(m_root / "meshes" / "tetra.obj").string());
  // The directory may itself be reached through a link or be relative.
  const fs::path linkedRoot = m_root.string() + "_link";
  fs::remove(linkedRoot);
  fs::create_directory_symlink(m_root, linkedRoot);
  EXPECT_TRUE(resolveContainedFile("meshes/tetra.obj", linkedRoot.string()).ok());
  EXPECT_FALSE(resolveContainedFile("meshes/link_outside.obj", linkedRoot.string()).ok());
  fs::remove(linkedRoot);
  EXPECT_FALSE(resolveContainedFile("x.obj", (m_root / "no_such_directory").string()).ok());
}

TEST(ConfigMeshPaths, ConfigFilesMayStillNameMeshesAnywhere) {
  // The same absolute path a spawned body may not use.
  const Expected<BodyDef> body = parseBodyDef(spawnYaml(kOutsideMesh.string()), "world.yaml", "/nonexistent");
  ASSERT_TRUE(body.ok()) << body.error().message;
  // And '..' relative to the config file.
  const Expected<WorldDef> world = loadWorldConfig((kConfigData / "nested" / "relative_mesh.yaml").string());
  EXPECT_TRUE(world.ok()) << world.error().message;
}

}  // namespace
}  // namespace rbsim
