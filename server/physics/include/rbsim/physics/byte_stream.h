#pragma once
// Little-endian binary encoding for snapshots and checkpoints: fixed-width
// integers, doubles as their exact bit patterns, length-prefixed strings,
// and the math types (vectors, matrices, quaternions), which is why it lives
// in math/.
//
// The reader is for untrusted bytes. It never reads past the end, and every
// count is checked against the bytes that remain before anything is
// allocated. The first failure sticks: later reads return zeros, and
// error() says what was being read and at which byte offset, so a caller
// may read a whole record and check once.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rbsim/physics/expected.h"
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

class ByteWriter {
 public:
  void u8(uint8_t value) { m_bytes.push_back(value); }
  void u32(uint32_t value);
  void u64(uint64_t value);
  void i32(int32_t value) { u32(static_cast<uint32_t>(value)); }
  void i64(int64_t value) { u64(static_cast<uint64_t>(value)); }
  void boolean(bool value) { u8(value ? 1 : 0); }
  void f64(double value);  // the bit pattern, so the value comes back exactly
  void vec3(const Vec3& v);
  void mat3(const Mat3& m);  // row by row
  void quaternion(const Quaternion& q);  // w, x, y, z
  void string(const std::string& text);  // u32 length, then the bytes
  void bytes(std::span<const uint8_t> data);  // raw, no length

  const std::vector<uint8_t>& data() const { return m_bytes; }
  std::vector<uint8_t> take() { return std::move(m_bytes); }

 private:
  std::vector<uint8_t> m_bytes;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const uint8_t> bytes) : m_bytes(bytes) {}

  uint8_t u8(const char* what);
  uint32_t u32(const char* what);
  uint64_t u64(const char* what);
  int32_t i32(const char* what) { return static_cast<int32_t>(u32(what)); }
  int64_t i64(const char* what) { return static_cast<int64_t>(u64(what)); }
  bool boolean(const char* what);  // 0 or 1, anything else is an error
  double f64(const char* what);
  Vec3 vec3(const char* what);
  Mat3 mat3(const char* what);
  Quaternion quaternion(const char* what);
  std::string string(const char* what, uint32_t maxLength);
  // A count of items that take at least `minBytesEach` bytes each: more
  // than the remaining bytes can hold is an error (no huge allocations).
  uint32_t count(const char* what, std::size_t minBytesEach);
  std::span<const uint8_t> bytes(const char* what, std::size_t size);

  // Marks the data as bad with a message (for checks of the values read).
  void fail(const std::string& message);
  bool failed() const { return !m_error.empty(); }
  const std::string& error() const { return m_error; }
  std::size_t offset() const { return m_offset; }
  std::size_t remaining() const { return m_bytes.size() - m_offset; }

 private:
  bool need(std::size_t size, const char* what);

  std::span<const uint8_t> m_bytes;
  std::size_t m_offset = 0;
  std::string m_error;
};

// CRC-32 (IEEE 802.3, the zlib/PNG polynomial) of `data`: detects torn or
// corrupted files.
uint32_t crc32(std::span<const uint8_t> data);

}  // namespace rbsim
