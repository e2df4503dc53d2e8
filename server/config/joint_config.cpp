#include "config/joint_config.h"

#include "config/closest_names.h"

#include <algorithm>
#include <array>
#include <limits>
#include <cctype>
#include <cmath>
#include <map>
#include <span>
#include <string>
#include <string_view>

namespace rbsim {

namespace {

constexpr double kMaxLength = 1e6;  // m, the config's bound on positions
constexpr double kMaxEffort = 1e12;  // N or N·m
constexpr double kMaxRate = 1e6;     // rad/s or m/s
constexpr std::size_t kMaxNameLength = 128;

constexpr std::array<std::string_view, 20> kJointKeys = {
    "name",   "type",  "body_a", "body_b", "anchor",   "axis",     "anchor_b",          "length",
    "limits", "motor", "effort", "drive",  "damping",  "friction", "collide_connected", "cone_limit",
    "spring", "position", "actuator_limits", "mimic"};
// A follower: q = multiplier · q_leader + offset (a gear: multiplier is
// the ratio with its sign).
constexpr std::array<std::string_view, 3> kMimicKeys = {"joint", "multiplier", "offset"};
constexpr std::array<std::string_view, 2> kActuatorLimitKeys = {"effort", "rate"};
constexpr std::array<std::string_view, 2> kLimitKeys = {"lower", "upper"};
constexpr std::array<std::string_view, 2> kMotorKeys = {"max_effort", "target_rate"};
constexpr std::array<std::string_view, 7> kDriveKeys = {"target",        "stiffness",  "damping",
                                                        "frequency",     "damping_ratio", "max_effort",
                                                        "gravity_compensation"};
// A distance joint's spring: a drive whose target is the joint's `length`.
constexpr std::array<std::string_view, 5> kSpringKeys = {"stiffness", "damping", "frequency", "damping_ratio",
                                                         "max_effort"};
constexpr double kMaxGain = 1e12;       // N·m/rad, N/m, N·m·s/rad or N·s/m
constexpr double kMaxFrequency = 1e6;   // Hz

struct TypeName {
  std::string_view name;
  JointType type;
};
constexpr std::array<TypeName, 5> kTypes = {{{"fixed", JointType::Fixed},
                                             {"revolute", JointType::Revolute},
                                             {"prismatic", JointType::Prismatic},
                                             {"spherical", JointType::Spherical},
                                             {"distance", JointType::Distance}}};

class JointParser {
 public:
  JointParser(const YamlReader& reader, const JointBodyLookup& bodies, const JointBodyNames& bodyNames = {})
      : m_reader(reader), m_bodies(bodies), m_bodyNames(bodyNames) {}

