#include "meshio/mesh_io.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <vector>

#include "meshio/collada_mesh.h"
#include "meshio/mesh_file.h"
#include "meshio/vertex_welder.h"

namespace rbsim {
namespace {

using meshio::fileError;
using meshio::OpenFile;
using meshio::openMeshFile;
using meshio::triangleLimitText;
using meshio::VertexWelder;

// Bounds the memory an OBJ file can make us allocate through vertex lines
// alone. A closed triangle mesh has about half as many vertices as
// triangles, so this leaves ample room for unreferenced vertices.
constexpr long long kMaxObjVertices = 3LL * kMaxMeshTriangles;

constexpr std::uintmax_t kStlHeaderBytes = 84;  // 80-byte comment + uint32 triangle count
constexpr std::uintmax_t kStlRecordBytes = 50;  // normal, 3 vertices (12 float32), uint16

Error lineError(const std::string& path, long long line, const std::string& text) {
  return Error{path + ":" + std::to_string(line) + ": " + text};
}

// A token from the file, quoted in a message: unprintable bytes replaced and
// length capped, so that a binary file cannot garble the message.
std::string quoteToken(std::string_view token) {
  constexpr size_t kMaxShown = 24;
  std::string shown;
  for (size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    shown += std::isprint(c) ? static_cast<char>(c) : '?';
  }
  if (token.size() > kMaxShown) shown += "...";
  return "'" + shown + "'";
}

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

std::vector<std::string_view> splitWhitespace(std::string_view text) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isSpace(text[i])) ++i;
    const size_t begin = i;
    while (i < text.size() && !isSpace(text[i])) ++i;
    if (i > begin) tokens.push_back(text.substr(begin, i - begin));
  }
  return tokens;
}

// Locale-independent (unlike strtod) and strict: the whole token must be a
// number. std::from_chars accepts "inf" and "nan", which the callers reject.
bool parseDouble(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  return result.ec == std::errc() && result.ptr == end;
}

bool parseInteger(std::string_view token, long long& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  return result.ec == std::errc() && result.ptr == end;
}

std::uint32_t readLittleEndian32(const unsigned char* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8) |
         (static_cast<std::uint32_t>(bytes[2]) << 16) |
         (static_cast<std::uint32_t>(bytes[3]) << 24);
}

Expected<TriangleMesh> readBinaryStl(const std::string& path, std::ifstream& stream,
                                     std::uint32_t triangleCount) {
  if (triangleCount == 0) return fileError(path, "binary STL contains no triangles");
  if (triangleCount > static_cast<std::uint32_t>(kMaxMeshTriangles)) {
    return fileError(path, "binary STL declares " + std::to_string(triangleCount) + " triangles, " +
                               triangleLimitText());
  }
  TriangleMesh mesh;
  mesh.triangles.reserve(triangleCount);
  VertexWelder welder(mesh);
  stream.clear();
  stream.seekg(static_cast<std::streamoff>(kStlHeaderBytes));

  constexpr std::uint32_t kChunk = 4096;
  std::vector<unsigned char> buffer(kChunk * kStlRecordBytes);
  for (std::uint32_t first = 0; first < triangleCount; first += kChunk) {
    const std::uint32_t count = std::min(kChunk, triangleCount - first);
    stream.read(reinterpret_cast<char*>(buffer.data()),
                static_cast<std::streamsize>(count * kStlRecordBytes));
    if (stream.gcount() != static_cast<std::streamsize>(count * kStlRecordBytes)) {
      return fileError(path, "truncated binary STL: read failed at triangle " +
                                 std::to_string(first + static_cast<std::uint32_t>(
                                                            stream.gcount() / kStlRecordBytes)));
    }
    for (std::uint32_t r = 0; r < count; ++r) {
      // The stored normal (first 12 bytes) is ignored: exporters often get it
      // wrong, and the vertex order (counter-clockwise seen from outside)
      // already says which way the facet faces.
      const unsigned char* record = buffer.data() + r * kStlRecordBytes;
      std::array<int, 3> triangle{};
      for (int corner = 0; corner < 3; ++corner) {
        Vec3 p;
        for (int axis = 0; axis < 3; ++axis) {
          const unsigned char* bytes = record + 12 + 12 * corner + 4 * axis;
          p[axis] = static_cast<double>(std::bit_cast<float>(readLittleEndian32(bytes)));
        }
        if (!p.allFinite()) {
          return fileError(path, "binary STL triangle " + std::to_string(first + r) +
                                     " has a non-finite vertex coordinate");
        }
        triangle[static_cast<size_t>(corner)] = welder.indexOf(p);
      }
      mesh.triangles.push_back(triangle);
    }
  }
  return mesh;
}

