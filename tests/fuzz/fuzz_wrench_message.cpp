// RBSIM_WRENCH as the server receives it: the bytes of one LCM message are
// decoded as wrench_t, validated against the world and the limits
// (wrenchRequestFrom), and an accepted request is scheduled and stepped, so
// that whatever passes validation also has to be safe to apply.

#include <cstddef>
#include <cstdint>

#include <rbsim/wrench_t.hpp>

#include "bridge/message_decode.h"
#include "bridge/wire_convert.h"
#include "session/wrench_scheduler.h"
#include "small_world.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rbsim;
  rbsim::wrench_t message;
  if (!decodeWholeMessage(message, data, size)) return 0;

  World world = fuzz::smallWorld();
  const auto request = wrenchRequestFrom(message, world, world.stepCount() + 1, WrenchLimits{});
  if (!request) return 0;
  WrenchScheduler scheduler;
  scheduler.add(*request);
  // Enough steps for apply_at_step a little ahead and for short durations.
  for (int i = 0; i < 4; ++i) {
    const int64_t step = world.stepCount() + 1;
    scheduler.applyForStep(world, step);
    world.step();
    scheduler.finishStep(step);
  }
  return 0;
}
