#pragma once
// Typed, checked reads from a parsed YAML document, for config files.
//
// Every read either gives a value or an Error that says where and what:
// "world.yaml:7:15: bodies[2].shape.radius: expected a positive number, got "-1"",
// with 1-based line and column and the key path from the document's root.
// Nothing here throws (yaml-cpp's node accessors used here do not).

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rbsim/physics/types.h"

namespace rbsim {

// A node of the document, with the key path that leads to it and the place
// to point at in messages: the node's own mark, or its key's when the value
// is empty (yaml-cpp marks an empty value at the start of the next line).
struct YamlNode {
  YAML::Node node;
  std::string path;  // e.g. "bodies[2].shape"; empty for the root
  YAML::Mark mark;

  static YamlNode root(const YAML::Node& node);
  YamlNode element(const YAML::Node& child, std::size_t index) const;  // path[index]
};

// A mapping whose keys are checked to be scalars and unique, in file order.
class YamlMap {
 public:
  struct Entry {
    std::string key;
    YAML::Mark keyMark;
    YamlNode value;  // value.path is the map's path + "." + key
  };

  YamlMap(YamlNode self, std::vector<Entry> entries)
      : m_self(std::move(self)), m_entries(std::move(entries)) {}

  const YamlNode& self() const { return m_self; }
  const std::vector<Entry>& entries() const { return m_entries; }
  // nullptr if the key is absent.
  const Entry* find(std::string_view key) const;
  // The path a key of this map has, present or not.
  std::string pathOf(std::string_view key) const;

 private:
  YamlNode m_self;
  std::vector<Entry> m_entries;
};

// What a number must be, beyond finite.
struct NumberRule {
  enum class Sign { Any, Positive, NonNegative };
  Sign sign = Sign::Any;
  // Upper bound of the value (Positive, NonNegative) or of its magnitude (Any).
  double limit = std::numeric_limits<double>::max();

  static NumberRule any(double maxMagnitude) { return {Sign::Any, maxMagnitude}; }
  static NumberRule positive(double max) { return {Sign::Positive, max}; }
  static NumberRule nonNegative(double max) { return {Sign::NonNegative, max}; }
};

class YamlReader {
 public:
  explicit YamlReader(std::string sourceName) : m_sourceName(std::move(sourceName)) {}

  const std::string& sourceName() const { return m_sourceName; }

  // "source:line:column: path: what"; the location or the path is left out
  // when unknown or empty.
  Error error(const YAML::Mark& mark, std::string_view path, std::string_view what) const;
  Error error(const YamlNode& at, std::string_view what) const;

  // The node must be a mapping with scalar, unique keys.
  Expected<YamlMap> map(const YamlNode& node) const;
  // Every key of `map` must be one of `allowed`; `owner` names the map in
  // the message ("a sphere shape", "the world").
  std::optional<Error> checkKeys(const YamlMap& map, std::span<const std::string_view> allowed,
                                 std::string_view owner) const;
  // An error at the map if the key is absent.
  Expected<YamlNode> required(const YamlMap& map, std::string_view key) const;

  Expected<std::vector<YamlNode>> list(const YamlNode& node) const;
  // A finite number within `rule`.
  Expected<double> number(const YamlNode& node, NumberRule rule) const;
  // A list of exactly N numbers, each within `rule`.
  template <std::size_t N>
  Expected<std::array<double, N>> numbers(const YamlNode& node, NumberRule rule) const;
  Expected<Vec3> vec3(const YamlNode& node, NumberRule rule) const;
  // A whole number from 0 to `max`, written in decimal or in hexadecimal
  // with 0x (for bit sets); `what` says what it is in the message
  // ("a set of 32 collision bits").
  Expected<uint64_t> wholeNumber(const YamlNode& node, uint64_t max, std::string_view what) const;
  // true or false (YAML 1.2 core schema spellings only, not yes/no/on/off).
  Expected<bool> boolean(const YamlNode& node) const;
  // Any scalar, as written (quoted or plain), possibly empty.
  Expected<std::string> string(const YamlNode& node) const;

  // Optional keys: `fallback` when absent.
  Expected<double> number(const YamlMap& map, std::string_view key, NumberRule rule,
                          double fallback) const;
  Expected<Vec3> vec3(const YamlMap& map, std::string_view key, NumberRule rule,
                      const Vec3& fallback) const;
  Expected<bool> boolean(const YamlMap& map, std::string_view key, bool fallback) const;

 private:
  Expected<std::vector<double>> numberList(const YamlNode& node, std::size_t count,
                                           NumberRule rule) const;

  std::string m_sourceName;
};

// How a node reads in "got ..." messages: the scalar text in quotes, or
// "a list", "a mapping", "nothing".
std::string describeNode(const YAML::Node& node);

template <std::size_t N>
Expected<std::array<double, N>> YamlReader::numbers(const YamlNode& node, NumberRule rule) const {
  Expected<std::vector<double>> values = numberList(node, N, rule);
  if (!values) return values.error();
  std::array<double, N> result{};
  for (std::size_t i = 0; i < N; ++i) result[i] = (*values)[i];
  return result;
}

}  // namespace rbsim
