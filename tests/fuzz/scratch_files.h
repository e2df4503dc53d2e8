#pragma once
// Files for the fuzz targets whose entry point reads a path (the mesh
// loaders, the server settings): the input is written to a private
// directory, under /dev/shm when there is one so that no disk is touched,
// and the directory is removed when the process exits.

#include <cstddef>
#include <cstdint>
#include <string>

namespace rbsim::fuzz {

// Writes `size` bytes to `name` in the scratch directory (replacing what was
// there) and returns the full path. Aborts if the file cannot be written:
// that is a broken machine, not a finding.
std::string writeScratchFile(const std::string& name, const uint8_t* data, std::size_t size);

}  // namespace rbsim::fuzz