  Expected<NamedJointDef> parse(const YamlNode& node) const {
    Expected<YamlMap> map = m_reader.map(node);
    if (!map) return map.error();
    if (auto error = m_reader.checkKeys(*map, kJointKeys, "a joint")) return *error;
    NamedJointDef out;
    out.source = location(node);
    JointDef& def = out.def;

    Expected<YamlNode> nameNode = m_reader.required(*map, "name");
    if (!nameNode) return nameNode.error();
    Expected<std::string> name = m_reader.string(*nameNode);
    if (!name) return name.error();
    if (name->empty() || name->size() > kMaxNameLength ||
        std::any_of(name->begin(), name->end(), [](char c) { return std::iscntrl(static_cast<unsigned char>(c)) != 0; }))
      return m_reader.error(*nameNode, "expected a non-empty name of at most " + std::to_string(kMaxNameLength) +
                                           " characters, without control characters");
    def.name = *name;

    Expected<YamlNode> typeNode = m_reader.required(*map, "type");
    if (!typeNode) return typeNode.error();
    Expected<std::string> typeName = m_reader.string(*typeNode);
    if (!typeName) return typeName.error();
    const auto type = std::find_if(kTypes.begin(), kTypes.end(), [&](const TypeName& t) { return t.name == *typeName; });
    if (type == kTypes.end())
      return m_reader.error(*typeNode, "expected one of fixed, revolute, prismatic, spherical, distance, got \"" +
                                           *typeName + "\"");
    def.type = type->type;
    const bool axial = def.type == JointType::Revolute || def.type == JointType::Prismatic;

    // Keys that this type does not take.
    for (const YamlMap::Entry& entry : map->entries()) {
      const std::string_view key = entry.key;
      const bool spherical = def.type == JointType::Spherical, distance = def.type == JointType::Distance;
      if (key == "cone_limit" && !spherical)
        return m_reader.error(entry.keyMark, entry.value.path, "only spherical joints take cone_limit, this one is " + *typeName);
      if (key == "axis" && spherical && !map->find("cone_limit"))
        return m_reader.error(entry.keyMark, entry.value.path, "a spherical joint takes an axis only with cone_limit (the cone's axis)");
      if (key == "limits" && distance) continue;  // a rope's lengths
      if (key == "spring" && !distance)
        return m_reader.error(entry.keyMark, entry.value.path, "only distance joints take a spring, this one is " + *typeName);
      if (key == "length" && distance && map->find("limits") && !map->find("spring"))
        return m_reader.error(entry.keyMark, entry.value.path,
                              "a distance joint has a length (a rod) or limits (a rope: free between them), not both "
                              "(a spring takes both: its rest length and its stops)");
      if (((key == "axis" && !spherical) || key == "limits" || key == "motor" || key == "effort" || key == "drive" ||
           key == "damping" || key == "friction" || key == "position" || key == "actuator_limits" || key == "mimic") &&
          !axial)
        return m_reader.error(entry.keyMark, entry.value.path,
                              "only revolute and prismatic joints take " + std::string(key) + ", this one is " +
                                  *typeName);
      if ((key == "anchor_b" || key == "length") && def.type != JointType::Distance)
        return m_reader.error(entry.keyMark, entry.value.path,
                              "only distance joints take " + std::string(key) + ", this one is " + *typeName);
    }

    bool moves[2] = {false, false};
    for (const bool sideB : {false, true}) {
      const char* key = sideB ? "body_b" : "body_a";
      Expected<YamlNode> bodyNode = m_reader.required(*map, key);
      if (!bodyNode) return bodyNode.error();
      Expected<std::string> body = m_reader.string(*bodyNode);
      if (!body) return body.error();
      if (*body != "world") {
        const std::optional<bool> bodyMoves = m_bodies(*body);
        if (!bodyMoves)
          return m_reader.error(*bodyNode, "no body named \"" + *body + "\" (a body's name, or world)" +
                                               (m_bodyNames ? didYouMean(*body, m_bodyNames()) : std::string()));
        moves[sideB ? 1 : 0] = *bodyMoves;
      }
      (sideB ? out.bodyB : out.bodyA) = *body;
    }
    if (out.bodyA == out.bodyB) {
      const YamlMap::Entry* entry = map->find("body_b");
      return m_reader.error(entry->value, out.bodyA == "world" ? "both sides are the world: the joint joins nothing"
                                                                : "body_a and body_b are the same body");
    }
    if (!moves[0] && !moves[1])
      return m_reader.error(map->find("body_b")->value, "neither side moves (both are the world or static bodies)");

    Expected<YamlNode> anchor = m_reader.required(*map, "anchor");
    if (!anchor) return anchor.error();
    Expected<Vec3> anchorValue = m_reader.vec3(*anchor, NumberRule::any(kMaxLength));
    if (!anchorValue) return anchorValue.error();
    def.anchor = *anchorValue;

    if (axial) {
      Expected<YamlNode> axisNode = m_reader.required(*map, "axis");
      if (!axisNode) return axisNode.error();
      Expected<Vec3> axis = m_reader.vec3(*axisNode, NumberRule::any(kMaxLength));
      if (!axis) return axis.error();
      if (axis->norm() < 1e-9) return m_reader.error(*axisNode, "the axis must not be zero");
      def.axis = axis->normalized();
      if (const YamlMap::Entry* limits = map->find("limits")) {
        Expected<JointLimit> limit = parseLimit(limits->value, NumberRule::any(kMaxLength));
        if (!limit) return limit.error();
        def.limit = *limit;
      }
      // The joint's coordinate as the bodies are placed (a robot
      // description's joint position); the limits and the drive's target
      // count from the same zero.
      if (const YamlMap::Entry* position = map->find("position")) {
        Expected<double> value = m_reader.number(position->value, NumberRule::any(kMaxLength));
        if (!value) return value.error();
        if (def.limit.enabled && (*value < def.limit.lower || *value > def.limit.upper))
          return m_reader.error(position->value, "the joint starts at " + std::to_string(*value) +
                                                     ", outside its limits [" + std::to_string(def.limit.lower) + ", " +
                                                     std::to_string(def.limit.upper) +
                                                     "]: a joint cannot start beyond its stops");
        def.position = *value;
      }
      if (const YamlMap::Entry* motor = map->find("motor")) {
        Expected<YamlMap> motorMap = m_reader.map(motor->value);
        if (!motorMap) return motorMap.error();
        if (auto error = m_reader.checkKeys(*motorMap, kMotorKeys, "a motor")) return *error;
        Expected<YamlNode> capNode = m_reader.required(*motorMap, "max_effort");
        if (!capNode) return capNode.error();
        Expected<double> cap = m_reader.number(*capNode, NumberRule::nonNegative(kMaxEffort));
        if (!cap) return cap.error();
        Expected<double> target = m_reader.number(*motorMap, "target_rate", NumberRule::any(kMaxRate), 0.0);
        if (!target) return target.error();
        def.motor = {true, *target, *cap};
      }
      if (const YamlMap::Entry* drive = map->find("drive")) {
        if (def.motor.enabled)
          return m_reader.error(drive->keyMark, drive->value.path,
                                "a joint takes a motor or a drive, not both (the drive is a position servo, the motor a velocity one)");
        Expected<JointDrive> parsed = parseDrive(drive->value, kDriveKeys, "a drive");
        if (!parsed) return parsed.error();
        def.drive = *parsed;
      }
      Expected<double> damping = m_reader.number(*map, "damping", NumberRule::nonNegative(kMaxGain), 0.0);
      if (!damping) return damping.error();
      def.damping = *damping;
      Expected<double> friction = m_reader.number(*map, "friction", NumberRule::nonNegative(kMaxEffort), 0.0);
      if (!friction) return friction.error();
      def.friction = *friction;
      Expected<double> effort = m_reader.number(*map, "effort", NumberRule::any(kMaxEffort), 0.0);
      if (!effort) return effort.error();
      def.effort = *effort;
      if (const YamlMap::Entry* limits = map->find("actuator_limits")) {
        Expected<YamlMap> limitMap = m_reader.map(limits->value);
        if (!limitMap) return limitMap.error();
        if (auto error = m_reader.checkKeys(*limitMap, kActuatorLimitKeys, "actuator limits")) return *error;
        if (limitMap->find("effort") == nullptr && limitMap->find("rate") == nullptr)
          return m_reader.error(limits->value, "actuator limits need an effort (N·m or N), a rate (rad/s or m/s) or both");
        const double none = std::numeric_limits<double>::infinity();
        Expected<double> cap = m_reader.number(*limitMap, "effort", NumberRule::positive(kMaxEffort), none);
        if (!cap) return cap.error();
        Expected<double> rate = m_reader.number(*limitMap, "rate", NumberRule::positive(kMaxRate), none);
        if (!rate) return rate.error();
        def.actuatorLimits = {*cap, *rate};
      }
      if (const YamlMap::Entry* mimic = map->find("mimic")) {
        Expected<YamlMap> mimicMap = m_reader.map(mimic->value);
        if (!mimicMap) return mimicMap.error();
        if (auto error = m_reader.checkKeys(*mimicMap, kMimicKeys, "a mimic")) return *error;
        Expected<YamlNode> leaderNode = m_reader.required(*mimicMap, "joint");
        if (!leaderNode) return leaderNode.error();
        Expected<std::string> leader = m_reader.string(*leaderNode);
        if (!leader) return leader.error();
        if (leader->empty() || leader->size() > kMaxNameLength)
          return m_reader.error(*leaderNode, "the leading joint's name must be 1 to " + std::to_string(kMaxNameLength) +
                                                 " characters");
        if (*leader == def.name) return m_reader.error(*leaderNode, "a joint cannot follow itself");
        Expected<double> multiplier = m_reader.number(*mimicMap, "multiplier", NumberRule::any(kMaxGain), 1.0);
        if (!multiplier) return multiplier.error();
        Expected<double> offset = m_reader.number(*mimicMap, "offset", NumberRule::any(kMaxLength), 0.0);
        if (!offset) return offset.error();
        if (map->find("motor") || map->find("drive") || map->find("effort"))
          return m_reader.error(mimic->value, "a joint that follows another (mimic) takes no motor, drive or effort of its "
                                              "own: its leader's move both");
        def.mimic = {true, *leader, *multiplier, *offset};
      }
    }
    if (def.type == JointType::Spherical) {
      if (const YamlMap::Entry* cone = map->find("cone_limit")) {
        Expected<double> angle = m_reader.number(cone->value, NumberRule::positive(3.14159265358979323846));
        if (!angle) return angle.error();
        if (!(*angle < 3.14159265358979323846)) return m_reader.error(cone->value, "the cone's half angle must be below π rad");
        def.coneAngle = *angle;
        Expected<YamlNode> axisNode = m_reader.required(*map, "axis");
        if (!axisNode) return axisNode.error();
        Expected<Vec3> axis = m_reader.vec3(*axisNode, NumberRule::any(kMaxLength));
        if (!axis) return axis.error();
        if (axis->norm() < 1e-9) return m_reader.error(*axisNode, "the axis must not be zero");
        def.axis = axis->normalized();
      }
    }
    if (def.type == JointType::Distance) {
      Expected<YamlNode> otherAnchor = m_reader.required(*map, "anchor_b");
      if (!otherAnchor) return otherAnchor.error();
      Expected<Vec3> anchorB = m_reader.vec3(*otherAnchor, NumberRule::any(kMaxLength));
      if (!anchorB) return anchorB.error();
      def.anchorB = *anchorB;
      const double apart = (def.anchorB - def.anchor).norm();
      const YamlMap::Entry* limits = map->find("limits");
      if (limits) {
        Expected<JointLimit> limit = parseLimit(limits->value, NumberRule::nonNegative(kMaxLength));
        if (!limit) return limit.error();
        if (!(limit->upper > 0.0)) return m_reader.error(limits->value, "a rope's upper length must be positive");
        def.limit = *limit;
      }
      if (const YamlMap::Entry* spring = map->find("spring")) {
        // A spring between the anchors, its rest length `length` (the
        // anchors' distance by default), between the limits' stops if any.
        Expected<JointDrive> drive = parseDrive(spring->value, kSpringKeys, "a spring");
        if (!drive) return drive.error();
        Expected<double> rest = m_reader.number(*map, "length", NumberRule::nonNegative(kMaxLength), apart);
        if (!rest) return rest.error();
        drive->target = *rest;
        def.drive = *drive;
        def.length = *rest;
        return finish(*map, out);
      }
      if (limits) return finish(*map, out);
      Expected<double> length = m_reader.number(*map, "length", NumberRule::positive(kMaxLength), apart);
      if (!length) return length.error();
      if (!(*length > 0.0))
        return m_reader.error(*otherAnchor, "the anchors coincide: give the rod a length");
      def.length = *length;
    }
    return finish(*map, out);
  }

