// Checkpoints, as `--resume FILE` and RESET to a checkpoint read them: the
// file container (checkpointPayload: magic, version, length, CRC-32) and,
// since random bytes rarely pass a CRC, the payload decoder on its own
// (decodeSessionCheckpoint: session fields, world snapshot, wrenches). A
// session that decodes is resumed in the small world's settings, stepped,
// published and saved again, as the server would.

#include <cstddef>
#include <cstdint>
#include <span>

#include "bridge/wire_convert.h"
#include "persist/checkpoint_file.h"
#include "persist/session_checkpoint.h"
#include "session/session.h"
#include "small_world.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rbsim;
  const std::span<const uint8_t> bytes(data, size);
  (void)checkpointPayload(bytes, "fuzz.rbck");

  auto state = decodeSessionCheckpoint(bytes, fuzz::smallWorld().settings());
  if (!state) return 0;
  Session session(fuzz::smallWorld());
  session.resumeFrom(std::move(state->world), std::move(state->wrenches), state->worldRevision,
                     state->paused, state->stepsRequested, std::move(state->jointCommands));
  for (int i = 0; i < 3; ++i) session.step();
  (void)worldStatePages(session.world(), 0, session.worldRevision());
  (void)worldDescriptionPages(session.world(), 0, session.worldRevision());
  (void)encodeSessionCheckpoint(session);
  return 0;
}