Expected<TriangleMesh> readAsciiStl(const std::string& path, std::ifstream& stream) {
  enum class State { kBeforeSolid, kInSolid, kInFacet, kInLoop, kAfterLoop };
  State state = State::kBeforeSolid;
  TriangleMesh mesh;
  VertexWelder welder(mesh);
  std::array<int, 3> triangle{};
  int cornersRead = 0;

  stream.clear();
  stream.seekg(0);
  std::string line;
  long long lineNumber = 0;
  while (std::getline(stream, line)) {
    ++lineNumber;
    if (line.find('\0') != std::string::npos) {
      return lineError(path, lineNumber, "contains a NUL byte: not a text (ASCII) STL line");
    }
    const std::vector<std::string_view> tokens = splitWhitespace(line);
    if (tokens.empty()) continue;
    const std::string_view keyword = tokens[0];
    auto unexpected = [&](const char* expected) {
      return lineError(path, lineNumber,
                       std::string("expected ") + expected + ", found " + quoteToken(keyword));
    };
    switch (state) {
      case State::kBeforeSolid:
        if (keyword != "solid") return unexpected("'solid'");
        state = State::kInSolid;  // the rest of the line is the solid's name
        break;
      case State::kInSolid:
        if (keyword == "facet") {
          // "facet normal nx ny nz": the normal is ignored, as in binary STL.
          if (mesh.triangles.size() >= static_cast<size_t>(kMaxMeshTriangles)) {
            return lineError(path, lineNumber, triangleLimitText());
          }
          state = State::kInFacet;
        } else if (keyword == "endsolid") {
          // Several solids may follow each other; they form one mesh.
          state = State::kBeforeSolid;
        } else {
          return unexpected("'facet' or 'endsolid'");
        }
        break;
      case State::kInFacet:
        if (keyword != "outer" || tokens.size() < 2 || tokens[1] != "loop") {
          return unexpected("'outer loop'");
        }
        cornersRead = 0;
        state = State::kInLoop;
        break;
      case State::kInLoop:
        if (keyword == "vertex") {
          if (cornersRead == 3) {
            return lineError(path, lineNumber,
                             "facet has more than 3 vertices; STL facets are triangles");
          }
          if (tokens.size() != 4) {
            return lineError(path, lineNumber, "a vertex needs 3 coordinates (vertex x y z)");
          }
          Vec3 p;
          for (int axis = 0; axis < 3; ++axis) {
            const std::string_view token = tokens[static_cast<size_t>(axis + 1)];
            if (!parseDouble(token, p[axis]) || !std::isfinite(p[axis])) {
              return lineError(
                  path, lineNumber,
                  "vertex coordinate " + quoteToken(token) + " is not a finite number");
            }
          }
          triangle[static_cast<size_t>(cornersRead++)] = welder.indexOf(p);
        } else if (keyword == "endloop") {
          if (cornersRead != 3) {
            return lineError(
                path, lineNumber,
                "facet has " + std::to_string(cornersRead) + " vertices; STL facets are triangles");
          }
          mesh.triangles.push_back(triangle);
          state = State::kAfterLoop;
        } else {
          return unexpected("'vertex' or 'endloop'");
        }
        break;
      case State::kAfterLoop:
        if (keyword != "endfacet") return unexpected("'endfacet'");
        state = State::kInSolid;
        break;
    }
  }
  if (stream.bad()) return fileError(path, "read error");
  if (state != State::kBeforeSolid) {
    return lineError(path, lineNumber,
                     "unexpected end of file inside a solid (missing 'endsolid'; truncated?)");
  }
  if (mesh.triangles.empty()) return fileError(path, "ASCII STL contains no facets");
  return mesh;
}

}  // namespace

