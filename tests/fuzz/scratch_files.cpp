#include "scratch_files.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace rbsim::fuzz {
namespace {

std::filesystem::path& scratchDirectory() {
  static std::filesystem::path directory = [] {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm")
                                                           : fs::temp_directory_path();
    std::string pattern = (base / "rbsim-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      std::perror("rbsim fuzz: mkdtemp");
      std::abort();
    }
    // libFuzzer ends with exit(), which runs atexit handlers; a crash leaves
    // the directory behind, with the input that caused it, which is fine.
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(scratchDirectory(), ignored);
    });
    return fs::path(pattern);
  }();
  return directory;
}

}  // namespace

std::string writeScratchFile(const std::string& name, const uint8_t* data, std::size_t size) {
  const std::filesystem::path path = scratchDirectory() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "rbsim fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path.string();
}

}  // namespace rbsim::fuzz
