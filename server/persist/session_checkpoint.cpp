#include "persist/session_checkpoint.h"

#include <cmath>

#include "persist/checkpoint_file.h"
#include "rbsim/physics/byte_stream.h"
#include "rbsim/physics/world.h"

namespace rbsim {

namespace {

constexpr uint32_t kMagic = 0x53534252u;  // "RBSS"
// 2: a wrench's point frame; 3: joint commands scheduled ahead; 4: their
// target rate and feed-forward (robot_command_t)
constexpr uint32_t kVersion = 4;
constexpr uint32_t kMaxTextLength = 4096;

void writeRequest(const WrenchRequest& r, ByteWriter& out) {
  out.string(r.client);
  out.i64(r.seq);
  out.string(r.body);
  out.u8(static_cast<uint8_t>(r.frame));
  out.u8(static_cast<uint8_t>(r.pointFrame));
  out.vec3(r.force);
  out.vec3(r.torque);
  out.vec3(r.point);
  out.u8(static_cast<uint8_t>(r.mode));
  out.i64(r.durationSteps);
  out.i64(r.firstStep);
}

WrenchRequest readRequest(ByteReader& in) {
  WrenchRequest r;
  r.client = in.string("wrench client", kMaxTextLength);
  r.seq = in.i64("wrench seq");
  r.body = in.string("wrench body", kMaxTextLength);
  const uint8_t frame = in.u8("wrench frame");
  const uint8_t pointFrame = in.u8("wrench point frame");
  r.force = in.vec3("wrench force");
  r.torque = in.vec3("wrench torque");
  r.point = in.vec3("wrench point");
  const uint8_t mode = in.u8("wrench mode");
  r.durationSteps = in.i64("wrench duration");
  r.firstStep = in.i64("wrench first step");
  if (frame > static_cast<uint8_t>(WrenchFrame::ShapeFrame) ||
      pointFrame > static_cast<uint8_t>(WrenchFrame::ShapeFrame) ||
      mode > static_cast<uint8_t>(WrenchMode::ClearAllClients) || r.durationSteps < 1 ||
      !r.force.allFinite() || !r.torque.allFinite() || !r.point.allFinite())
    in.fail("a wrench of client '" + r.client + "' has an invalid frame, mode, duration or value");
  r.frame = static_cast<WrenchFrame>(frame);
  r.pointFrame = static_cast<WrenchFrame>(pointFrame);
  r.mode = static_cast<WrenchMode>(mode);
  return r;
}

std::vector<WrenchRequest> readRequests(ByteReader& in, const char* what) {
  std::vector<WrenchRequest> out;
  const uint32_t count = in.count(what, 100);
  for (uint32_t i = 0; i < count && !in.failed(); ++i) out.push_back(readRequest(in));
  return out;
}

void writeJointCommand(const JointCommandRequest& r, ByteWriter& out) {
  out.string(r.client);
  out.i64(r.seq);
  out.string(r.joint);
  out.u8(static_cast<uint8_t>(r.mode));
  out.f64(r.target);
  out.f64(r.maxEffort);
  out.f64(r.stiffness);
  out.f64(r.damping);
  out.f64(r.targetRate);
  out.f64(r.feedForward);
  out.i64(r.firstStep);
}

std::vector<JointCommandRequest> readJointCommands(ByteReader& in) {
  std::vector<JointCommandRequest> out;
  const uint32_t count = in.count("pending joint command count", 50);
  for (uint32_t i = 0; i < count && !in.failed(); ++i) {
    JointCommandRequest r;
    r.client = in.string("joint command client", kMaxTextLength);
    r.seq = in.i64("joint command seq");
    r.joint = in.string("joint command joint", kMaxTextLength);
    const uint8_t mode = in.u8("joint command mode");
    r.target = in.f64("joint command target");
    r.maxEffort = in.f64("joint command max effort");
    r.stiffness = in.f64("joint command stiffness");
    r.damping = in.f64("joint command damping");
    r.targetRate = in.f64("joint command target rate");
    r.feedForward = in.f64("joint command feed-forward");
    r.firstStep = in.i64("joint command step");
    // Checked as when accepted: a mode, finite numbers (an uncapped
    // drive's max effort is infinite), gains not negative, a step ahead.
    if (mode > static_cast<uint8_t>(JointCommandMode::Effort) || !std::isfinite(r.target) ||
        std::isnan(r.maxEffort) || r.maxEffort < 0.0 || !std::isfinite(r.stiffness) || r.stiffness < 0.0 ||
        !std::isfinite(r.damping) || r.damping < 0.0 || !std::isfinite(r.targetRate) ||
        !std::isfinite(r.feedForward) || r.firstStep < 1)
      in.fail("a joint command of client '" + r.client + "' has an invalid mode, value or step");
    r.mode = static_cast<JointCommandMode>(mode);
    out.push_back(r);
  }
  return out;
}

}  // namespace

Expected<std::vector<uint8_t>> encodeSessionCheckpoint(const Session& session) {
  ByteWriter out;
  out.u32(kMagic);
  out.u32(kVersion);
  out.i64(session.worldRevision());
  out.boolean(session.paused());
  out.i64(session.stepsRequested());
  if (auto written = session.world().writeSnapshot(out); !written) return written.error();
  for (const auto* list : {&session.wrenches().pending(), &session.wrenches().active()}) {
    out.u32(static_cast<uint32_t>(list->size()));
    for (const WrenchRequest& r : *list) writeRequest(r, out);
  }
  out.u32(static_cast<uint32_t>(session.jointCommands().pending().size()));
  for (const JointCommandRequest& r : session.jointCommands().pending()) writeJointCommand(r, out);
  return out.take();
}

Expected<SessionState> decodeSessionCheckpoint(std::span<const uint8_t> payload, const WorldSettings& settings) {
  ByteReader in(payload);
  const uint32_t magic = in.u32("session magic");
  const uint32_t version = in.u32("session version");
  if (in.failed()) return Error{"session: " + in.error()};
  if (magic != kMagic) return Error{"session: not a session checkpoint (bad magic)"};
  if (version != kVersion)
    return Error{"session: version " + std::to_string(version) + " is not supported (this build reads " +
                 std::to_string(kVersion) + ")"};
  const int64_t revision = in.i64("world revision");
  const bool paused = in.boolean("paused");
  const int64_t stepsRequested = in.i64("steps requested");
  if (in.failed()) return Error{"session: " + in.error()};
  auto world = World::readSnapshot(in, settings);
  if (!world) return world.error();
  auto pending = readRequests(in, "pending wrench count");
  auto active = readRequests(in, "active wrench count");
  auto jointCommands = readJointCommands(in);
  if (in.failed()) return Error{"session: " + in.error()};
  if (in.remaining() != 0)
    return Error{"session: " + std::to_string(in.remaining()) + " unexpected bytes after the end"};
  if (revision < 1 || stepsRequested < 0) return Error{"session: invalid world revision or step count"};
  SessionState state{std::move(world).value(), {}, {}, revision, paused, stepsRequested};
  state.wrenches.restore(std::move(pending), std::move(active));
  state.jointCommands = std::move(jointCommands);
  return state;
}

Expected<bool> saveSessionCheckpoint(const Session& session, const std::string& path) {
  const auto payload = encodeSessionCheckpoint(session);
  if (!payload) return payload.error();
  return writeFileAtomically(path, checkpointFileBytes(*payload));
}

Expected<SessionState> loadSessionCheckpoint(const std::string& path, const WorldSettings& settings,
                                             bool noFollow) {
  const auto file = readWholeFile(path, noFollow);
  if (!file) return Error{"checkpoint: " + file.error().message};
  const auto payload = checkpointPayload(*file, path);
  if (!payload) return payload.error();
  auto state = decodeSessionCheckpoint(*payload, settings);
  if (!state) return Error{"checkpoint '" + path + "': " + state.error().message};
  return state;
}

}  // namespace rbsim
