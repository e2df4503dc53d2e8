#pragma once
// Checkpoint files on disk: the container around a session checkpoint, the
// atomic write, and where clients may put them.
//
// Container (little-endian): the 8 bytes "RBSIMCKP", format version (u32),
// payload length (u64), CRC-32 of the payload (u32), then the payload. A
// file that is short, long, of another version or whose checksum does not
// match is refused with a message saying which.
//
// Writing is atomic: the bytes go to a temporary file in the same
// directory, which is fsync'ed, renamed over the target, and the directory
// fsync'ed; a crash at any moment leaves either the old file or the new
// one, never a torn one.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rbsim/physics/types.h"

namespace rbsim {

inline constexpr uint32_t kCheckpointFormatVersion = 1;
// The file --checkpoint-every keeps replacing in the checkpoint directory.
inline constexpr const char* kPeriodicCheckpointName = "periodic.rbck";
// Files larger than this are refused unread (a checkpoint of 100000 bodies
// is about 50 MB).
inline constexpr uint64_t kMaxCheckpointBytes = uint64_t{1} << 32;

// The whole file for `payload`.
std::vector<uint8_t> checkpointFileBytes(std::span<const uint8_t> payload);
// The payload of a checkpoint file's bytes; `source` names it in errors.
Expected<std::vector<uint8_t>> checkpointPayload(std::span<const uint8_t> file, const std::string& source);

Expected<bool> writeFileAtomically(const std::string& path, std::span<const uint8_t> bytes);
// Reads a whole file (not following a symbolic link when `noFollow`).
Expected<std::vector<uint8_t>> readWholeFile(const std::string& path, bool noFollow);

// Where a client's SAVE_CHECKPOINT or RESET `path` points: always inside
// `directory`. The name must be a plain file name (letters, digits, '.',
// '_', '-'; not starting with '.'; at most 128 characters): no directories,
// no "..", no absolute paths, so a client can never reach a file outside
// the checkpoint directory.
Expected<std::string> checkpointPathIn(const std::string& directory, const std::string& name);

}  // namespace rbsim
