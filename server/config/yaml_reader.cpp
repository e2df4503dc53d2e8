#include "config/yaml_reader.h"

#include <charconv>
#include <cmath>
#include <string>

namespace rbsim {

namespace {

// yaml-cpp's tag for a plain (unquoted, untagged) scalar. Quoted scalars get
// "!", which YAML defines as a string: "1" in quotes is not a number.
constexpr std::string_view kPlainTag = "?";
constexpr std::string_view kFloatTag = "tag:yaml.org,2002:float";
constexpr std::string_view kIntTag = "tag:yaml.org,2002:int";
constexpr std::size_t kMaxQuotedLength = 40;

std::string formatNumber(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

// A YAML 1.2 core-schema float: [-+]digits[.digits][e[-+]digits], .inf and
// .nan in their three spellings. Anything std::from_chars reads whole is
// taken too ("inf", "1."), so that such typos get the finite-number message
// rather than "not a number".
std::optional<double> parseFloat(std::string_view text) {
  bool negative = false;
  std::string_view digits = text;
  if (!digits.empty() && (digits.front() == '+' || digits.front() == '-')) {
    negative = digits.front() == '-';
    digits.remove_prefix(1);
  }
  if (digits == ".inf" || digits == ".Inf" || digits == ".INF") {
    const double inf = std::numeric_limits<double>::infinity();
    return negative ? -inf : inf;
  }
  if (digits == ".nan" || digits == ".NaN" || digits == ".NAN") {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // from_chars rejects a leading '+' and reads the sign itself otherwise.
  const std::string_view parsed = text.starts_with('+') ? digits : text;
  if (parsed.empty() || parsed.starts_with('+') || parsed.starts_with('-') != negative) {
    return std::nullopt;
  }
  double value = 0.0;
  const auto result = std::from_chars(parsed.data(), parsed.data() + parsed.size(), value);
  if (result.ec != std::errc() || result.ptr != parsed.data() + parsed.size()) {
    return std::nullopt;
  }
  return value;
}

std::string ruleDescription(NumberRule rule) {
  switch (rule.sign) {
    case NumberRule::Sign::Positive:
      return "a positive number";
    case NumberRule::Sign::NonNegative:
      return "a non-negative number";
    case NumberRule::Sign::Any:
      break;
  }
  return "a number";
}

}  // namespace

std::string describeNode(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: {
      const std::string& text = node.Scalar();
      if (text.size() <= kMaxQuotedLength) return "\"" + text + "\"";
      return "\"" + text.substr(0, kMaxQuotedLength) + "...\"";
    }
    case YAML::NodeType::Sequence:
      return node.size() == 1 ? "a list of 1 item"
                              : "a list of " + std::to_string(node.size()) + " items";
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      break;
  }
  return "nothing";
}

YamlNode YamlNode::root(const YAML::Node& node) {
  return {node, "", node.Mark()};
}

YamlNode YamlNode::element(const YAML::Node& child, std::size_t index) const {
  // An empty list item ("- ") is marked on the next line, like an empty
  // value; point at the list instead.
  const YAML::Mark childMark = child.IsNull() ? mark : child.Mark();
  return {child, path + "[" + std::to_string(index) + "]", childMark};
}

const YamlMap::Entry* YamlMap::find(std::string_view key) const {
  for (const Entry& entry : m_entries) {
    if (entry.key == key) return &entry;
  }
  return nullptr;
}

std::string YamlMap::pathOf(std::string_view key) const {
  return m_self.path.empty() ? std::string(key) : m_self.path + "." + std::string(key);
}

Error YamlReader::error(const YAML::Mark& mark, std::string_view path,
                        std::string_view what) const {
  // Appended piece by piece: "literal" + std::string trips a false
  // -Wrestrict in GCC 12 (GCC bug 105329).
  std::string message = m_sourceName;
  if (!mark.is_null()) {
    message.append(":").append(std::to_string(mark.line + 1));
    message.append(":").append(std::to_string(mark.column + 1));
  }
  message.append(": ");
  if (!path.empty()) message.append(path).append(": ");
  message.append(what);
  return Error{message};
}

Error YamlReader::error(const YamlNode& at, std::string_view what) const {
  return error(at.mark, at.path, what);
}

Expected<YamlMap> YamlReader::map(const YamlNode& node) const {
  if (!node.node.IsMap()) return error(node, "expected a mapping, got " + describeNode(node.node));
  std::vector<YamlMap::Entry> entries;
  entries.reserve(node.node.size());
  for (const auto& item : node.node) {
    const YAML::Node& key = item.first;
    const YAML::Node& value = item.second;
    if (!key.IsScalar()) {
      return error(key.Mark(), node.path, "expected a key name, got " + describeNode(key));
    }
    YamlMap::Entry entry;
    entry.key = key.Scalar();
    entry.keyMark = key.Mark();
    entry.value.node = value;
    entry.value.path = node.path.empty() ? entry.key : node.path + "." + entry.key;
    entry.value.mark = value.IsNull() ? key.Mark() : value.Mark();
    // yaml-cpp keeps duplicate keys and node[key] silently takes the first.
    for (const YamlMap::Entry& earlier : entries) {
      if (earlier.key == entry.key) {
        return error(
            entry.keyMark, entry.value.path,
            "duplicate key (first given on line " + std::to_string(earlier.keyMark.line + 1) + ")");
      }
    }
    entries.push_back(std::move(entry));
  }
  return YamlMap(node, std::move(entries));
}

std::optional<Error> YamlReader::checkKeys(const YamlMap& map,
                                           std::span<const std::string_view> allowed,
                                           std::string_view owner) const {
  for (const YamlMap::Entry& entry : map.entries()) {
    bool known = false;
    for (std::string_view key : allowed) known = known || key == entry.key;
    if (known) continue;
    std::string expected;
    for (std::string_view key : allowed) {
      if (!expected.empty()) expected += ", ";
      expected += key;
    }
    return error(entry.keyMark, entry.value.path,
                 "unknown key; " + std::string(owner) + " has: " + expected);
  }
  return std::nullopt;
}

Expected<YamlNode> YamlReader::required(const YamlMap& map, std::string_view key) const {
  const YamlMap::Entry* entry = map.find(key);
  if (entry == nullptr) return error(map.self().mark, map.pathOf(key), "missing required key");
  return entry->value;
}

Expected<std::vector<YamlNode>> YamlReader::list(const YamlNode& node) const {
  if (!node.node.IsSequence())
    return error(node, "expected a list, got " + describeNode(node.node));
  std::vector<YamlNode> items;
  items.reserve(node.node.size());
  for (std::size_t i = 0; i < node.node.size(); ++i) items.push_back(node.element(node.node[i], i));
  return items;
}

Expected<double> YamlReader::number(const YamlNode& node, NumberRule rule) const {
  const std::string expected = ruleDescription(rule);
  if (!node.node.IsScalar())
    return error(node, "expected " + expected + ", got " + describeNode(node.node));
  const std::string& tag = node.node.Tag();
  if (tag != kPlainTag && tag != kFloatTag && tag != kIntTag) {
    return error(node, "expected " + expected + ", got the string " + describeNode(node.node));
  }
  const std::optional<double> value = parseFloat(node.node.Scalar());
  if (!value) return error(node, "expected " + expected + ", got " + describeNode(node.node));
  if (!std::isfinite(*value)) {
    return error(node, "expected a finite number, got " + describeNode(node.node));
  }
  const bool signOk = rule.sign == NumberRule::Sign::Any ||
                      (rule.sign == NumberRule::Sign::Positive && *value > 0.0) ||
                      (rule.sign == NumberRule::Sign::NonNegative && *value >= 0.0);
  if (!signOk) return error(node, "expected " + expected + ", got " + describeNode(node.node));
  if (rule.sign == NumberRule::Sign::Any && std::abs(*value) > rule.limit) {
    return error(node, "expected a number between -" + formatNumber(rule.limit) + " and " +
                           formatNumber(rule.limit) + ", got " + describeNode(node.node));
  }
  if (rule.sign != NumberRule::Sign::Any && *value > rule.limit) {
    return error(node, "expected " + expected + " no larger than " + formatNumber(rule.limit) +
                           ", got " + describeNode(node.node));
  }
  return *value;
}

Expected<std::vector<double>> YamlReader::numberList(const YamlNode& node, std::size_t count,
                                                     NumberRule rule) const {
  const std::string expected = "expected a list of " + std::to_string(count) + " numbers";
  if (!node.node.IsSequence() || node.node.size() != count) {
    return error(node, expected + ", got " + describeNode(node.node));
  }
  std::vector<double> values;
  values.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    Expected<double> value = number(node.element(node.node[i], i), rule);
    if (!value) return value.error();
    values.push_back(*value);
  }
  return values;
}

Expected<Vec3> YamlReader::vec3(const YamlNode& node, NumberRule rule) const {
  Expected<std::array<double, 3>> values = numbers<3>(node, rule);
  if (!values) return values.error();
  return Vec3((*values)[0], (*values)[1], (*values)[2]);
}

Expected<bool> YamlReader::boolean(const YamlNode& node) const {
  if (node.node.IsScalar() && node.node.Tag() == kPlainTag) {
    const std::string& text = node.node.Scalar();
    if (text == "true" || text == "True" || text == "TRUE") return true;
    if (text == "false" || text == "False" || text == "FALSE") return false;
  }
  return error(node, "expected true or false, got " + describeNode(node.node));
}

Expected<uint64_t> YamlReader::wholeNumber(const YamlNode& node, uint64_t max, std::string_view what) const {
  const auto refuse = [&] {
    return error(node, "expected a whole number from 0 to " + std::to_string(max) + " (" + std::string(what) +
                           "; 0x for hexadecimal), got " + describeNode(node.node));
  };
  if (!node.node.IsScalar()) return refuse();
  const std::string_view tag = node.node.Tag();
  if (tag != kPlainTag && tag != kIntTag) return refuse();
  std::string_view text = node.node.Scalar();
  int base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    base = 16;
    text.remove_prefix(2);
  }
  // from_chars takes no sign, spaces or prefix: "-1", "+1", " 1" and "1.0" are refused.
  uint64_t value = 0;
  const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value, base);
  if (text.empty() || status != std::errc() || end != text.data() + text.size() || value > max) return refuse();
  return value;
}

Expected<std::string> YamlReader::string(const YamlNode& node) const {
  if (!node.node.IsScalar())
    return error(node, "expected a string, got " + describeNode(node.node));
  return node.node.Scalar();
}

Expected<double> YamlReader::number(const YamlMap& map, std::string_view key, NumberRule rule,
                                    double fallback) const {
  const YamlMap::Entry* entry = map.find(key);
  if (entry == nullptr) return fallback;
  return number(entry->value, rule);
}

Expected<Vec3> YamlReader::vec3(const YamlMap& map, std::string_view key, NumberRule rule,
                                const Vec3& fallback) const {
  const YamlMap::Entry* entry = map.find(key);
  if (entry == nullptr) return fallback;
  return vec3(entry->value, rule);
}

Expected<bool> YamlReader::boolean(const YamlMap& map, std::string_view key, bool fallback) const {
  const YamlMap::Entry* entry = map.find(key);
  if (entry == nullptr) return fallback;
  return boolean(entry->value);
}

}  // namespace rbsim
