#pragma once
// Decoding LCM messages that arrive from the network (or from a log file):
// untrusted bytes, which must give a message or a refusal, never a crash.

#include <climits>
#include <cstddef>
#include <exception>

namespace rbsim {

// Decodes `message` from exactly `size` bytes (hash included); false if the
// bytes are not one whole message of that type. The generated decoders are
// hardened at build time against length fields no encoder writes
// (lcmtypes/harden_decoders.cmake); what can still throw (an allocation that
// fails) counts as a malformed message, because an exception would unwind
// through LCM's C dispatch and terminate the server.
template <class Message>
bool decodeWholeMessage(Message& message, const void* data, std::size_t size) {
  if (size > static_cast<std::size_t>(INT_MAX)) return false;
  try {
    const int used = message.decode(data, 0, static_cast<int>(size));
    return used >= 0 && static_cast<std::size_t>(used) == size;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace rbsim
