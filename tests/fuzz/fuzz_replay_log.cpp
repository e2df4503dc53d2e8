// `rbserver --replay LOG --verify`: an LCM log file (an rbserver --record
// file or an lcm-logger log) read by LcmLogReader and re-simulated by Replay
// on a session of the small world, with every output page encoded.
//
// The harness keeps to logs of short sessions: a log whose states, acks or
// handled_t name a step beyond kMaxStep is skipped, because a replay
// faithfully steps the world up to any step a log names (a corrupt log can
// name step 2^62), which is slow by design, not a defect the fuzzer should
// keep reporting as a hang.

#include <cstddef>
#include <cstdint>
#include <string>

#include <rbsim/ack_t.hpp>
#include <rbsim/handled_t.hpp>
#include <rbsim/world_state_t.hpp>

#include "bridge/command_handler.h"
#include "bridge/message_decode.h"
#include "fuzz_paths.h"
#include "replay/lcm_log_reader.h"
#include "replay/replay.h"
#include "scratch_files.h"
#include "session/session.h"
#include "small_world.h"

namespace {

constexpr int64_t kMaxStep = 1000;

template <class Message>
bool namesAFarStep(const std::vector<uint8_t>& data, int64_t Message::*step) {
  Message message;
  return rbsim::decodeWholeMessage(message, data.data(), data.size()) && message.*step > kMaxStep;
}

bool isShortSession(const std::string& path) {
  rbsim::LcmLogReader reader;
  if (!reader.open(path)) return true;
  while (true) {
    auto event = reader.next();
    if (!event || !event->has_value()) return true;
    const rbsim::LogEvent& e = **event;
    if ((e.channel == "RBSIM_STATE" && namesAFarStep(e.data, &rbsim::world_state_t::step)) ||
        (e.channel == "RBSIM_HANDLED" && namesAFarStep(e.data, &rbsim::handled_t::step)) ||
        (e.channel == "RBSIM_ACK" && namesAFarStep(e.data, &rbsim::ack_t::effective_step)))
      return false;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rbsim;
  const std::string path = fuzz::writeScratchFile("session.lcmlog", data, size);
  if (!isShortSession(path)) return 0;

  Session session(fuzz::smallWorld());
  const ServerSettings settings;
  CommandHandler handler(session, settings, rbsim::fuzz::kMeshDir);
  Replay replay(session, handler, settings.channelPrefix, /*verify=*/true,
                [](const std::string&, const std::vector<uint8_t>&, int64_t) {});
  (void)replay.run(path);
  return 0;
}
