#include "persist/checkpoint_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "rbsim/physics/byte_stream.h"

namespace rbsim {

namespace {

constexpr char kMagic[8] = {'R', 'B', 'S', 'I', 'M', 'C', 'K', 'P'};
constexpr std::size_t kHeaderBytes = 8 + 4 + 8 + 4;

std::string systemError(const std::string& what, const std::string& path) {
  return what + " '" + path + "': " + std::strerror(errno);
}

// Closes the descriptor on every path out.
struct FileDescriptor {
  int fd = -1;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::vector<uint8_t> checkpointFileBytes(std::span<const uint8_t> payload) {
  ByteWriter out;
  out.bytes(std::span(reinterpret_cast<const uint8_t*>(kMagic), sizeof kMagic));
  out.u32(kCheckpointFormatVersion);
  out.u64(payload.size());
  out.u32(crc32(payload));
  out.bytes(payload);
  return out.take();
}

Expected<std::vector<uint8_t>> checkpointPayload(std::span<const uint8_t> file, const std::string& source) {
  const std::string where = "checkpoint '" + source + "': ";
  if (file.size() < kHeaderBytes || std::memcmp(file.data(), kMagic, sizeof kMagic) != 0)
    return Error{where + (file.size() < sizeof kMagic ? "too short (" + std::to_string(file.size()) + " bytes)"
                                                      : std::string("not an rbsim checkpoint (bad magic)"))};
  ByteReader header(file.subspan(sizeof kMagic, kHeaderBytes - sizeof kMagic));
  const uint32_t version = header.u32("version");
  const uint64_t length = header.u64("payload length");
  const uint32_t checksum = header.u32("checksum");
  if (version != kCheckpointFormatVersion)
    return Error{where + "format version " + std::to_string(version) + " is not supported (this build reads " +
                 std::to_string(kCheckpointFormatVersion) + ")"};
  const uint64_t present = file.size() - kHeaderBytes;
  if (length != present)
    return Error{where + (length > present ? "truncated: " : "trailing bytes: ") + "the header announces " +
                 std::to_string(length) + " bytes of payload, the file has " + std::to_string(present)};
  const auto payload = file.subspan(kHeaderBytes);
  if (crc32(payload) != checksum) return Error{where + "corrupt: the checksum does not match the contents"};
  return std::vector<uint8_t>(payload.begin(), payload.end());
}

Expected<bool> writeFileAtomically(const std::string& path, std::span<const uint8_t> bytes) {
  const std::filesystem::path target(path);
  const std::filesystem::path directory = target.has_parent_path() ? target.parent_path() : ".";
  // Unique per write: the periodic writer thread and a SAVE_CHECKPOINT may
  // write the same name at once. Client names cannot start with '.'.
  static std::atomic<uint64_t> writes{0};
  const std::string temporary =
      (directory / ("." + target.filename().string() + "." + std::to_string(::getpid()) + "." +
                    std::to_string(writes++) + ".tmp"))
          .string();
  {
    FileDescriptor file{::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644)};
    if (file.fd < 0) return Error{systemError("cannot create", temporary)};
    std::size_t written = 0;
    while (written < bytes.size()) {
      const ssize_t n = ::write(file.fd, bytes.data() + written, bytes.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const Error error{systemError("cannot write", temporary)};
        ::unlink(temporary.c_str());
        return error;
      }
      written += static_cast<std::size_t>(n);
    }
    if (::fsync(file.fd) != 0) {
      const Error error{systemError("cannot fsync", temporary)};
      ::unlink(temporary.c_str());
      return error;
    }
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const Error error{systemError("cannot rename " + temporary + " to", path)};
    ::unlink(temporary.c_str());
    return error;
  }
  // The rename is durable only once the directory entry is.
  FileDescriptor dir{::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)};
  if (dir.fd < 0 || ::fsync(dir.fd) != 0) return Error{systemError("cannot fsync directory", directory.string())};
  return true;
}

Expected<std::vector<uint8_t>> readWholeFile(const std::string& path, bool noFollow) {
  FileDescriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | (noFollow ? O_NOFOLLOW : 0))};
  if (file.fd < 0) return Error{systemError("cannot open", path)};
  struct stat info {};
  if (::fstat(file.fd, &info) != 0) return Error{systemError("cannot stat", path)};
  if (!S_ISREG(info.st_mode)) return Error{"'" + path + "' is not a regular file"};
  if (static_cast<uint64_t>(info.st_size) > kMaxCheckpointBytes)
    return Error{"'" + path + "' is " + std::to_string(info.st_size) + " bytes, more than a checkpoint may be"};
  std::vector<uint8_t> bytes(static_cast<std::size_t>(info.st_size));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(file.fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return Error{systemError("cannot read", path)};
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  bytes.resize(done);
  return bytes;
}

Expected<std::string> checkpointPathIn(const std::string& directory, const std::string& name) {
  const auto bad = [&](const std::string& why) {
    return Error{"checkpoint name '" + name + "' " + why +
                 ": give a plain file name (letters, digits, '.', '_', '-'), it goes to the server's "
                 "checkpoint directory"};
  };
  if (directory.empty())
    return Error{"checkpoints are disabled on this server (set server.checkpoint_dir or --checkpoint-dir)"};
  if (name.empty() || name.size() > 128) return bad("must have 1 to 128 characters");
  if (name.front() == '.') return bad("must not start with '.'");
  for (const char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-'))
      return bad("has a character other than letters, digits, '.', '_' and '-'");
  return (std::filesystem::path(directory) / name).string();
}

}  // namespace rbsim
