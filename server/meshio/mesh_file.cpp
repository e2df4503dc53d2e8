#include "meshio/mesh_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "meshio/mesh_io.h"

namespace rbsim::meshio {

Error fileError(const std::string& path, const std::string& text) {
  return Error{path + ": " + text};
}

std::string triangleLimitText() {
  return "more than " + std::to_string(kMaxMeshTriangles) +
         " triangles; larger meshes are rejected (mesh files are untrusted input)";
}

Expected<OpenFile> openMeshFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) return fileError(path, "no such file");
  if (fs::is_directory(status)) return fileError(path, "is a directory, not a mesh file");
  OpenFile file;
  file.stream.open(path, std::ios::binary);
  if (!file.stream) {
    return fileError(path,
                     std::string("cannot be opened for reading (") + std::strerror(errno) + ")");
  }
  file.size = fs::file_size(path, ec);
  if (ec) return fileError(path, "cannot determine the file size (" + ec.message() + ")");
  if (file.size == 0) return fileError(path, "file is empty");
  return file;
}

}  // namespace rbsim::meshio
