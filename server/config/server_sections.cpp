#include "config/server_sections.h"

#include <array>
#include <filesystem>
#include <string_view>

namespace rbsim {

namespace {

// Reads the optional section `name` of the root map into `settings` with `read`.
template <class ReadSection>
std::optional<Error> readSection(const YamlReader& reader, const YamlMap& root,
                                 std::string_view name, ReadSection read) {
  const YamlMap::Entry* entry = root.find(name);
  if (entry == nullptr) return std::nullopt;
  const auto section = reader.map(entry->value);
  if (!section) return section.error();
  return read(*section);
}

std::optional<Error> readLcm(const YamlReader& reader, const YamlMap& lcm, ServerSettings& out) {
  static constexpr std::array<std::string_view, 5> kKeys = {"url", "channel_prefix", "state_rate",
                                                            "status_rate", "contacts_rate"};
  if (auto error = reader.checkKeys(lcm, kKeys, "the lcm section")) return error;
  if (const auto* url = lcm.find("url")) {
    const auto text = reader.string(url->value);
    if (!text) return text.error();
    out.lcmUrl = *text;
  }
  if (const auto* prefix = lcm.find("channel_prefix")) {
    const auto text = reader.string(prefix->value);
    if (!text) return text.error();
    out.channelPrefix = *text;
  }
  const auto stateRate = reader.number(lcm, "state_rate", NumberRule::nonNegative(1e6), out.stateRate);
  if (!stateRate) return stateRate.error();
  out.stateRate = *stateRate;
  const auto contactsRate =
      reader.number(lcm, "contacts_rate", NumberRule::nonNegative(1e6), out.contactsRate);
  if (!contactsRate) return contactsRate.error();
  out.contactsRate = *contactsRate;
  if (const auto* entry = lcm.find("status_rate")) {
    const auto rate = reader.number(entry->value, NumberRule::positive(10.0));
    if (!rate) return rate.error();
    if (*rate < 1.0) return reader.error(entry->value, "expected a rate between 1 and 10 Hz");
    out.statusRate = *rate;
  }
  return std::nullopt;
}

std::optional<Error> readServer(const YamlReader& reader, const YamlMap& server,
                                ServerSettings& out) {
  // viewer_mesh_directory is the world's (readViewerMeshDirectory).
  static constexpr std::array<std::string_view, 12> kKeys = {
      "real_time_factor", "duration",         "catch_up",  "max_burst",
      "record",           "start_paused",     "spin_us",   "checkpoint_dir",
      "checkpoint_every", "read_only",        "spawn_mesh_directory", "viewer_mesh_directory"};
  if (auto error = reader.checkKeys(server, kKeys, "the server section")) return error;
  const auto rtf = reader.number(server, "real_time_factor",
                                 NumberRule::nonNegative(out.maxRealTimeFactor), out.realTimeFactor);
  if (!rtf) return rtf.error();
  out.realTimeFactor = *rtf;
  if (const auto* entry = server.find("duration")) {
    const auto duration = reader.number(entry->value, NumberRule::positive(1e9));
    if (!duration) return duration.error();
    out.duration = *duration;
  }
  if (const auto* entry = server.find("catch_up")) {
    const auto policy = reader.string(entry->value);
    if (!policy) return policy.error();
    if (*policy == "burst") {
      out.catchUp = CatchUpPolicy::Burst;
    } else if (*policy == "reanchor") {
      out.catchUp = CatchUpPolicy::Reanchor;
    } else {
      return reader.error(entry->value, "expected burst or reanchor, got \"" + *policy + "\"");
    }
  }
  const auto burst = reader.number(server, "max_burst", NumberRule::positive(100000),
                                   static_cast<double>(out.maxBurst));
  if (!burst) return burst.error();
  out.maxBurst = static_cast<int>(*burst);
  if (const auto* entry = server.find("record")) {
    const auto path = reader.string(entry->value);
    if (!path) return path.error();
    out.recordPath = *path;
  }
  if (const auto* entry = server.find("spawn_mesh_directory")) {
    const auto directory = reader.string(entry->value);
    if (!directory) return directory.error();
    if (directory->empty()) return reader.error(entry->value, "expected a directory");
    // Like mesh paths in the config file: relative to the file.
    out.spawnMeshDirectory =
        (std::filesystem::path(reader.sourceName()).parent_path() / *directory).lexically_normal().string();
  }
  if (const auto* entry = server.find("viewer_mesh_directory")) {
    // Used by the world's robots (readViewerMeshDirectory); checked here
    // too, for a world without robots.
    const auto directory = reader.string(entry->value);
    if (!directory) return directory.error();
    if (directory->empty()) return reader.error(entry->value, "expected a directory");
  }
  const auto spin = reader.number(server, "spin_us", NumberRule::nonNegative(1e6),
                                  static_cast<double>(out.spinNanoseconds) * 1e-3);
  if (!spin) return spin.error();
  out.spinNanoseconds = static_cast<int64_t>(*spin * 1e3);
  if (const auto* entry = server.find("checkpoint_dir")) {
    const auto path = reader.string(entry->value);
    if (!path) return path.error();
    if (path->empty()) return reader.error(entry->value, "expected a directory path");
    // Relative to the config file, like mesh files: the daemon's working
    // directory is nobody's business (systemd starts it in /).
    const std::filesystem::path directory(*path);
    out.checkpointDirectory =
        directory.is_absolute() ? *path
                                : (std::filesystem::path(reader.sourceName()).parent_path() / directory).string();
  }
  const auto every = reader.number(server, "checkpoint_every", NumberRule::nonNegative(1e9), out.checkpointEvery);
  if (!every) return every.error();
  out.checkpointEvery = *every;
  const auto readOnly = reader.boolean(server, "read_only", out.readOnly);
  if (!readOnly) return readOnly.error();
  out.readOnly = *readOnly;
  const auto paused = reader.boolean(server, "start_paused", out.startPaused);
  if (!paused) return paused.error();
  out.startPaused = *paused;
  return std::nullopt;
}

std::optional<Error> readLimits(const YamlReader& reader, const YamlMap& limits,
                                ServerSettings& out) {
  static constexpr std::array<std::string_view, 15> kKeys = {
      "max_force", "max_torque", "max_lever_arm", "max_duration", "max_steps_ahead",
      "max_real_time_factor", "max_steps_per_command", "wrench_bodies", "client_rate", "client_burst",
      "max_message_bytes", "max_bodies", "max_joints", "max_linear_speed", "max_angular_speed"};
  if (auto error = reader.checkKeys(limits, kKeys, "the limits section")) return error;
  struct Field {
    std::string_view key;
    double* value;
  };
  double stepsAhead = static_cast<double>(out.limits.maxStepsAhead);
  double stepsPerCommand = static_cast<double>(out.maxStepsPerCommand);
  const std::array<Field, 9> fields = {{{"max_force", &out.limits.maxForce},
                                        {"max_torque", &out.limits.maxTorque},
                                        {"max_lever_arm", &out.limits.maxLeverArm},
                                        {"max_duration", &out.limits.maxDuration},
                                        {"max_steps_ahead", &stepsAhead},
                                        {"max_real_time_factor", &out.maxRealTimeFactor},
                                        {"max_steps_per_command", &stepsPerCommand},
                                        {"max_linear_speed", &out.stateLimits.maxLinearSpeed},
                                        {"max_angular_speed", &out.stateLimits.maxAngularSpeed}}};
  for (const Field& field : fields) {
    const auto value = reader.number(limits, field.key, NumberRule::positive(1e15), *field.value);
    if (!value) return value.error();
    *field.value = *value;
  }
  if (const auto* entry = limits.find("wrench_bodies")) {
    const auto names = reader.list(entry->value);
    if (!names) return names.error();
    out.wrenchBodies.emplace();
    for (const YamlNode& node : *names) {
      const auto name = reader.string(node);
      if (!name) return name.error();
      out.wrenchBodies->push_back(*name);
    }
  }
  const auto rate = reader.number(limits, "client_rate", NumberRule::nonNegative(1e9), out.clientRate);
  if (!rate) return rate.error();
  out.clientRate = *rate;
  const auto burst = reader.number(limits, "client_burst", NumberRule::positive(1e9), out.clientBurst);
  if (!burst) return burst.error();
  if (const auto* entry = limits.find("client_burst"); entry != nullptr && *burst < 1.0)
    return reader.error(entry->value, "expected at least 1 message, got " + describeNode(entry->value.node));
  out.clientBurst = *burst;
  const auto bytes = reader.number(limits, "max_message_bytes", NumberRule::positive(268435456.0),
                                   static_cast<double>(out.maxMessageBytes));
  if (!bytes) return bytes.error();
  out.maxMessageBytes = static_cast<int64_t>(*bytes);
  const auto bodies = reader.number(limits, "max_bodies", NumberRule::positive(1e9),
                                    static_cast<double>(out.maxBodies));
  if (!bodies) return bodies.error();
  out.maxBodies = static_cast<int64_t>(*bodies);
  const auto joints = reader.number(limits, "max_joints", NumberRule::positive(1e9),
                                    static_cast<double>(out.maxJoints));
  if (!joints) return joints.error();
  out.maxJoints = static_cast<int64_t>(*joints);
  out.limits.maxStepsAhead = static_cast<int64_t>(stepsAhead);
  out.maxStepsPerCommand = static_cast<int64_t>(stepsPerCommand);
  return std::nullopt;
}

}  // namespace

std::optional<Error> readServerSections(const YamlReader& reader, const YamlMap& root,
                                        ServerSettings& settings) {
  if (auto error = readSection(reader, root, "lcm",
                               [&](const YamlMap& m) { return readLcm(reader, m, settings); }))
    return error;
  if (auto error = readSection(reader, root, "server",
                               [&](const YamlMap& m) { return readServer(reader, m, settings); }))
    return error;
  if (auto error = readSection(reader, root, "limits",
                               [&](const YamlMap& m) { return readLimits(reader, m, settings); }))
    return error;
  return std::nullopt;
}

Expected<std::optional<std::filesystem::path>> readViewerMeshDirectory(const YamlReader& reader,
                                                                       const YamlMap& root,
                                                                       const std::filesystem::path& baseDirectory) {
  const YamlMap::Entry* section = root.find("server");
  if (section == nullptr) return std::optional<std::filesystem::path>();
  const auto server = reader.map(section->value);
  if (!server) return server.error();
  const YamlMap::Entry* entry = server->find("viewer_mesh_directory");
  if (entry == nullptr) return std::optional<std::filesystem::path>();
  const auto directory = reader.string(entry->value);
  if (!directory) return directory.error();
  if (directory->empty()) return reader.error(entry->value, "expected a directory");
  // Only a prefix for the URLs the server publishes: what the bridge serves
  // is its own --meshes directory, and a mesh outside this one, or reached
  // through a link leading out, gets no URL (RobotBuilder::meshUrl).
  const std::filesystem::path path(*directory);
  return std::optional<std::filesystem::path>(
      (path.is_absolute() ? path : baseDirectory / path).lexically_normal());
}

}  // namespace rbsim