Expected<TriangleMesh> loadObj(const std::string& path) {
  Expected<OpenFile> file = openMeshFile(path);
  if (!file) return file.error();
  std::ifstream& stream = file->stream;

  TriangleMesh mesh;
  std::vector<int> face;
  std::string line;
  long long lineNumber = 0;
  while (std::getline(stream, line)) {
    ++lineNumber;
    if (line.find('\0') != std::string::npos) {
      return lineError(path, lineNumber, "contains a NUL byte: not a text OBJ file");
    }
    const std::vector<std::string_view> tokens =
        splitWhitespace(std::string_view(line).substr(0, line.find('#')));
    if (tokens.empty()) continue;
    const long long vertexCount = static_cast<long long>(mesh.vertices.size());

    if (tokens[0] == "v") {
      // "v x y z [w]" or "v x y z r g b": only the position matters here.
      if (tokens.size() < 4) {
        return lineError(path, lineNumber, "a vertex needs 3 coordinates (v x y z)");
      }
      if (vertexCount >= kMaxObjVertices) {
        return lineError(path, lineNumber,
                         "more than " + std::to_string(kMaxObjVertices) +
                             " vertices; larger meshes are rejected (mesh files are untrusted "
                             "input)");
      }
      Vec3 p;
      for (int axis = 0; axis < 3; ++axis) {
        const std::string_view token = tokens[static_cast<size_t>(axis + 1)];
        if (!parseDouble(token, p[axis]) || !std::isfinite(p[axis])) {
          return lineError(path, lineNumber,
                           "vertex coordinate " + quoteToken(token) + " is not a finite number");
        }
      }
      mesh.vertices.push_back(p);
    } else if (tokens[0] == "f") {
      if (tokens.size() < 4) {
        return lineError(
            path, lineNumber,
            "a face needs at least 3 vertices, found " + std::to_string(tokens.size() - 1));
      }
      face.clear();
      for (size_t k = 1; k < tokens.size(); ++k) {
        // "v", "v/vt", "v//vn" or "v/vt/vn": the position index comes first.
        const std::string_view reference = tokens[k];
        const std::string_view indexText = reference.substr(0, reference.find('/'));
        long long index = 0;
        if (!parseInteger(indexText, index)) {
          return lineError(path, lineNumber, "malformed face vertex " + quoteToken(reference));
        }
        if (index == 0) {
          return lineError(path, lineNumber, "face index 0 is invalid (OBJ indices start at 1)");
        }
        // Negative indices count back from the last vertex defined so far
        // (-1 is the latest); positive ones may only refer to vertices
        // already defined, as in the OBJ specification.
        const long long resolved = index > 0 ? index - 1 : vertexCount + index;
        if (resolved < 0 || resolved >= vertexCount) {
          return lineError(path, lineNumber,
                           "face index " + std::to_string(index) + " out of range (" +
                               std::to_string(vertexCount) + " vertices)");
        }
        face.push_back(static_cast<int>(resolved));
      }
      // A fan is exact for convex polygons, which is what exporters write;
      // a concave polygon would need ear clipping.
      for (size_t k = 1; k + 1 < face.size(); ++k) {
        if (mesh.triangles.size() >= static_cast<size_t>(kMaxMeshTriangles)) {
          return lineError(path, lineNumber, triangleLimitText());
        }
        mesh.triangles.push_back({face[0], face[k], face[k + 1]});
      }
    }
    // Every other statement (vt, vn, o, g, s, usemtl, mtllib, l, p, ...) does
    // not change the solid and is ignored.
  }
  if (stream.bad()) return fileError(path, "read error");
  if (mesh.triangles.empty()) {
    return fileError(path, "no faces ('f' lines) found: not an OBJ mesh, or an empty one");
  }
  return mesh;
}

