#pragma once
// The complete state of a World as bytes, for checkpoints: a world restored
// from its snapshot steps on bit-identically to the world it was taken from.
//
// What it holds: the step count and serial counter; every body with the 13
// state numbers as bit patterns, its description (shape with mesh vertices,
// mass properties and whether they were given, placement of the shape in
// body space, material, flags),
// its dynamics, the load given for the coming step, its sleep state
// (asleep, time at rest) and whether the numerical guard froze it; the slot
// table behind BodyIds; and the contact
// solver's warm-start cache (last step's solved manifolds), because the
// next step's impulses start from it. Colliders, body-space meshes and the
// broad phase are rebuilt from the above: they are functions of it.
//
// World settings are not restored: they come from the config. The snapshot
// records the ones a resumed run must share (dt, gravity, integrator,
// contact model and switches) and decoding refuses a mismatch.
//
// Format (little-endian, see byte_stream.h): "RBWS", version, then the
// fields in the order of world_snapshot.cpp. Bumping kVersion is how the
// format changes; old versions are rejected with a message, not misread.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/math/byte_stream.h"
#include "physics/common/expected.h"
#include "physics/world/world.h"

namespace rbsim {

class WorldSnapshot {
 public:
  static constexpr uint32_t kMagic = 0x53574252u;  // "RBWS" in file order
  // 2: a body's freeze reason (numerical guard); 3: loads at points fixed in
  // the body, and whether a body's mass properties were given as data.
  static constexpr uint32_t kVersion = 3;

  // Errors only for a body whose shape the format cannot hold.
  static Expected<bool> write(const World& world, ByteWriter& out);
  static Expected<std::vector<uint8_t>> encode(const World& world);

  // Rebuilds the world with `settings` (the config's), which must match the
  // snapshot's recorded settings. Errors name the field and byte offset of
  // truncated, corrupt or inconsistent data.
  static Expected<World> read(ByteReader& in, const WorldSettings& settings);
  static Expected<World> decode(std::span<const uint8_t> bytes, const WorldSettings& settings);

 private:
  // The warm-start cache: the only part that depends on the contact
  // solver's types, kept here so that a change of SolvedManifold has one
  // place to follow.
  static void writeWarmStart(const std::vector<SolvedManifold>& manifolds, ByteWriter& out);
  static std::vector<SolvedManifold> readWarmStart(ByteReader& in, int bodyCount);
};

}  // namespace rbsim
