#include "rbsim/physics/byte_stream.h"

#include <array>
#include <bit>
#include <cstring>

namespace rbsim {

void ByteWriter::u32(uint32_t value) {
  for (int i = 0; i < 4; ++i) m_bytes.push_back(static_cast<uint8_t>(value >> (8 * i)));
}

void ByteWriter::u64(uint64_t value) {
  for (int i = 0; i < 8; ++i) m_bytes.push_back(static_cast<uint8_t>(value >> (8 * i)));
}

void ByteWriter::f64(double value) { u64(std::bit_cast<uint64_t>(value)); }

void ByteWriter::vec3(const Vec3& v) {
  for (int i = 0; i < 3; ++i) f64(v[i]);
}

void ByteWriter::mat3(const Mat3& m) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) f64(m(r, c));
}

void ByteWriter::quaternion(const Quaternion& q) {
  f64(q.w);
  f64(q.x);
  f64(q.y);
  f64(q.z);
}

void ByteWriter::string(const std::string& text) {
  u32(static_cast<uint32_t>(text.size()));
  m_bytes.insert(m_bytes.end(), text.begin(), text.end());
}

void ByteWriter::bytes(std::span<const uint8_t> data) {
  m_bytes.insert(m_bytes.end(), data.begin(), data.end());
}

void ByteReader::fail(const std::string& message) {
  if (m_error.empty()) m_error = message;
}

bool ByteReader::need(std::size_t size, const char* what) {
  if (failed()) return false;
  if (remaining() >= size) return true;
  fail("truncated: " + std::string(what) + " needs " + std::to_string(size) + " bytes at byte " +
       std::to_string(m_offset) + ", " + std::to_string(remaining()) + " left");
  return false;
}

uint8_t ByteReader::u8(const char* what) {
  if (!need(1, what)) return 0;
  return m_bytes[m_offset++];
}

uint32_t ByteReader::u32(const char* what) {
  if (!need(4, what)) return 0;
  uint32_t value = 0;
  for (int i = 0; i < 4; ++i) value |= uint32_t{m_bytes[m_offset++]} << (8 * i);
  return value;
}

uint64_t ByteReader::u64(const char* what) {
  if (!need(8, what)) return 0;
  uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value |= uint64_t{m_bytes[m_offset++]} << (8 * i);
  return value;
}

bool ByteReader::boolean(const char* what) {
  const std::size_t at = m_offset;
  const uint8_t value = u8(what);
  if (value > 1) fail(std::string(what) + " at byte " + std::to_string(at) + " is " +
                      std::to_string(value) + ", not a boolean (0 or 1)");
  return value == 1;
}

double ByteReader::f64(const char* what) { return std::bit_cast<double>(u64(what)); }

Vec3 ByteReader::vec3(const char* what) {
  Vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = f64(what);
  return v;
}

Mat3 ByteReader::mat3(const char* what) {
  Mat3 m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = f64(what);
  return m;
}

Quaternion ByteReader::quaternion(const char* what) {
  Quaternion q;
  q.w = f64(what);
  q.x = f64(what);
  q.y = f64(what);
  q.z = f64(what);
  return q;
}

std::string ByteReader::string(const char* what, uint32_t maxLength) {
  const std::size_t at = m_offset;
  const uint32_t length = u32(what);
  if (failed()) return {};
  if (length > maxLength) {
    fail(std::string(what) + " at byte " + std::to_string(at) + ": length " +
         std::to_string(length) + " exceeds " + std::to_string(maxLength));
    return {};
  }
  if (!need(length, what)) return {};
  std::string text(reinterpret_cast<const char*>(m_bytes.data() + m_offset), length);
  m_offset += length;
  return text;
}

uint32_t ByteReader::count(const char* what, std::size_t minBytesEach) {
  const std::size_t at = m_offset;
  const uint32_t n = u32(what);
  if (failed()) return 0;
  if (minBytesEach > 0 && n > remaining() / minBytesEach) {
    fail(std::string(what) + " at byte " + std::to_string(at) + " is " + std::to_string(n) +
         ", more than the " + std::to_string(remaining()) + " remaining bytes can hold");
    return 0;
  }
  return n;
}

std::span<const uint8_t> ByteReader::bytes(const char* what, std::size_t size) {
  if (!need(size, what)) return {};
  const auto out = m_bytes.subspan(m_offset, size);
  m_offset += size;
  return out;
}

uint32_t crc32(std::span<const uint8_t> data) {
  // Table of the reflected polynomial 0xEDB88320, built once.
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  uint32_t crc = 0xFFFFFFFFu;
  for (const uint8_t byte : data) crc = table[(crc ^ byte) & 0xFFu] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

}  // namespace rbsim
