// Decoding untrusted LCM bytes: a malformed message is refused, never a crash.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include <rbsim/command_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <rbsim/wrench_t.hpp>

#include "bridge/message_decode.h"

namespace rbsim {
namespace {

template <class Message>
std::vector<uint8_t> encoded(const Message& message) {
  std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// The byte offset of wrench_t.body's length prefix: hash (8), utime (8),
// client length (4) and characters with NUL, seq (8).
size_t bodyLengthOffset(const rbsim::wrench_t& message) {
  return 8 + 8 + 4 + message.client.size() + 1 + 8;
}

void putBigEndian32(std::vector<uint8_t>& bytes, size_t offset, int32_t value) {
  const auto u = static_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) bytes[offset + static_cast<size_t>(i)] = static_cast<uint8_t>(u >> (24 - 8 * i));
}

rbsim::wrench_t aWrench() {
  rbsim::wrench_t w{};
  w.client = "fuzz";
  w.body = "crate";
  w.apply_at_step = -1;
  return w;
}

TEST(MessageDecode, DecodesAWholeMessage) {
  const auto bytes = encoded(aWrench());
  rbsim::wrench_t decoded;
  ASSERT_TRUE(decodeWholeMessage(decoded, bytes.data(), bytes.size()));
  EXPECT_EQ(decoded.body, "crate");
}

TEST(MessageDecode, RefusesTruncatedAndOverlongBytes) {
  auto bytes = encoded(aWrench());
  rbsim::wrench_t decoded;
  EXPECT_FALSE(decodeWholeMessage(decoded, bytes.data(), bytes.size() - 1));
  bytes.push_back(0);
  EXPECT_FALSE(decodeWholeMessage(decoded, bytes.data(), bytes.size()));
}

// Found by tests/fuzz/fuzz_wrench_message (regressions/wrench_message/
// zero_length_string, negative_string_length): lcm-gen's decoder threw
// std::length_error for a string length prefix of 0, which would have ended
// rbserver, and read far past the buffer for INT32_MIN.
TEST(MessageDecode, RefusesStringLengthsOfZeroOrLess) {
  const rbsim::wrench_t message = aWrench();
  for (const int32_t length : {0, -1, -1000, INT32_MIN}) {
    auto bytes = encoded(message);
    putBigEndian32(bytes, bodyLengthOffset(message), length);
    rbsim::wrench_t decoded;
    EXPECT_FALSE(decodeWholeMessage(decoded, bytes.data(), bytes.size())) << length;
  }
  rbsim::command_t command{};
  command.client = "";  // the first string: its length prefix is at byte 16
  auto bytes = encoded(command);
  putBigEndian32(bytes, 16, 0);
  rbsim::command_t decoded;
  EXPECT_FALSE(decodeWholeMessage(decoded, bytes.data(), bytes.size()));
}

// Found by tests/fuzz/fuzz_command_handler (regressions/command_handler/
// embedded_nul_in_client): a string with a NUL inside was kept whole, and
// the ack echoing it encoded to fewer bytes than its announced size.
TEST(MessageDecode, RefusesStringsThatAreNotCStrings) {
  const rbsim::wrench_t message = aWrench();  // body "crate"
  const size_t body = bodyLengthOffset(message) + 4;
  auto embedded = encoded(message);
  embedded[body + 2] = 0;  // "cr\0te"
  auto unterminated = encoded(message);
  unterminated[body + 5] = 'x';  // the NUL after "crate"
  rbsim::wrench_t decoded;
  EXPECT_FALSE(decodeWholeMessage(decoded, embedded.data(), embedded.size()));
  EXPECT_FALSE(decodeWholeMessage(decoded, unterminated.data(), unterminated.size()));
}

// An array count is checked against the bytes left before anything is
// allocated: a state page claiming 2^31 − 1 bodies is refused at once.
TEST(MessageDecode, RefusesArrayCountsBeyondTheBytesLeft) {
  rbsim::world_state_t page{};
  page.num_bodies = 0;
  auto bytes = encoded(page);
  // num_bodies is the last field of an empty page.
  for (const int32_t count : {INT32_MAX, -1, 1}) {
    putBigEndian32(bytes, bytes.size() - 4, count);
    rbsim::world_state_t decoded;
    EXPECT_FALSE(decodeWholeMessage(decoded, bytes.data(), bytes.size())) << count;
  }
}

}  // namespace
}  // namespace rbsim
