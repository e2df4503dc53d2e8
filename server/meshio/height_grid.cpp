#include "meshio/height_grid.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

namespace rbsim {

namespace {

Error fileError(const std::string& path, const std::string& text) {
  return Error{path + ": " + text};
}

std::string lowercaseExtension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string extension = path.substr(dot);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// The whole file, or why not. A height file holds at most kMaxHeightSamples
// values of 8 bytes and a header; anything larger is refused unread.
constexpr std::uintmax_t kMaxFileBytes = 8 * static_cast<std::uintmax_t>(kMaxHeightSamples) + (1u << 20);

Expected<std::vector<unsigned char>> readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return fileError(path, "cannot be opened (missing, unreadable or a directory)");
  const std::streamoff size = in.tellg();
  if (size < 0) return fileError(path, "cannot be read (its size is unknown; a directory?)");
  if (size == 0) return fileError(path, "is empty");
  if (static_cast<std::uintmax_t>(size) > kMaxFileBytes)
    return fileError(path, "is " + std::to_string(size) + " bytes, more than a height grid of " +
                               std::to_string(kMaxHeightSamples) + " samples can take");
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) return fileError(path, "cannot be read");
  return bytes;
}

std::string gridSizeProblem(long rows, long columns) {
  if (rows < 2 || columns < 2)
    return "has " + std::to_string(rows) + " × " + std::to_string(columns) +
           " samples; a height grid needs at least 2 × 2 (one cell)";
  if (rows > kMaxHeightSamples / columns)
    return "has " + std::to_string(rows) + " × " + std::to_string(columns) + " samples, more than the " +
           std::to_string(kMaxHeightSamples) + " a height grid may have";
  return "";
}

// --- PNG, through libpng ---
//
// libpng reports errors by longjmp. Everything the reading changes lives in
// the caller's PngRead (reached through a pointer, not an automatic object
// of the function that calls setjmp), so nothing is left indeterminate by
// the jump and every destructor still runs.
struct PngRead {
  const std::vector<unsigned char>* bytes = nullptr;
  std::size_t at = 0;
  std::string failure;
  png_uint_32 width = 0, height = 0;
  int bitDepth = 0;
  std::vector<unsigned char> pixels;
  std::vector<png_bytep> rows;
};

void pngReadBytes(png_structp png, png_bytep out, png_size_t count) {
  auto* read = static_cast<PngRead*>(png_get_io_ptr(png));
  if (count > read->bytes->size() - read->at) png_error(png, "the file ends in the middle of its data");
  std::memcpy(out, read->bytes->data() + read->at, count);
  read->at += count;
}

[[noreturn]] void pngOnError(png_structp png, png_const_charp message) {
  auto* read = static_cast<PngRead*>(png_get_error_ptr(png));
  if (read->failure.empty()) read->failure = message;
  png_longjmp(png, 1);
}

void pngOnWarning(png_structp, png_const_charp) {}

const char* colourTypeName(int type) {
  switch (type) {
    case PNG_COLOR_TYPE_GRAY_ALPHA: return "greyscale with alpha";
    case PNG_COLOR_TYPE_PALETTE: return "a palette";
    case PNG_COLOR_TYPE_RGB: return "RGB";
    case PNG_COLOR_TYPE_RGB_ALPHA: return "RGBA";
    default: return "an unknown colour type";
  }
}

