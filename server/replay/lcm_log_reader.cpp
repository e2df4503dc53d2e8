#include "replay/lcm_log_reader.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace rbsim {

namespace {

// Every event starts with this word; all integers in the log are big-endian.
constexpr uint32_t kSyncWord = 0xEDA1DA01u;
constexpr int64_t kHeaderBytes = 4 + 8 + 8 + 4 + 4;

uint64_t bigEndian(const unsigned char* bytes, int count) {
  uint64_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
  return value;
}

}  // namespace

Expected<bool> LcmLogReader::open(const std::string& path) {
  m_path = path;
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error) return Error{"cannot read log '" + path + "': " + error.message()};
  m_file.open(path, std::ios::binary);
  if (!m_file) return Error{"cannot open log '" + path + "': " + std::strerror(errno)};
  m_fileSize = static_cast<int64_t>(size);
  m_offset = 0;
  m_eventsRead = 0;
  return true;
}

Expected<std::optional<LogEvent>> LcmLogReader::next() {
  if (m_offset == m_fileSize) return std::optional<LogEvent>{};
  const std::string where = "log '" + m_path + "', event " + std::to_string(m_eventsRead) +
                            " at byte " + std::to_string(m_offset) + ": ";
  if (m_fileSize - m_offset < kHeaderBytes)
    return Error{where + "truncated event header (" + std::to_string(m_fileSize - m_offset) +
                 " bytes left, a header has " + std::to_string(kHeaderBytes) + ")"};
  unsigned char header[kHeaderBytes];
  if (!m_file.read(reinterpret_cast<char*>(header), kHeaderBytes)) return Error{where + "read error"};
  if (bigEndian(header, 4) != kSyncWord)
    return Error{where + "no LCM event sync word (not an LCM log, or corrupt)"};
  LogEvent event;
  event.eventNumber = static_cast<int64_t>(bigEndian(header + 4, 8));
  event.timestamp = static_cast<int64_t>(bigEndian(header + 12, 8));
  const auto channelLength = static_cast<int32_t>(bigEndian(header + 20, 4));
  const auto dataLength = static_cast<int32_t>(bigEndian(header + 24, 4));
  if (channelLength <= 0 || channelLength > kMaxChannelLength)
    return Error{where + "channel length " + std::to_string(channelLength) + " is out of range"};
  if (dataLength < 0 || dataLength > kMaxDataLength)
    return Error{where + "data length " + std::to_string(dataLength) + " is out of range"};
  const int64_t bodyBytes = int64_t{channelLength} + dataLength;
  if (m_fileSize - m_offset - kHeaderBytes < bodyBytes)
    return Error{where + "truncated event (" + std::to_string(bodyBytes) + " bytes announced, " +
                 std::to_string(m_fileSize - m_offset - kHeaderBytes) + " left)"};
  event.channel.resize(static_cast<std::size_t>(channelLength));
  event.data.resize(static_cast<std::size_t>(dataLength));
  if (!m_file.read(event.channel.data(), channelLength) ||
      !m_file.read(reinterpret_cast<char*>(event.data.data()), dataLength))
    return Error{where + "read error"};
  m_offset += kHeaderBytes + bodyBytes;
  ++m_eventsRead;
  return std::optional<LogEvent>{std::move(event)};
}

}  // namespace rbsim
