// Mesh loading: OBJ and STL (ASCII and binary) of the same solid give the
// same mass properties, and every kind of bad file gives an error that names
// the file (and the line, for text formats).
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include "meshio/mesh_io.h"
#include "rbsim/physics/triangle_mesh.h"
#include "rbsim/physics/mass_properties.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

namespace fs = std::filesystem;

std::string dataPath(const std::string& name) {
  return std::string(rbsim::test_support::kTestDataDir) + "/meshes/" + name;
}

// cube.obj: side 2 m from (1, 2, 3) to (3, 4, 5).
const Vec3 kCubeHalf = Vec3::Ones();
const Vec3 kCubeCenter(2.0, 3.0, 4.0);

void expectSameMassProperties(const MassProperties& actual, const MassProperties& expected) {
  EXPECT_NEAR(actual.volume, expected.volume, 1e-12 * expected.volume);
  EXPECT_NEAR(actual.mass, expected.mass, 1e-12 * expected.mass);
  EXPECT_LE((actual.centerOfMass - expected.centerOfMass).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((actual.inertia - expected.inertia).cwiseAbs().maxCoeff(),
            1e-12 * expected.inertia.cwiseAbs().maxCoeff());
}

// A fresh directory per test for the files the tests write.
class MeshIo : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::path(testing::TempDir()) / ("rbsim_mesh_io_" + std::string(info->name()) + "_" +
                                            std::to_string(std::random_device{}()));
    fs::create_directories(m_dir);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(m_dir, ignored);
  }

  std::string path(const std::string& name) const { return (m_dir / name).string(); }

  std::string writeText(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }

 private:
  fs::path m_dir;
};

std::string asciiStl(const TriangleMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  out << "solid cube\n";
  for (const auto& t : mesh.triangles) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (int i : t) {
      const Vec3& p = mesh.vertices[static_cast<size_t>(i)];
      out << "      vertex " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid cube\n";
  return out.str();
}

void appendLittleEndian(std::string& bytes, std::uint32_t value) {
  for (int k = 0; k < 4; ++k) bytes += static_cast<char>((value >> (8 * k)) & 0xFFu);
}

// Binary STL as the format defines it: 80-byte header, uint32 count, then
// per triangle a normal, three vertices (float32, little-endian) and a
// uint16 attribute.
std::string binaryStl(const TriangleMesh& mesh, const std::string& header) {
  std::string bytes = header.substr(0, 80);
  bytes.resize(80, ' ');
  appendLittleEndian(bytes, static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) appendLittleEndian(bytes, 0);  // normal, ignored
    for (int i : t) {
      for (int axis = 0; axis < 3; ++axis) {
        const float x = static_cast<float>(mesh.vertices[static_cast<size_t>(i)][axis]);
        appendLittleEndian(bytes, std::bit_cast<std::uint32_t>(x));
      }
    }
    bytes += std::string(2, '\0');
  }
  return bytes;
}

TriangleMesh loadCubeObj() {
  Expected<TriangleMesh> mesh = loadMesh(dataPath("cube.obj"));
  EXPECT_TRUE(mesh.ok()) << mesh.error().message;
  return mesh.ok() ? *mesh : TriangleMesh{};
}

void expectLoadError(const std::string& path, const std::string& expectedText) {
  const Expected<TriangleMesh> mesh = loadMesh(path);
  ASSERT_FALSE(mesh.ok()) << "expected an error containing: " << expectedText;
  const std::string& message = mesh.error().message;
  EXPECT_EQ(message.rfind(path + ":", 0), 0u) << "does not start with the file name: " << message;
  EXPECT_NE(message.find(expectedText), std::string::npos) << message;
}

void expectValidationError(const std::string& path, const std::string& expectedText) {
  const Expected<TriangleMesh> mesh = loadMesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  const Expected<bool> valid = validateClosedMesh(*mesh, path);
  ASSERT_FALSE(valid.ok()) << "expected an error containing: " << expectedText;
  const std::string& message = valid.error().message;
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(expectedText), std::string::npos) << message;
}

// ------------------------------------------------------------- good files

TEST_F(MeshIo, ObjCubeWithMixedFaceSyntax) {
  const TriangleMesh mesh = loadCubeObj();
  ASSERT_EQ(mesh.vertices.size(), 8u);
  ASSERT_EQ(mesh.triangles.size(), 12u);
  EXPECT_EQ(mesh.vertices[3], Vec3(3.0, 4.0, 3.0));  // "v 3 4 3 1": w ignored
  EXPECT_EQ(mesh.vertices[7], Vec3(3.0, 4.0, 5.0));  // "v 3e0 4.0e+0 +5.0"
  // "f 1/1/1 3/4/1 4/3/1 2/2/1" as a fan from its first vertex.
  EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(mesh.triangles[1], (std::array<int, 3>{0, 3, 1}));
  // "f -8 -4 -2 -6" after 8 vertices is "f 1 5 7 3".
  EXPECT_EQ(mesh.triangles[8], (std::array<int, 3>{0, 4, 6}));
  EXPECT_EQ(mesh.triangles[9], (std::array<int, 3>{0, 6, 2}));
  ASSERT_TRUE(validateClosedMesh(mesh, "cube.obj").ok());

  const MassProperties props = polyhedronMassProperties(mesh, 800.0);
  MassProperties expected = boxMassProperties(kCubeHalf, 800.0);
  expected.centerOfMass = kCubeCenter;
  expectSameMassProperties(props, expected);
}

