#include "config/sensor_config.h"

#include <array>
#include <cctype>
#include <cstdio>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <span>
#include <string_view>

#include "config/closest_names.h"
#include "config/orientation_config.h"

namespace rbsim {

namespace {

constexpr std::size_t kMaxSensorNameLength = 64;  // it is part of a channel name
constexpr double kMaxPosition = 1e6;              // m
constexpr double kMaxRange = 1e6;                 // m
constexpr double kMaxNoise = 1e9;                 // in the reading's unit
constexpr int kMaxHorizontalSamples = 100000;
constexpr int kMaxBeams = 1024;
// A scan is one LCM message; LCM's own bound is 256 MiB, ours far below.
constexpr int kMaxRays = 1 << 20;

constexpr std::array<std::string_view, 5> kTypeNames = {"imu", "contact", "force_torque", "range", "lidar"};
constexpr std::array<SensorType, 5> kTypes = {SensorType::Imu, SensorType::Contact, SensorType::ForceTorque,
                                              SensorType::Range, SensorType::Lidar};

// Keys every sensor takes, then each type's own.
constexpr std::array<std::string_view, 10> kCommonKeys = {"name", "type",        "body", "robot", "link",
                                                          "position", "orientation", "rpy", "rate",  "noise"};
constexpr std::array<std::string_view, 1> kForceTorqueKeys = {"joint"};
constexpr std::array<std::string_view, 3> kRangeKeys = {"min_range", "max_range", "report_bodies"};
constexpr std::array<std::string_view, 5> kLidarKeys = {"min_range", "max_range", "report_bodies", "horizontal",
                                                        "vertical"};
constexpr std::array<std::string_view, 3> kImuNoiseKeys = {"linear_acceleration", "angular_velocity", "seed"};
constexpr std::array<std::string_view, 3> kWrenchNoiseKeys = {"force", "torque", "seed"};
constexpr std::array<std::string_view, 2> kRangeNoiseKeys = {"range", "seed"};
constexpr std::array<std::string_view, 3> kHorizontalKeys = {"samples", "min", "max"};
constexpr std::array<std::string_view, 3> kVerticalKeys = {"beams", "min", "max"};

// A number as a message shows it: "2000", "0.1", "1e-05".
std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

bool channelSafe(const std::string& name) {
  if (name.empty() || name.size() > kMaxSensorNameLength) return false;
  for (const char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

class SensorParser {
 public:
  SensorParser(const YamlReader& reader, const WorldDef& world) : m_reader(reader), m_world(world) {
    for (const BodyDef& body : world.bodies) m_bodies.push_back(body.name);
    for (const NamedJointDef& joint : world.joints) m_joints.push_back(joint.def.name);
  }

  Expected<SensorDef> parse(const YamlNode& node) const;

 private:
  // An error at `at` that names the sensor.
  Error error(const YamlNode& at, const std::string& sensor, std::string_view what) const {
    return m_reader.error(at, "sensor \"" + sensor + "\": " + std::string(what));
  }
  Error named(Error error, const std::string& sensor) const {
    error.message += " (sensor \"" + sensor + "\")";
    return error;
  }
  std::optional<Error> parseMount(const YamlMap& map, const std::string& name, SensorDef& sensor) const;
  std::optional<Error> parseNoise(const YamlMap& map, const std::string& name, SensorDef& sensor) const;
  std::optional<Error> parsePattern(const YamlMap& map, const std::string& name, SensorDef& sensor) const;
  Expected<std::array<double, 2>> angleLimits(const YamlMap& map, double bound, const std::string& name) const;
  Expected<int> count(const YamlMap& map, std::string_view key, int max, const std::string& name) const;

  const YamlReader& m_reader;
  const WorldDef& m_world;
  std::vector<std::string> m_bodies;
  std::vector<std::string> m_joints;
};

Expected<SensorDef> SensorParser::parse(const YamlNode& node) const {
  Expected<YamlMap> map = m_reader.map(node);
  if (!map) return map.error();
  SensorDef sensor;
  sensor.source = m_reader.sourceName() + ":" + std::to_string(node.mark.line + 1) + ":" +
                  std::to_string(node.mark.column + 1) + ": " + node.path;

  Expected<YamlNode> nameNode = m_reader.required(*map, "name");
  if (!nameNode) return nameNode.error();
  Expected<std::string> name = m_reader.string(*nameNode);
  if (!name) return name.error();
  if (!channelSafe(*name))
    return m_reader.error(*nameNode, "a sensor's name is 1 to " + std::to_string(kMaxSensorNameLength) +
                                         " letters, digits or '_' (it names the channel SENSOR_<name>), got \"" +
                                         *name + "\"");
  sensor.name = *name;

  Expected<YamlNode> typeNode = m_reader.required(*map, "type");
  if (!typeNode) return named(typeNode.error(), *name);
  Expected<std::string> type = m_reader.string(*typeNode);
  if (!type) return named(type.error(), *name);
  bool known = false;
  for (std::size_t i = 0; i < kTypes.size(); ++i) {
    if (*type == kTypeNames[i]) {
      sensor.type = kTypes[i];
      known = true;
    }
  }
  if (!known)
    return error(*typeNode, *name,
                 "unknown sensor type \"" + *type + "\" (expected imu, contact, force_torque, range or lidar)");

  std::vector<std::string_view> allowed(kCommonKeys.begin(), kCommonKeys.end());
  const auto allow = [&](std::span<const std::string_view> keys) { allowed.insert(allowed.end(), keys.begin(), keys.end()); };
  if (sensor.type == SensorType::ForceTorque) allow(kForceTorqueKeys);
  if (sensor.type == SensorType::Range) allow(kRangeKeys);
  if (sensor.type == SensorType::Lidar) allow(kLidarKeys);
  const std::string owner = (sensor.type == SensorType::Imu ? "an " : "a ") + *type + " sensor";
  if (auto bad = m_reader.checkKeys(*map, allowed, owner)) return named(*bad, *name);

  if (auto bad = parseMount(*map, *name, sensor)) return *bad;

  const YamlMap::Entry* position = map->find("position");
  if (position != nullptr) {
    Expected<Vec3> value = m_reader.vec3(position->value, NumberRule::any(kMaxPosition));
    if (!value) return named(value.error(), *name);
    sensor.position = *value;
  }
  Expected<Quaternion> orientation = parseOrientation(m_reader, *map);
  if (!orientation) return named(orientation.error(), *name);
  sensor.orientation = *orientation;

  Expected<YamlNode> rateNode = m_reader.required(*map, "rate");
  if (!rateNode) return named(rateNode.error(), *name);
  Expected<double> rate = m_reader.number(*rateNode, NumberRule::positive(std::numeric_limits<double>::max()));
  if (!rate) return named(rate.error(), *name);
  const double stepRate = 1.0 / m_world.settings.dt;
  if (*rate > stepRate * (1.0 + 1e-9))
    return error(*rateNode, *name,
                 "rate " + shortNumber(*rate) + " Hz is above the world's step rate (" + shortNumber(stepRate) +
                     " Hz, 1/dt): a sensor reads at most once a step");
  sensor.rate = *rate;

  if (auto bad = parseNoise(*map, *name, sensor)) return *bad;
  if (sensor.type == SensorType::Range || sensor.type == SensorType::Lidar)
    if (auto bad = parsePattern(*map, *name, sensor)) return *bad;
  return sensor;
}

std::optional<Error> SensorParser::parseMount(const YamlMap& map, const std::string& name, SensorDef& sensor) const {
  const YamlMap::Entry* robot = map.find("robot");
  std::string robotPrefix;
  if (robot != nullptr) {
    Expected<std::string> text = m_reader.string(robot->value);
    if (!text) return named(text.error(), name);
    robotPrefix = *text + "/";
  }
  if (sensor.type == SensorType::ForceTorque) {
    for (const char* key : {"body", "link"})
      if (const YamlMap::Entry* entry = map.find(key))
        return error(entry->value, name,
                     std::string("a force_torque sensor is on its joint's child body: give joint, not ") + key);
    Expected<YamlNode> jointNode = m_reader.required(map, "joint");
    if (!jointNode) return named(jointNode.error(), name);
    Expected<std::string> joint = m_reader.string(*jointNode);
    if (!joint) return named(joint.error(), name);
    sensor.joint = robotPrefix + *joint;
    for (const NamedJointDef& def : m_world.joints) {
      if (def.def.name != sensor.joint) continue;
      if (def.bodyB == "world")
        return error(*jointNode, name, "joint \"" + sensor.joint + "\" has the world as its child (body_b)");
      sensor.body = def.bodyB;
      return std::nullopt;
    }
    return error(*jointNode, name, "no joint named \"" + sensor.joint + "\"" + didYouMean(sensor.joint, m_joints));
  }

  const YamlMap::Entry* body = map.find("body");
  const YamlMap::Entry* link = map.find("link");
  if (body != nullptr && (robot != nullptr || link != nullptr))
    return error(body->value, name, "give either body, or robot and link, not both");
  if (robot != nullptr && link == nullptr) return error(robot->value, name, "robot needs link (the robot's link the sensor is on)");
  if (link != nullptr && robot == nullptr) return error(link->value, name, "link needs robot (the robot whose link it is)");
  const YamlMap::Entry* where = body != nullptr ? body : link;
  if (where == nullptr) return m_reader.error(map.self(), "sensor \"" + name + "\": missing key \"body\" (or robot and link)");
  Expected<std::string> text = m_reader.string(where->value);
  if (!text) return named(text.error(), name);
  sensor.body = robotPrefix + *text;
  for (const std::string& known : m_bodies)
    if (known == sensor.body) return std::nullopt;
  const std::string what = link != nullptr ? "robot link" : "body";
  return error(where->value, name,
               "no " + what + " named \"" + sensor.body + "\"" + didYouMean(sensor.body, m_bodies) +
                   (link != nullptr ? " (a link joined by a fixed joint is merged into its parent's body)" : ""));
}

std::optional<Error> SensorParser::parseNoise(const YamlMap& map, const std::string& name, SensorDef& sensor) const {
  const YamlMap::Entry* entry = map.find("noise");
  if (entry == nullptr) return std::nullopt;
  Expected<YamlMap> noise = m_reader.map(entry->value);
  if (!noise) return named(noise.error(), name);
  std::span<const std::string_view> keys;
  switch (sensor.type) {
    case SensorType::Imu: keys = kImuNoiseKeys; break;
    case SensorType::Contact:
    case SensorType::ForceTorque: keys = kWrenchNoiseKeys; break;
    case SensorType::Range:
    case SensorType::Lidar: keys = kRangeNoiseKeys; break;
  }
  if (auto bad = m_reader.checkKeys(*noise, keys, "the noise of a " + std::string(sensorTypeName(sensor.type)) + " sensor"))
    return named(*bad, name);
  const auto stddev = [&](std::string_view key, double& out) -> std::optional<Error> {
    Expected<double> value = m_reader.number(*noise, key, NumberRule::nonNegative(kMaxNoise), 0.0);
    if (!value) return named(value.error(), name);
    out = *value;
    return std::nullopt;
  };
  SensorNoise& n = sensor.noise;
  for (auto [key, out] : {std::pair<std::string_view, double*>{"linear_acceleration", &n.linearAcceleration},
                          {"angular_velocity", &n.angularVelocity}, {"force", &n.force}, {"torque", &n.torque},
                          {"range", &n.range}})
    if (auto bad = stddev(key, *out)) return bad;
  if (const YamlMap::Entry* seed = noise->find("seed")) {
    Expected<uint64_t> value =
        m_reader.wholeNumber(seed->value, std::numeric_limits<uint64_t>::max(), "the noise's seed");
    if (!value) return named(value.error(), name);
    n.seed = *value;
  }
  return std::nullopt;
}

Expected<int> SensorParser::count(const YamlMap& map, std::string_view key, int max, const std::string& name) const {
  const YamlMap::Entry* entry = map.find(key);
  if (entry == nullptr) return 1;
  Expected<uint64_t> value = m_reader.wholeNumber(entry->value, static_cast<uint64_t>(max), "a count");
  if (!value) return named(value.error(), name);
  if (*value == 0) return error(entry->value, name, std::string(key) + " must be at least 1");
  return static_cast<int>(*value);
}

Expected<std::array<double, 2>> SensorParser::angleLimits(const YamlMap& map, double bound,
                                                          const std::string& name) const {
  std::array<double, 2> limits{};
  const char* keys[2] = {"min", "max"};
  for (int i = 0; i < 2; ++i) {
    Expected<double> value = m_reader.number(map, keys[i], NumberRule::any(bound), 0.0);
    if (!value) return named(value.error(), name);
    limits[static_cast<std::size_t>(i)] = *value;
  }
  if (limits[0] > limits[1])
    return error(map.find("max") != nullptr ? map.find("max")->value : map.self(), name,
                 "max (" + shortNumber(limits[1]) + " rad) is below min (" + shortNumber(limits[0]) + " rad)");
  return limits;
}

std::optional<Error> SensorParser::parsePattern(const YamlMap& map, const std::string& name, SensorDef& sensor) const {
  ScanPattern& pattern = sensor.pattern;
  Expected<double> minRange = m_reader.number(map, "min_range", NumberRule::nonNegative(kMaxRange), 0.0);
  if (!minRange) return named(minRange.error(), name);
  const YamlMap::Entry* maxEntry = map.find("max_range");
  if (maxEntry == nullptr) return m_reader.error(map.self(), "sensor \"" + name + "\": missing key \"max_range\"");
  Expected<double> maxRange = m_reader.number(maxEntry->value, NumberRule::positive(kMaxRange));
  if (!maxRange) return named(maxRange.error(), name);
  if (*maxRange <= *minRange)
    return error(maxEntry->value, name, "max_range must be above min_range (" + shortNumber(*minRange) + " m)");
  pattern.minRange = *minRange;
  pattern.maxRange = *maxRange;
  Expected<bool> report = m_reader.boolean(map, "report_bodies", false);
  if (!report) return named(report.error(), name);
  pattern.reportBodies = *report;
  if (sensor.type != SensorType::Lidar) return std::nullopt;

  if (const YamlMap::Entry* entry = map.find("horizontal")) {
    Expected<YamlMap> horizontal = m_reader.map(entry->value);
    if (!horizontal) return named(horizontal.error(), name);
    if (auto bad = m_reader.checkKeys(*horizontal, kHorizontalKeys, "a lidar's horizontal pattern"))
      return named(*bad, name);
    Expected<int> samples = count(*horizontal, "samples", kMaxHorizontalSamples, name);
    if (!samples) return samples.error();
    Expected<std::array<double, 2>> limits = angleLimits(*horizontal, 2.0 * std::numbers::pi, name);
    if (!limits) return limits.error();
    pattern.horizontalSamples = *samples;
    pattern.horizontalMin = (*limits)[0];
    pattern.horizontalMax = (*limits)[1];
    if (pattern.horizontalMax - pattern.horizontalMin > 2.0 * std::numbers::pi * (1.0 + 1e-12))
      return error(entry->value, name, "the horizontal span is more than a full turn (2 pi rad)");
  }
  if (const YamlMap::Entry* entry = map.find("vertical")) {
    Expected<YamlMap> vertical = m_reader.map(entry->value);
    if (!vertical) return named(vertical.error(), name);
    if (auto bad = m_reader.checkKeys(*vertical, kVerticalKeys, "a lidar's vertical pattern")) return named(*bad, name);
    Expected<int> beams = count(*vertical, "beams", kMaxBeams, name);
    if (!beams) return beams.error();
    Expected<std::array<double, 2>> limits = angleLimits(*vertical, 0.5 * std::numbers::pi, name);
    if (!limits) return limits.error();
    pattern.beams = *beams;
    pattern.verticalMin = (*limits)[0];
    pattern.verticalMax = (*limits)[1];
  }
  if (static_cast<int64_t>(pattern.beams) * pattern.horizontalSamples > kMaxRays)
    return m_reader.error(map.self(), "sensor \"" + name + "\": " + std::to_string(pattern.beams) + " beams x " +
                                          std::to_string(pattern.horizontalSamples) + " samples is more than " +
                                          std::to_string(kMaxRays) + " rays a scan");
  return std::nullopt;
}

}  // namespace

std::optional<Error> parseSensors(const YamlReader& reader, const YamlNode& node, const WorldDef& world,
                                  std::vector<SensorDef>& sensors) {
  Expected<std::vector<YamlNode>> items = reader.list(node);
  if (!items) return items.error();
  const SensorParser parser(reader, world);
  std::map<std::string, std::string, std::less<>> declaredAt;  // name -> where
  for (const YamlNode& item : *items) {
    Expected<SensorDef> sensor = parser.parse(item);
    if (!sensor) return sensor.error();
    const auto [previous, inserted] = declaredAt.emplace(sensor->name, sensor->source);
    if (!inserted)
      return reader.error(item.node["name"].Mark(), item.path + ".name",
                          "sensor \"" + sensor->name + "\": a second sensor of that name (the first is at " +
                              previous->second + ")");
    sensors.push_back(std::move(*sensor));
  }
  return std::nullopt;
}

}  // namespace rbsim