 private:
  // The keys every joint may take, last.
  Expected<NamedJointDef> finish(const YamlMap& map, NamedJointDef& out) const {
    Expected<bool> collide = m_reader.boolean(map, "collide_connected", false);
    if (!collide) return collide.error();
    out.def.collideConnected = *collide;
    return out;
  }

  // limits: {lower, upper}, lower <= upper.
  Expected<JointLimit> parseLimit(const YamlNode& node, NumberRule rule) const {
    Expected<YamlMap> limitMap = m_reader.map(node);
    if (!limitMap) return limitMap.error();
    if (auto error = m_reader.checkKeys(*limitMap, kLimitKeys, "limits")) return *error;
    Expected<YamlNode> lowerNode = m_reader.required(*limitMap, "lower");
    if (!lowerNode) return lowerNode.error();
    Expected<YamlNode> upperNode = m_reader.required(*limitMap, "upper");
    if (!upperNode) return upperNode.error();
    Expected<double> lower = m_reader.number(*lowerNode, rule);
    if (!lower) return lower.error();
    Expected<double> upper = m_reader.number(*upperNode, rule);
    if (!upper) return upper.error();
    if (*lower > *upper)
      return m_reader.error(*upperNode, "upper (" + std::to_string(*upper) + ") is below lower (" +
                                            std::to_string(*lower) + ")");
    return JointLimit{true, *lower, *upper};
  }

