#pragma once
// What every mesh reader shares: opening the file (with the checks and
// messages common to all formats) and the wording of file-level errors.
// Internal to meshio.

#include <cstdint>
#include <fstream>
#include <string>

#include "rbsim/physics/types.h"

namespace rbsim::meshio {

// "path: text"
Error fileError(const std::string& path, const std::string& text);

// The message for a mesh over kMaxMeshTriangles.
std::string triangleLimitText();

struct OpenFile {
  std::ifstream stream;
  std::uintmax_t size = 0;  // bytes
};

// Opens `path` for binary reading; an error if it does not exist, is a
// directory, cannot be opened or is empty.
Expected<OpenFile> openMeshFile(const std::string& path);

}  // namespace rbsim::meshio