Expected<TriangleMesh> loadStl(const std::string& path) {
  Expected<OpenFile> file = openMeshFile(path);
  if (!file) return file.error();
  std::ifstream& stream = file->stream;
  const std::uintmax_t size = file->size;

  std::array<unsigned char, kStlHeaderBytes> header{};
  const std::uintmax_t headerBytes = std::min(size, kStlHeaderBytes);
  stream.read(reinterpret_cast<char*>(header.data()), static_cast<std::streamsize>(headerBytes));
  if (stream.gcount() != static_cast<std::streamsize>(headerBytes)) {
    return fileError(path, "read error");
  }
  size_t firstNonSpace = 0;
  while (firstNonSpace < headerBytes && isSpace(static_cast<char>(header[firstNonSpace]))) {
    ++firstNonSpace;
  }
  const std::string_view headerText(reinterpret_cast<const char*>(header.data()), headerBytes);
  const bool startsWithSolid = headerText.substr(firstNonSpace, 5) == "solid";

  // A binary STL is exactly 84 + 50·n bytes. Many binary exporters start the
  // 80-byte comment with "solid", so that word proves nothing; the size test
  // is conclusive the other way round, since an ASCII file has printable
  // bytes where the count is (n >= 0x20202020) and would need to be > 27 GB.
  std::uint32_t declared = 0;
  std::uintmax_t declaredSize = 0;
  if (size >= kStlHeaderBytes) {
    declared = readLittleEndian32(header.data() + 80);
    declaredSize = kStlHeaderBytes + kStlRecordBytes * static_cast<std::uintmax_t>(declared);
    if (size == declaredSize) return readBinaryStl(path, stream, declared);
  }
  const std::string counts = "the header declares " + std::to_string(declared) +
                             " triangles, which need " + std::to_string(declaredSize) +
                             " bytes, but the file has " + std::to_string(size) + " bytes";
  const bool plausibleTruncatedBinary = size >= kStlHeaderBytes && declaredSize > size &&
                                        declared <= static_cast<std::uint32_t>(kMaxMeshTriangles);
  const std::string binaryDiagnosis =
      size < kStlHeaderBytes ? "it is too short for a binary STL (" + std::to_string(size) +
                                   " bytes; the header alone is 84)"
      : plausibleTruncatedBinary ? "as a binary STL it is truncated: " + counts
                                 : "it is not a binary STL either: " + counts;

  if (startsWithSolid) {
    Expected<TriangleMesh> ascii = readAsciiStl(path, stream);
    if (ascii) return ascii;
    return Error{ascii.error().message +
                 " (the file starts with 'solid' but is not valid ASCII STL; " + binaryDiagnosis +
                 ")"};
  }
  if (plausibleTruncatedBinary) return fileError(path, "truncated binary STL: " + counts);
  return fileError(
      path, "not an STL file: it does not start with 'solid' (ASCII STL), and " + binaryDiagnosis);
}

Expected<TriangleMesh> loadMesh(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".obj") return loadObj(path);
  if (extension == ".stl") return loadStl(path);
  if (extension == ".dae") return loadCollada(path);
  if (extension.empty()) return fileError(path, "has no extension (expected .obj, .stl or .dae)");
  return fileError(path, "unsupported mesh format " + quoteToken(extension) +
                             " (expected .obj, .stl or .dae)");
}

}  // namespace rbsim