 public:
  // drive: {target, stiffness, damping} or {target, frequency,
  // damping_ratio}, with an optional max_effort.
  // The same keys but target make a distance joint's spring (`keys` and
  // `what` say which).
  Expected<JointDrive> parseDrive(const YamlNode& node, std::span<const std::string_view> keys, const char* what) const {
    Expected<YamlMap> map = m_reader.map(node);
    if (!map) return map.error();
    if (auto error = m_reader.checkKeys(*map, keys, what)) return *error;
    JointDrive drive;
    drive.enabled = true;
    Expected<double> target = m_reader.number(*map, "target", NumberRule::any(kMaxLength), 0.0);
    if (!target) return target.error();
    drive.target = *target;
    const YamlMap::Entry* frequency = map->find("frequency");
    const YamlMap::Entry* stiffness = map->find("stiffness");
    if (frequency && (stiffness || map->find("damping")))
      return m_reader.error(frequency->keyMark, frequency->value.path,
                            "give stiffness and damping, or frequency and damping_ratio, not both");
    if (frequency) {
      Expected<double> hertz = m_reader.number(frequency->value, NumberRule::positive(kMaxFrequency));
      if (!hertz) return hertz.error();
      drive.frequency = *hertz;
      Expected<double> ratio = m_reader.number(*map, "damping_ratio", NumberRule::nonNegative(kMaxFrequency), 1.0);
      if (!ratio) return ratio.error();
      drive.dampingRatio = *ratio;
    } else {
      if (const YamlMap::Entry* ratio = map->find("damping_ratio"))
        return m_reader.error(ratio->keyMark, ratio->value.path, "damping_ratio goes with frequency (or give damping)");
      Expected<YamlNode> stiffnessNode = m_reader.required(*map, "stiffness");
      if (!stiffnessNode) return stiffnessNode.error();
      Expected<double> k = m_reader.number(*stiffnessNode, NumberRule::nonNegative(kMaxGain));
      if (!k) return k.error();
      drive.stiffness = *k;
      Expected<double> c = m_reader.number(*map, "damping", NumberRule::nonNegative(kMaxGain), 0.0);
      if (!c) return c.error();
      drive.damping = *c;
    }
    if (const YamlMap::Entry* cap = map->find("max_effort")) {
      Expected<double> value = m_reader.number(cap->value, NumberRule::positive(kMaxEffort));
      if (!value) return value.error();
      drive.maxEffort = *value;
    }
    // (A spring's keys do not hold it: checkKeys refused it above.)
    Expected<bool> compensate = m_reader.boolean(*map, "gravity_compensation", false);
    if (!compensate) return compensate.error();
    drive.gravityCompensation = *compensate;
    return drive;
  }

