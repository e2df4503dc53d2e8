// RBSIM_COMMAND as the server receives it: the bytes of one LCM message are
// decoded as command_t; the parts of a command that come from the sender
// and reach code other than a flag are then exercised on a small world: a
// SPAWN's spawn_yaml is parsed and the body created and stepped, a REMOVE
// removes the named body.

#include <cstddef>
#include <cstdint>

#include <rbsim/command_t.hpp>

#include "bridge/message_decode.h"
#include "config/config_loader.h"
#include "fuzz_paths.h"
#include "small_world.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rbsim;
  rbsim::command_t message;
  if (!decodeWholeMessage(message, data, size)) return 0;

  World world = fuzz::smallWorld();
  if (message.command == rbsim::command_t::SPAWN) {
    const auto def = parseBodyDef(message.spawn_yaml, "spawn_yaml", rbsim::fuzz::kMeshDir);
    if (!def) return 0;
    if (!world.createBody(*def)) return 0;
  } else if (message.command == rbsim::command_t::REMOVE) {
    const BodyId id = world.findBody(message.body);
    if (id.isNull()) return 0;
    world.removeBody(id);
  } else {
    return 0;
  }
  for (int i = 0; i < 2; ++i) world.step();
  return 0;
}