TEST_F(MeshIo, AsciiAndBinaryStlMatchObj) {
  const TriangleMesh obj = loadCubeObj();
  ASSERT_EQ(obj.triangles.size(), 12u);
  const MassProperties reference = polyhedronMassProperties(obj, 800.0);

  // The second binary file starts its header with "solid", as many
  // exporters do: only the size tells it from ASCII. The upper-case
  // extension checks that the reader is chosen case-insensitively.
  const std::string files[] = {
      writeText("cube_ascii.stl", asciiStl(obj)),
      writeText("cube_binary.stl", binaryStl(obj, "binary cube written by test_mesh_io")),
      writeText("cube_solid_header.STL", binaryStl(obj, "solid cube (binary, despite the name)")),
  };
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const Expected<TriangleMesh> stl = loadMesh(file);
    ASSERT_TRUE(stl.ok()) << stl.error().message;
    EXPECT_EQ(stl->vertices.size(), 8u);  // 36 corners welded
    EXPECT_EQ(stl->triangles.size(), 12u);
    ASSERT_TRUE(validateClosedMesh(*stl, file).ok());
    expectSameMassProperties(polyhedronMassProperties(*stl, 800.0), reference);
  }
}

TEST_F(MeshIo, HandWrittenAsciiStlTetrahedron) {
  // CRLF line ends, tabs, exponents and a "-0.0" that must weld with 0.
  const Expected<TriangleMesh> mesh = loadMesh(dataPath("tetrahedron.stl"));
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_EQ(mesh->vertices.size(), 4u);
  ASSERT_TRUE(validateClosedMesh(*mesh, "tetrahedron.stl").ok());
  const MassProperties props = polyhedronMassProperties(*mesh, 1.0);
  EXPECT_NEAR(props.volume, 1.0 / 6.0, 1e-15);
  EXPECT_LE((props.centerOfMass - Vec3::Constant(0.25)).cwiseAbs().maxCoeff(), 1e-15);
}

// ------------------------------------------------- meshes that load but are bad

TEST_F(MeshIo, OpenMeshIsRejected) {
  expectValidationError(dataPath("open_box.obj"), "mesh is open");
}

TEST_F(MeshIo, InconsistentWindingIsRejected) {
  expectValidationError(dataPath("inconsistent_winding.obj"), "inconsistent winding");
}

TEST_F(MeshIo, DegenerateTriangleIsRejected) {
  expectValidationError(dataPath("degenerate_triangle.obj"), "triangle 5 is degenerate: zero area");
}

TEST_F(MeshIo, InvertedCubeIsRejected) {
  expectValidationError(dataPath("inverted_cube.obj"), "the winding is inverted");
}

// ---------------------------------------------------------- unreadable files

TEST_F(MeshIo, ObjIndexOutOfRangeNamesFileAndLine) {
  const std::string file = dataPath("out_of_range.obj");
  const Expected<TriangleMesh> mesh = loadMesh(file);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.error().message, file + ":12: face index 9 out of range (8 vertices)");
}

TEST_F(MeshIo, ObjSyntaxErrors) {
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expectLoadError(writeText("zero.obj", vertices + "f 0 1 2\n"),
                  ":4: face index 0 is invalid (OBJ indices start at 1)");
  expectLoadError(writeText("negative.obj", vertices + "f -1 -2 -4\n"),
                  ":4: face index -4 out of range (3 vertices)");
  expectLoadError(writeText("two.obj", vertices + "\n# comment\nf 1 2\n"),
                  ":6: a face needs at least 3 vertices, found 2");
  expectLoadError(writeText("word.obj", vertices + "f 1 2 x/1/1\n"),
                  ":4: malformed face vertex 'x/1/1'");
  expectLoadError(writeText("short.obj", "v 1 2\n"), ":1: a vertex needs 3 coordinates");
  expectLoadError(writeText("abc.obj", "v 1 2 abc\n"), ":1: vertex coordinate 'abc' is not");
  expectLoadError(writeText("nan.obj", "v 1 nan 0\n"), ":1: vertex coordinate 'nan' is not");
  expectLoadError(writeText("huge.obj", "v 1 1e999 0\n"), ":1: vertex coordinate '1e999' is not");
  expectLoadError(writeText("nofaces.obj", vertices), "no faces ('f' lines) found");
}