 private:
  std::string location(const YamlNode& node) const {
    return m_reader.sourceName() + ":" + std::to_string(node.mark.line + 1) + ":" + std::to_string(node.mark.column + 1) +
           ": " + node.path;
  }

  const YamlReader& m_reader;
  const JointBodyLookup& m_bodies;
  JointBodyNames m_bodyNames;
};

}  // namespace

Expected<JointDrive> parseJointDrive(const YamlReader& reader, const YamlNode& node) {
  const JointBodyLookup noBodies = [](const std::string&) { return std::optional<bool>(); };
  return JointParser(reader, noBodies).parseDrive(node, kDriveKeys, "a drive");
}

std::optional<Error> parseJoints(const YamlReader& reader, const YamlNode& node, const JointBodyLookup& bodies,
                                 std::vector<NamedJointDef>& joints, const JointBodyNames& bodyNames) {
  Expected<std::vector<YamlNode>> items = reader.list(node);
  if (!items) return items.error();
  const JointParser parser(reader, bodies, bodyNames);
  std::map<std::string, std::size_t, std::less<>> indexByName;
  for (std::size_t i = 0; i < items->size(); ++i) {
    Expected<NamedJointDef> joint = parser.parse((*items)[i]);
    if (!joint) return joint.error();
    const auto [existing, inserted] = indexByName.emplace(joint->def.name, i);
    if (!inserted)
      return reader.error((*items)[i].node["name"].Mark(), (*items)[i].path + ".name",
                          "duplicate joint name \"" + joint->def.name + "\" (also the name of " + node.path + "[" +
                              std::to_string(existing->second) + "])");
    joints.push_back(std::move(*joint));
  }
  return std::nullopt;
}

}  // namespace rbsim
