#pragma once
// Reading a terrain's grid of heights from a file: a greyscale PNG (8 or
// 16 bits per sample, through libpng) or a NumPy .npy array (2-D, of
// floats or integers). Load-time I/O only, like the mesh readers; files are
// untrusted, and every error names the file and what is wrong with it.
//
// The grid's orientation is a map's: row 0 is the terrain's −y edge and
// column 0 its −x edge, rows along +y, columns along +x. An image is seen
// from above with north up, so its top row is the +y edge: a PNG's rows
// are taken bottom up. An .npy array's rows are taken in order (its
// element [0][0] at −x, −y).

#include <string>
#include <vector>

#include "rbsim/physics/triangle_mesh.h"
#include "rbsim/physics/types.h"

namespace rbsim {

struct HeightGrid {
  int rows = 0;     // samples along y
  int columns = 0;  // samples along x
  // rows × columns values, row by row (row r, column c at r · columns + c).
  // A PNG's samples as fractions of full scale, in [0, 1] (65535 is 1 in a
  // 16-bit file); an .npy file's values as stored.
  std::vector<double> values;

  double at(int row, int column) const { return values[static_cast<std::size_t>(row * columns + column)]; }
};

// Limits on what a file may hold, checked before the values are stored:
// at least 2 × 2 samples (one cell), at most this many in all (1024 × 1024:
// a terrain's two triangles per cell stay within a mesh's limit,
// kMaxMeshTriangles).
inline constexpr long kMaxHeightSamples = 1024L * 1024;

// Chooses the reader by extension (.png, .npy; case-insensitive).
Expected<HeightGrid> loadHeightGrid(const std::string& path);
// Greyscale only (colour type 0, bit depth 8 or 16; no palette, no alpha):
// a height map that an editor saved in colour is refused rather than
// guessed at.
Expected<HeightGrid> loadHeightPng(const std::string& path);
// Format versions 1, 2 and 3; dtypes float32, float64, int8, uint8, int16,
// uint16, int32, uint32, in either byte order; C or Fortran order; two
// dimensions. Values must be finite.
Expected<HeightGrid> loadHeightNpy(const std::string& path);

// The terrain surface of a grid, as a triangle mesh: sample (r, c) at
// x = (c − (columns − 1)/2) cellX, y = (r − (rows − 1)/2) cellY (the grid
// centred on the shape's origin), z = heightScale · value + heightOffset;
// each cell split along its diagonal from (r, c) to (r + 1, c + 1) into
// two triangles wound counter-clockwise seen from +z (the front, up; the
// ground below). Sizes must be finite and positive, the scale finite.
TriangleMesh heightGridMesh(const HeightGrid& grid, double cellX, double cellY, double heightScale,
                            double heightOffset);

}  // namespace rbsim
