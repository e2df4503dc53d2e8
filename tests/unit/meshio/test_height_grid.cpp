// Height grids from PNG and .npy files (meshio/height_grid.h): values and
// orientation worked by hand for each format and sample type, and a clear
// error for every kind of bad file. The PNG files are written here with
// libpng's simplified API; the .npy files byte by byte, as numpy.save
// writes them.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "meshio/height_grid.h"

namespace rbsim {
namespace {

class HeightGridFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    m_directory = std::filesystem::temp_directory_path() /
                  ("rbsim_height_grid_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(m_directory);
  }
  void TearDown() override { std::filesystem::remove_all(m_directory); }

  std::string path(const std::string& name) const { return (m_directory / name).string(); }

  std::string writeBytes(const std::string& name, const std::vector<unsigned char>& bytes) const {
    std::ofstream out(path(name), std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return path(name);
  }

  // A PNG of `width` × `height` in libpng's simplified `format`, rows top first.
  std::string writePng(const std::string& name, png_uint_32 width, png_uint_32 height, png_uint_32 format,
                       const void* pixels) const {
    png_image image;
    std::memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    image.width = width;
    image.height = height;
    image.format = format;
    EXPECT_NE(png_image_write_to_file(&image, path(name).c_str(), 0, pixels, 0, nullptr), 0) << image.message;
    return path(name);
  }

  // An .npy file: the magic, version, padded header and the data.
  std::string writeNpy(const std::string& name, const std::string& dict, const std::vector<unsigned char>& data,
                       int version = 1) const {
    std::string header = dict;
    const std::size_t prefix = version == 1 ? 10 : 12;
    while ((prefix + header.size() + 1) % 64 != 0) header += ' ';
    header += '\n';
    std::vector<unsigned char> bytes = {0x93, 'N', 'U', 'M', 'P', 'Y', static_cast<unsigned char>(version), 0};
    const std::size_t length = header.size();
    bytes.push_back(static_cast<unsigned char>(length & 0xff));
    bytes.push_back(static_cast<unsigned char>((length >> 8) & 0xff));
    if (version != 1) {
      bytes.push_back(static_cast<unsigned char>((length >> 16) & 0xff));
      bytes.push_back(static_cast<unsigned char>((length >> 24) & 0xff));
    }
    bytes.insert(bytes.end(), header.begin(), header.end());
    bytes.insert(bytes.end(), data.begin(), data.end());
    return writeBytes(name, bytes);
  }

  template <class T>
  static std::vector<unsigned char> raw(const std::vector<T>& values, bool bigEndian = false) {
    std::vector<unsigned char> bytes(values.size() * sizeof(T));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    if (bigEndian)
      for (std::size_t i = 0; i < values.size(); ++i)
        std::reverse(bytes.begin() + static_cast<std::ptrdiff_t>(i * sizeof(T)),
                     bytes.begin() + static_cast<std::ptrdiff_t>((i + 1) * sizeof(T)));
    return bytes;
  }

  void expectError(const Expected<HeightGrid>& grid, const std::string& file, const std::string& words) const {
    ASSERT_FALSE(grid.ok());
    EXPECT_NE(grid.error().message.find(path(file)), std::string::npos) << grid.error().message;
    EXPECT_NE(grid.error().message.find(words), std::string::npos) << grid.error().message;
  }

 private:
  std::filesystem::path m_directory;
};

TEST_F(HeightGridFiles, SixteenBitPngIsReadBottomRowFirstAsFractionsOfFullScale) {
  // 3 wide, 2 high; the image's top row is the grid's last (the +y edge).
  const uint16_t pixels[] = {0, 1, 2,            // top
                             65535, 32768, 7};   // bottom
  const auto grid = loadHeightGrid(writePng("terrain.PNG", 3, 2, PNG_FORMAT_LINEAR_Y, pixels));
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  ASSERT_EQ(grid->rows, 2);
  ASSERT_EQ(grid->columns, 3);
  EXPECT_EQ(grid->at(0, 0), 1.0);
  EXPECT_EQ(grid->at(0, 1), 32768.0 / 65535.0);
  EXPECT_EQ(grid->at(0, 2), 7.0 / 65535.0);
  EXPECT_EQ(grid->at(1, 0), 0.0);
  EXPECT_EQ(grid->at(1, 1), 1.0 / 65535.0);
  EXPECT_EQ(grid->at(1, 2), 2.0 / 65535.0);
}

TEST_F(HeightGridFiles, EightBitPng) {
  const uint8_t pixels[] = {10, 20, 30, 40};  // 2 × 2: top row 10 20
  const auto grid = loadHeightPng(writePng("h.png", 2, 2, PNG_FORMAT_GRAY, pixels));
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  EXPECT_EQ(grid->at(0, 0), 30.0 / 255.0);
  EXPECT_EQ(grid->at(0, 1), 40.0 / 255.0);
  EXPECT_EQ(grid->at(1, 0), 10.0 / 255.0);
  EXPECT_EQ(grid->at(1, 1), 20.0 / 255.0);
}

TEST_F(HeightGridFiles, BadPngsAreRefusedWithTheirReason) {
  const uint8_t rgb[2 * 2 * 3] = {};
  expectError(loadHeightPng(writePng("rgb.png", 2, 2, PNG_FORMAT_RGB, rgb)), "rgb.png", "greyscale");
  const uint8_t ga[2 * 2 * 2] = {};
  expectError(loadHeightPng(writePng("ga.png", 2, 2, PNG_FORMAT_GA, ga)), "ga.png", "alpha");
  const uint8_t line[5] = {};
  expectError(loadHeightPng(writePng("line.png", 5, 1, PNG_FORMAT_GRAY, line)), "line.png", "at least 2 × 2");
  expectError(loadHeightPng(writeBytes("text.png", {'h', 'e', 'l', 'l', 'o', ' ', 'p', 'n', 'g'})), "text.png",
              "not a PNG");
  // A good file cut short, in its header and in its data.
  const uint16_t pixels[64 * 64] = {};
  std::ifstream in(writePng("whole.png", 64, 64, PNG_FORMAT_LINEAR_Y, pixels), std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 60u);
  for (const std::size_t keep : {std::size_t{20}, bytes.size() - 20}) {
    const auto grid = loadHeightPng(writeBytes("cut.png", std::vector<unsigned char>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(keep))));
    ASSERT_FALSE(grid.ok()) << "kept " << keep;
    EXPECT_NE(grid.error().message.find(path("cut.png")), std::string::npos);
  }
  expectError(loadHeightPng(path("missing.png")), "missing.png", "cannot be opened");
  expectError(loadHeightPng(writeBytes("empty.png", {})), "empty.png", "empty");
}

TEST_F(HeightGridFiles, NpyOfEveryDtypeByteOrderAndLayout) {
  // Row 0 first, as stored: [[0.5, -1.25, 2], [3, 4, 1e-3]].
  const std::vector<double> values = {0.5, -1.25, 2.0, 3.0, 4.0, 1e-3};
  const auto check = [&](const Expected<HeightGrid>& grid, double tolerance) {
    ASSERT_TRUE(grid.ok()) << grid.error().message;
    ASSERT_EQ(grid->rows, 2);
    ASSERT_EQ(grid->columns, 3);
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(grid->at(r, c), values[static_cast<std::size_t>(3 * r + c)], tolerance);
  };
  check(loadHeightGrid(writeNpy("f8.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", raw(values))), 0.0);
  std::vector<float> floats(values.begin(), values.end());
  check(loadHeightNpy(writeNpy("f4.npy", "{'descr': '>f4', 'fortran_order': False, 'shape': (2, 3), }", raw(floats, true))), 1e-7);
  // Fortran order: column by column.
  const std::vector<double> byColumn = {0.5, 3.0, -1.25, 4.0, 2.0, 1e-3};
  check(loadHeightNpy(writeNpy("fortran.npy", "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }", raw(byColumn))), 0.0);
  // Version 2's longer header length; double quotes.
  check(loadHeightNpy(writeNpy("v2.npy", "{\"descr\": \"<f8\", \"fortran_order\": False, \"shape\": (2, 3)}", raw(values), 2)), 0.0);
  // Integers as stored.
  const std::vector<uint16_t> u16 = {0, 1, 65535, 7, 8, 9};
  auto grid = loadHeightNpy(writeNpy("u2.npy", "{'descr': '<u2', 'fortran_order': False, 'shape': (3, 2), }", raw(u16)));
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  EXPECT_EQ(grid->rows, 3);
  EXPECT_EQ(grid->at(1, 0), 65535.0);
  const std::vector<int8_t> i8 = {-128, 127, 0, -1};
  grid = loadHeightNpy(writeNpy("i1.npy", "{'descr': '|i1', 'fortran_order': False, 'shape': (2, 2), }", raw(i8)));
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  EXPECT_EQ(grid->at(0, 0), -128.0);
  EXPECT_EQ(grid->at(1, 1), -1.0);
  const std::vector<int32_t> i4 = {-100000, 5, 6, 7};
  grid = loadHeightNpy(writeNpy("i4.npy", "{'descr': '>i4', 'fortran_order': False, 'shape': (2, 2), }", raw(i4, true)));
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  EXPECT_EQ(grid->at(0, 0), -100000.0);
}

TEST_F(HeightGridFiles, BadNpyFilesAreRefusedWithTheirReason) {
  const std::vector<double> six(6, 1.0);
  expectError(loadHeightNpy(writeNpy("c16.npy", "{'descr': '<c16', 'fortran_order': False, 'shape': (2, 3), }", raw(six))),
              "c16.npy", "dtype '<c16'");
  expectError(loadHeightNpy(writeNpy("f2.npy", "{'descr': '<f2', 'fortran_order': False, 'shape': (2, 3), }", raw(six))),
              "f2.npy", "dtype '<f2'");
  expectError(loadHeightNpy(writeNpy("flat.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (6,), }", raw(six))),
              "flat.npy", "1 dimensions");
  expectError(loadHeightNpy(writeNpy("cube.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2, 3), }", raw(six))),
              "cube.npy", "3 dimensions");
  expectError(loadHeightNpy(writeNpy("short.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 3), }", raw(six))),
              "short.npy", "holds 48 bytes of data");
  expectError(loadHeightNpy(writeNpy("thin.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 6), }", raw(six))),
              "thin.npy", "at least 2 × 2");
  expectError(loadHeightNpy(writeNpy("huge.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (100000, 100000), }", raw(six))),
              "huge.npy", "more than the");
  std::vector<double> withNan = six;
  withNan[4] = std::nan("");
  expectError(loadHeightNpy(writeNpy("nan.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", raw(withNan))),
              "nan.npy", "row 1, column 1");
  expectError(loadHeightNpy(writeNpy("order.npy", "{'descr': '<f8', 'fortran_order': maybe, 'shape': (2, 3), }", raw(six))),
              "order.npy", "fortran_order");
  expectError(loadHeightNpy(writeNpy("noshape.npy", "{'descr': '<f8', 'fortran_order': False}", raw(six))),
              "noshape.npy", "'shape'");
  expectError(loadHeightNpy(writeNpy("v9.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", raw(six), 9)),
              "v9.npy", "version 9");
  expectError(loadHeightNpy(writeBytes("magic.npy", {'N', 'U', 'M', 'P', 'Y', 0, 0, 0, 0, 0, 0})), "magic.npy",
              "not a NumPy");
  // The header's length points past the end of the file.
  expectError(loadHeightNpy(writeBytes("cut.npy", {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, 0xff, 0x00, '{'})), "cut.npy",
              "ends inside its header");
  expectError(loadHeightGrid(writeBytes("terrain.tif", {1, 2, 3})), "terrain.tif", ".png or .npy");
}

TEST(HeightGridMesh, SamplesCentredOnTheOriginAndCellsFacingUp) {
  HeightGrid grid;
  grid.rows = 2;
  grid.columns = 3;
  grid.values = {0.0, 0.5, 1.0,   // row 0, at y = −0.2
                 2.0, 3.0, 4.0};  // row 1, at y = +0.2
  const TriangleMesh mesh = heightGridMesh(grid, 0.5, 0.4, 2.0, -1.0);
  ASSERT_EQ(mesh.vertices.size(), 6u);
  ASSERT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.vertices[0], Vec3(-0.5, -0.2, -1.0));
  EXPECT_EQ(mesh.vertices[2], Vec3(0.5, -0.2, 1.0));
  EXPECT_EQ(mesh.vertices[4], Vec3(0.0, 0.2, 5.0));
  // Every triangle faces up (+z), and the two of a cell cover it exactly once.
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vec3 n = (mesh.vertices[static_cast<std::size_t>(t[1])] - mesh.vertices[static_cast<std::size_t>(t[0])])
                       .cross(mesh.vertices[static_cast<std::size_t>(t[2])] - mesh.vertices[static_cast<std::size_t>(t[0])]);
    EXPECT_GT(n.z(), 0.0);
    area += 0.5 * n.z();  // the triangle's area seen from above
  }
  EXPECT_NEAR(area, 1.0 * 0.4, 1e-15);
}

}  // namespace
}  // namespace rbsim
