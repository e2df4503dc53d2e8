// The server's whole input path without LCM: a sequence of (channel, bytes)
// messages fed to the CommandHandler on a session of the small world, with
// steps in between taken the way rbserver takes them (paused sessions step
// only when STEP asked), and every message the server would publish in
// response (acks, world descriptions, state pages) encoded.
//
// Records (input_records.h), by tag % 4:
//   0 payload  on <prefix>WRENCH
//   1 payload  on <prefix>COMMAND
//   2 payload  on <prefix>JOINT_COMMAND if tag & 4, else on
//              <prefix>ROBOT_COMMAND if tag & 8, else on another channel
//              (no ack is due); the small world has no joints, so these
//              exercise decoding, admission and the rejections
//   3 count    take up to count % 8 steps (at most kMaxSteps per input:
//              stepping dominates the cost, and a fuzz input should run in
//              milliseconds; long sessions are the replay tests' business)

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bridge/command_handler.h"
#include "bridge/wire_convert.h"
#include "fuzz_paths.h"
#include "input_records.h"
#include "session/session.h"
#include "small_world.h"

namespace {

constexpr int kMaxSteps = 48;

template <class Message>
void encodeAsPublished(const Message& message) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  if (message.encode(bytes.data(), 0, static_cast<int>(bytes.size())) != static_cast<int>(bytes.size())) {
    std::fprintf(stderr, "a message the server publishes does not encode\n");
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rbsim;
  Session session(fuzz::smallWorld());
  const ServerSettings settings;
  CommandHandler handler(session, settings, rbsim::fuzz::kMeshDir);
  int64_t receivedAt = 0;
  int stepsLeft = kMaxSteps;

  fuzz::InputRecords records(data, size);
  while (!records.done()) {
    const uint8_t tag = records.byte();
    if (tag % 4 == 3) {
      for (int i = records.byte() % 8; i > 0 && stepsLeft > 0; --i, --stepsLeft) {
        // As Server::stepOnce: a paused session steps only when STEP asked.
        if (session.paused() && !session.takeRequestedStep()) break;
        session.step();
      }
      for (const auto& page : worldStatePages(session.world(), 0, session.worldRevision()))
        encodeAsPublished(page);
      for (const auto& page : jointStatePages(session.world(), 0, session.worldRevision()))
        encodeAsPublished(page);
      continue;
    }
    const auto message = records.payload();
    const std::string channel = tag % 4 == 0   ? handler.wrenchChannel()
                                : tag % 4 == 1 ? handler.commandChannel()
                                : (tag & 4) != 0 ? handler.jointCommandChannel()
                                : (tag & 8) != 0 ? handler.robotCommandChannel()
                                                 : std::string("RBSIM_STATE");
    const auto outcome = handler.handle(channel, message.data, message.size, ++receivedAt);
    if (!outcome) continue;
    encodeAsPublished(outcome->ack);
    if (outcome->publishWorld)
      for (const auto& page : worldDescriptionPages(session.world(), 0, session.worldRevision()))
        encodeAsPublished(page);
  }
  return 0;
}