bool readPng(PngRead* read) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, read, pngOnError, pngOnWarning);
  if (png == nullptr) {
    read->failure = "libpng could not start reading";
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    read->failure = "libpng could not start reading";
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, read, pngReadBytes);
  // Refused before any row is stored: images larger than a grid may be.
  png_set_user_limits(png, static_cast<png_uint_32>(kMaxHeightSamples / 2),
                      static_cast<png_uint_32>(kMaxHeightSamples / 2));
  png_read_info(png, info);
  int colourType = 0, interlace = 0;
  png_get_IHDR(png, info, &read->width, &read->height, &read->bitDepth, &colourType, &interlace, nullptr, nullptr);
  if (colourType != PNG_COLOR_TYPE_GRAY) {
    read->failure = std::string("is ") + colourTypeName(colourType) +
                    " PNG; a height map must be greyscale (one channel, 8 or 16 bits), without alpha";
    png_error(png, "colour type");
  }
  if (read->bitDepth != 8 && read->bitDepth != 16) {
    read->failure = "has " + std::to_string(read->bitDepth) +
                    " bits per sample; a height map must have 8 or 16";
    png_error(png, "bit depth");
  }
  if (const std::string problem = gridSizeProblem(read->height, read->width); !problem.empty()) {
    read->failure = problem;
    png_error(png, "size");
  }
  if (interlace != PNG_INTERLACE_NONE) png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const std::size_t rowBytes = png_get_rowbytes(png, info);
  read->pixels.resize(rowBytes * read->height);
  read->rows.resize(read->height);
  for (png_uint_32 r = 0; r < read->height; ++r) read->rows[r] = read->pixels.data() + r * rowBytes;
  png_read_image(png, read->rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// --- NumPy .npy (the format of numpy.lib.format: a magic string, a
// version, a header that is a Python dict literal, then the raw array) ---

struct NpyHeader {
  char byteOrder = '<';  // '<' little, '>' big, '|' not applicable
  char kind = 'f';       // 'f' float, 'i' signed, 'u' unsigned
  int itemSize = 8;
  bool fortranOrder = false;
  std::vector<long> shape;
};

// The value after 'key': in the dict literal, or npos.
std::size_t valueAfterKey(const std::string& header, const std::string& key) {
  for (const char quote : {'\'', '"'}) {
    const std::string quoted = std::string(1, quote) + key + quote;
    std::size_t at = header.find(quoted);
    if (at == std::string::npos) continue;
    at = header.find(':', at + quoted.size());
    if (at == std::string::npos) return std::string::npos;
    ++at;
    while (at < header.size() && std::isspace(static_cast<unsigned char>(header[at]))) ++at;
    return at;
  }
  return std::string::npos;
}

std::string parseNpyHeader(const std::string& header, NpyHeader& out) {
  std::size_t at = valueAfterKey(header, "descr");
  if (at == std::string::npos || at >= header.size() || (header[at] != '\'' && header[at] != '"'))
    return "its header has no 'descr' string";
  const char quote = header[at];
  const std::size_t end = header.find(quote, at + 1);
  if (end == std::string::npos) return "its header's 'descr' is not closed";
  const std::string descr = header.substr(at + 1, end - at - 1);
  const bool sized = descr.size() >= 3 && std::string("<>|=").find(descr[0]) != std::string::npos &&
                     std::string("fiu").find(descr[1]) != std::string::npos &&
                     std::all_of(descr.begin() + 2, descr.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!sized || descr.size() > 4)
    return "has dtype '" + descr + "'; heights must be float32, float64 or integers of 1, 2 or 4 bytes";
  out.byteOrder = descr[0] == '=' ? '<' : descr[0];  // '=': native, little-endian on every machine rbsim builds for
  out.kind = descr[1];
  out.itemSize = std::stoi(descr.substr(2));
  const bool known = out.kind == 'f' ? (out.itemSize == 4 || out.itemSize == 8)
                                     : (out.itemSize == 1 || out.itemSize == 2 || out.itemSize == 4);
  if (!known) return "has dtype '" + descr + "'; heights must be float32, float64 or integers of 1, 2 or 4 bytes";

  at = valueAfterKey(header, "fortran_order");
  if (at == std::string::npos) return "its header has no 'fortran_order'";
  if (header.compare(at, 4, "True") == 0) out.fortranOrder = true;
  else if (header.compare(at, 5, "False") == 0) out.fortranOrder = false;
  else return "its header's 'fortran_order' is neither True nor False";

  at = valueAfterKey(header, "shape");
  if (at == std::string::npos || at >= header.size() || header[at] != '(') return "its header has no 'shape' tuple";
  const std::size_t close = header.find(')', at);
  if (close == std::string::npos) return "its header's 'shape' is not closed";
  std::stringstream dims(header.substr(at + 1, close - at - 1));
  std::string dim;
  while (std::getline(dims, dim, ',')) {
    dim.erase(std::remove_if(dim.begin(), dim.end(), [](unsigned char c) { return std::isspace(c) || c == 'L'; }),
              dim.end());
    if (dim.empty()) continue;  // the trailing comma of a 1-tuple
    if (dim.size() > 12 || !std::all_of(dim.begin(), dim.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return "its header's 'shape' holds '" + dim + "', not a size";
    out.shape.push_back(std::stol(dim));
  }
  if (out.shape.size() != 2)
    return "is an array of " + std::to_string(out.shape.size()) + " dimensions; a height grid has 2 (rows, columns)";
  return "";
}

double npyValue(const unsigned char* p, const NpyHeader& h) {
  unsigned char b[8];
  for (int k = 0; k < h.itemSize; ++k) b[k] = h.byteOrder == '>' ? p[h.itemSize - 1 - k] : p[k];
  switch (h.kind) {
    case 'f': {
      if (h.itemSize == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    case 'i': {
      if (h.itemSize == 1) return static_cast<int8_t>(b[0]);
      if (h.itemSize == 2) {
        int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      int32_t v;
      std::memcpy(&v, b, 4);
      return v;
    }
    default: {
      if (h.itemSize == 1) return b[0];
      if (h.itemSize == 2) {
        uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      uint32_t v;
      std::memcpy(&v, b, 4);
      return v;
    }
  }
}

}  // namespace

Expected<HeightGrid> loadHeightGrid(const std::string& path) {
  const std::string extension = lowercaseExtension(path);
  if (extension == ".png") return loadHeightPng(path);
  if (extension == ".npy") return loadHeightNpy(path);
  return fileError(path, "is not a height grid file this server reads (by its extension: .png or .npy)");
}

Expected<HeightGrid> loadHeightPng(const std::string& path) {
  Expected<std::vector<unsigned char>> bytes = readWholeFile(path);
  if (!bytes) return bytes.error();
  if (bytes->size() < 8 || png_sig_cmp(bytes->data(), 0, 8) != 0) return fileError(path, "is not a PNG file");
  PngRead read;
  read.bytes = &*bytes;
  if (!readPng(&read)) return fileError(path, read.failure);
  HeightGrid grid;
  grid.rows = static_cast<int>(read.height);
  grid.columns = static_cast<int>(read.width);
  grid.values.resize(static_cast<std::size_t>(grid.rows) * static_cast<std::size_t>(grid.columns));
  const double fullScale = read.bitDepth == 16 ? 65535.0 : 255.0;
  for (int r = 0; r < grid.rows; ++r) {
    // The image's top row is the terrain's +y edge.
    const unsigned char* row = read.rows[static_cast<std::size_t>(grid.rows - 1 - r)];
    for (int c = 0; c < grid.columns; ++c) {
      const double sample = read.bitDepth == 16 ? 256.0 * row[2 * c] + row[2 * c + 1] : row[c];  // big-endian
      grid.values[static_cast<std::size_t>(r * grid.columns + c)] = sample / fullScale;
    }
  }
  return grid;
}

Expected<HeightGrid> loadHeightNpy(const std::string& path) {
  Expected<std::vector<unsigned char>> read = readWholeFile(path);
  if (!read) return read.error();
  const std::vector<unsigned char>& bytes = *read;
  static const unsigned char kMagic[6] = {0x93, 'N', 'U', 'M', 'P', 'Y'};
  if (bytes.size() < 10 || std::memcmp(bytes.data(), kMagic, 6) != 0) return fileError(path, "is not a NumPy .npy file");
  const int major = bytes[6];
  std::size_t headerLength = 0, headerStart = 0;
  if (major == 1) {
    headerLength = bytes[8] | (static_cast<std::size_t>(bytes[9]) << 8);
    headerStart = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) return fileError(path, "ends inside its header");
    headerLength = bytes[8] | (static_cast<std::size_t>(bytes[9]) << 8) | (static_cast<std::size_t>(bytes[10]) << 16) |
                   (static_cast<std::size_t>(bytes[11]) << 24);
    headerStart = 12;
  } else {
    return fileError(path, "is .npy format version " + std::to_string(major) + "; versions 1 to 3 are read");
  }
  if (headerLength > bytes.size() - headerStart) return fileError(path, "ends inside its header");
  const std::string header(bytes.begin() + static_cast<std::ptrdiff_t>(headerStart),
                           bytes.begin() + static_cast<std::ptrdiff_t>(headerStart + headerLength));
  NpyHeader h;
  if (const std::string problem = parseNpyHeader(header, h); !problem.empty()) return fileError(path, problem);
  if (const std::string problem = gridSizeProblem(h.shape[0], h.shape[1]); !problem.empty())
    return fileError(path, problem);
  const std::size_t rows = static_cast<std::size_t>(h.shape[0]);
  const std::size_t columns = static_cast<std::size_t>(h.shape[1]);
  const std::size_t dataStart = headerStart + headerLength;
  const std::size_t expected = rows * columns * static_cast<std::size_t>(h.itemSize);
  if (bytes.size() - dataStart != expected)
    return fileError(path, "holds " + std::to_string(bytes.size() - dataStart) + " bytes of data where its header's " +
                               std::to_string(rows) + " × " + std::to_string(columns) + " array needs " +
                               std::to_string(expected));
  HeightGrid grid;
  grid.rows = static_cast<int>(rows);
  grid.columns = static_cast<int>(columns);
  grid.values.resize(rows * columns);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns; ++c) {
      const std::size_t element = h.fortranOrder ? c * rows + r : r * columns + c;
      const double value = npyValue(bytes.data() + dataStart + element * static_cast<std::size_t>(h.itemSize), h);
      if (!std::isfinite(value))
        return fileError(path, "has a value that is not finite at row " + std::to_string(r) + ", column " +
                                   std::to_string(c) + " (counting from 0)");
      grid.values[r * columns + c] = value;
    }
  }
  return grid;
}

TriangleMesh heightGridMesh(const HeightGrid& grid, double cellX, double cellY, double heightScale,
                            double heightOffset) {
  TriangleMesh mesh;
  mesh.vertices.reserve(grid.values.size());
  const double middleColumn = 0.5 * (grid.columns - 1);
  const double middleRow = 0.5 * (grid.rows - 1);
  for (int r = 0; r < grid.rows; ++r)
    for (int c = 0; c < grid.columns; ++c)
      mesh.vertices.emplace_back((c - middleColumn) * cellX, (r - middleRow) * cellY,
                                 heightScale * grid.at(r, c) + heightOffset);
  mesh.triangles.reserve(2 * static_cast<std::size_t>(grid.rows - 1) * static_cast<std::size_t>(grid.columns - 1));
  for (int r = 0; r + 1 < grid.rows; ++r) {
    for (int c = 0; c + 1 < grid.columns; ++c) {
      const int corner = r * grid.columns + c;  // (r, c)
      const int right = corner + 1;             // (r, c + 1)
      const int above = corner + grid.columns;  // (r + 1, c)
      const int diagonal = above + 1;           // (r + 1, c + 1)
      mesh.triangles.push_back({corner, right, diagonal});
      mesh.triangles.push_back({corner, diagonal, above});
    }
  }
  return mesh;
}

}  // namespace rbsim
