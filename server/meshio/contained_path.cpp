#include "meshio/contained_path.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace rbsim {

namespace {

namespace fs = std::filesystem;

// Whether `path` is `directory` or lies below it (both canonical).
bool isWithin(const fs::path& path, const fs::path& directory) {
  const auto [stop, unused] =
      std::mismatch(directory.begin(), directory.end(), path.begin(), path.end());
  return stop == directory.end();
}

}  // namespace

Expected<std::string> resolveContainedFile(const std::string& file, const std::string& directory) {
  const std::string quoted = "file '" + file + "'";
  if (file.empty()) return Error{"a file path is needed"};
  if (file.find('\0') != std::string::npos) return Error{quoted + ": contains a NUL character"};
  const fs::path relative(file);
  if (relative.is_absolute() || relative.has_root_name() || relative.has_root_directory())
    return Error{quoted + ": absolute paths are not allowed in a spawn; name a file "
                 "relative to the spawn mesh directory"};
  for (const fs::path& part : relative) {
    if (part == "..")
      return Error{quoted + ": '..' is not allowed in the paths of a spawn"};
  }

  std::error_code error;
  const fs::path root = fs::canonical(directory.empty() ? fs::path(".") : fs::path(directory), error);
  if (error) return Error{quoted + ": the spawn mesh directory cannot be resolved (" +
                          error.message() + ")"};
  const fs::path resolved = fs::canonical(root / relative, error);
  if (error) return Error{quoted + ": no such file in the spawn mesh directory (" + error.message() + ")"};
  // The host's own paths stay out of the message: it goes back to the sender.
  if (!isWithin(resolved, root))
    return Error{quoted + ": resolves (through a symbolic link) to a file outside the spawn "
                 "mesh directory"};
  if (!fs::is_regular_file(resolved, error))
    return Error{quoted + ": not a regular file"};
  return resolved.string();
}

}  // namespace rbsim