TEST_F(MeshIo, GarbageFiles) {
  std::mt19937_64 rng(12345);
  std::string noise;
  for (int i = 0; i < 1000; ++i) noise += static_cast<char>(rng() & 0xFF);
  noise[10] = '\0';  // binary data, as any real binary file has
  expectLoadError(writeText("garbage.stl", noise), "not an STL file");
  expectLoadError(writeText("garbage.obj", noise), "contains a NUL byte: not a text OBJ file");
  expectLoadError(writeText("prose.obj", "This is not a mesh.\nNor is this.\n"),
                  "no faces ('f' lines) found");
  expectLoadError(writeText("prose.stl", "This is not a mesh.\n"),
                  "not an STL file: it does not start with 'solid' (ASCII STL), and it is too "
                  "short for a binary STL (20 bytes; the header alone is 84)");
}

TEST_F(MeshIo, TruncatedBinaryStl) {
  const TriangleMesh cube = loadCubeObj();
  std::string bytes = binaryStl(cube, "binary cube");
  ASSERT_EQ(bytes.size(), 84u + 50u * 12u);
  bytes.resize(bytes.size() - 20);
  expectLoadError(writeText("truncated.stl", bytes),
                  "truncated binary STL: the header declares 12 triangles, which need 684 bytes, "
                  "but the file has 664 bytes");

  // Same, with a header that starts with "solid": the ASCII reader fails on
  // the binary bytes, and the message still says what happened.
  std::string solidBytes = binaryStl(cube, "solid cube");
  solidBytes.resize(300);
  expectLoadError(writeText("truncated_solid.stl", solidBytes),
                  "as a binary STL it is truncated: the header declares 12 triangles");
}

TEST_F(MeshIo, AsciiStlErrors) {
  const TriangleMesh cube = loadCubeObj();
  const std::string text = asciiStl(cube);
  expectLoadError(writeText("cut.stl", text.substr(0, text.size() / 2)),
                  "unexpected end of file inside a solid");

  const std::string quad =
      "solid quad\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
      "   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid quad\n";
  expectLoadError(writeText("quad.stl", quad),
                  ":7: facet has more than 3 vertices; STL facets are triangles");
  const std::string typo =
      "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
      "   vertx 1 0 0\n";
  expectLoadError(writeText("typo.stl", typo), ":5: expected 'vertex' or 'endloop', found 'vertx'");
  expectLoadError(writeText("nofacets.stl", "solid nothing\nendsolid nothing\n"),
                  "ASCII STL contains no facets");
}

TEST_F(MeshIo, BinaryStlContentErrors) {
  TriangleMesh cube = loadCubeObj();
  expectLoadError(writeText("none.stl", binaryStl(TriangleMesh{}, "empty")),
                  "binary STL contains no triangles");
  cube.vertices[2].y() = std::numeric_limits<double>::quiet_NaN();
  expectLoadError(writeText("nan.stl", binaryStl(cube, "nan")),
                  "has a non-finite vertex coordinate");
}

TEST_F(MeshIo, MissingEmptyAndUnsupportedFiles) {
  expectLoadError(path("missing.obj"), "no such file");
  expectLoadError(writeText("empty.obj", ""), "file is empty");
  expectLoadError(writeText("empty.stl", ""), "file is empty");
  expectLoadError(writeText("cube.ply", "ply\n"), "unsupported mesh format '.ply'");
  fs::create_directory(path("folder.obj"));
  expectLoadError(path("folder.obj"), "is a directory");
}

TEST_F(MeshIo, TriangleLimitIsEnforced) {
  const std::string limitText = "more than " + std::to_string(kMaxMeshTriangles) + " triangles";

  // A binary STL of the right size for 2,000,001 triangles: a sparse file,
  // so the test writes 84 bytes, and the loader must refuse before reading
  // (or allocating for) the triangles.
  std::string header(80, ' ');
  appendLittleEndian(header, static_cast<std::uint32_t>(kMaxMeshTriangles) + 1u);
  const std::string big = writeText("big.stl", header);
  fs::resize_file(big, 84u + 50u * (static_cast<std::uintmax_t>(kMaxMeshTriangles) + 1u));
  expectLoadError(big, limitText);

  // One OBJ polygon with kMaxMeshTriangles + 3 corners fans into one
  // triangle too many (~4 MB of text).
  std::string face = "v 0 0 0\nf";
  face.reserve(face.size() + 2 * static_cast<size_t>(kMaxMeshTriangles) + 16);
  for (int k = 0; k < kMaxMeshTriangles + 3; ++k) face += " 1";
  face += '\n';
  expectLoadError(writeText("big.obj", face), ":2: " + limitText);
}

}  // namespace
}  // namespace rbsim
