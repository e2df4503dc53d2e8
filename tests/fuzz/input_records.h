#pragma once
// Splits one fuzz input into a sequence of records, for targets that take a
// sequence of events (messages, steps) rather than one blob. Every byte
// string is a valid sequence: a short read gives what is left, so mutations
// never get stuck on framing.
//
// A record is a tag byte, then for records with a payload a 16-bit
// little-endian length and that many bytes (fewer at the end of the input).

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace rbsim::fuzz {

class InputRecords {
 public:
  InputRecords(const uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}

  bool done() const { return m_offset >= m_size; }
  uint8_t byte() { return done() ? 0 : m_data[m_offset++]; }

  struct Payload {
    const uint8_t* data;
    std::size_t size;
  };
  Payload payload() {
    const std::size_t length = byte() | (static_cast<std::size_t>(byte()) << 8);
    const std::size_t taken = std::min(length, m_size - m_offset);
    const Payload result{m_data + m_offset, taken};
    m_offset += taken;
    return result;
  }

 private:
  const uint8_t* m_data;
  std::size_t m_size;
  std::size_t m_offset = 0;
};

}  // namespace rbsim::fuzz
