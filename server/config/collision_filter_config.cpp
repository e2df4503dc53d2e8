#include "config/collision_filter_config.h"

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <tuple>

namespace rbsim {

namespace {

constexpr std::array<std::string_view, 2> kLinkFilterKeys = {"group", "mask"};

// Levenshtein distance (insertions, deletions, substitutions).
std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({above + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The link name of `links` nearest to `name` (the first of equals, in document order).
const std::string& nearestLink(const std::vector<std::pair<std::string, std::string>>& links, std::string_view name) {
  const auto nearer = [&](const auto& x, const auto& y) { return editDistance(x.first, name) < editDistance(y.first, name); };
  return std::min_element(links.begin(), links.end(), nearer)->first;
}

// The body the link named by `node` is part of, or an error naming the
// link and the nearest one the robot has.
Expected<std::string> bodyOfLink(const YamlReader& reader, const YamlNode& node, const RobotModel& model) {
  Expected<std::string> link = reader.string(node);
  if (!link) return link.error();
  const auto found = std::find_if(model.linkBodies.begin(), model.linkBodies.end(),
                                  [&](const auto& entry) { return entry.first == *link; });
  if (found != model.linkBodies.end()) return found->second;
  std::string message = "the robot has no link named \"" + *link + "\"";
  if (!model.linkBodies.empty()) message += " (nearest: \"" + nearestLink(model.linkBodies, *link) + "\")";
  return reader.error(node, message);
}

BodyDef* findBody(RobotModel& model, const std::string& name) {
  const auto found =
      std::find_if(model.bodies.begin(), model.bodies.end(), [&](const BodyDef& body) { return body.name == name; });
  return found == model.bodies.end() ? nullptr : &*found;
}

ExcludedPair orderedPair(const std::string& a, const std::string& b) { return a < b ? ExcludedPair{a, b} : ExcludedPair{b, a}; }

std::optional<Error> applyLinkFilters(const YamlReader& reader, const YamlNode& node, RobotModel& model) {
  Expected<YamlMap> links = reader.map(node);
  if (!links) return links.error();
  // Links merged into one body share its filter: they must agree.
  std::map<std::string, std::string, std::less<>> setBy;  // body -> the link that set its filter
  for (const YamlMap::Entry& entry : links->entries()) {
    // The key as a node of its own (assigning to a copy of entry.value's
    // YAML::Node would change the document's node itself).
    const YamlNode keyNode{YAML::Node(entry.key), entry.value.path, entry.keyMark};
    Expected<std::string> bodyName = bodyOfLink(reader, keyNode, model);
    if (!bodyName) return bodyName.error();
    Expected<YamlMap> fields = reader.map(entry.value);
    if (!fields) return fields.error();
    if (auto error = reader.checkKeys(*fields, kLinkFilterKeys, "a link's collision filter")) return *error;
    BodyDef* body = findBody(model, *bodyName);
    if (body == nullptr) return reader.error(keyNode, "link \"" + entry.key + "\" is part of no body");
    CollisionFilter filter;
    if (auto error = parseCollisionFilter(reader, *fields, "group", "mask", filter)) return *error;
    if (const auto previous = setBy.find(*bodyName); previous != setBy.end()) {
      if (body->collisionFilter != filter)
        return reader.error(entry.keyMark, entry.value.path,
                            "link \"" + entry.key + "\" is part of body \"" + *bodyName + "\" with link \"" +
                                previous->second + "\" (merged by a fixed joint), which has another filter");
      continue;
    }
    body->collisionFilter = filter;
    setBy.emplace(*bodyName, entry.key);
    model.report.push_back("body '" + *bodyName + "': collision group " + std::to_string(filter.group) + ", mask " +
                           std::to_string(filter.mask) + " (link_collision)");
  }
  return std::nullopt;
}

}  // namespace

Expected<uint32_t> parseCollisionBits(const YamlReader& reader, const YamlNode& node) {
  Expected<uint64_t> value = reader.wholeNumber(node, CollisionFilter::kAllBits, "a set of 32 collision bits");
  if (!value) return value.error();
  return static_cast<uint32_t>(*value);
}

std::optional<Error> parseCollisionFilter(const YamlReader& reader, const YamlMap& map, std::string_view groupKey,
                                          std::string_view maskKey, CollisionFilter& filter) {
  for (const bool isMask : {false, true}) {
    const YamlMap::Entry* entry = map.find(isMask ? maskKey : groupKey);
    if (entry == nullptr) continue;
    Expected<uint32_t> bits = parseCollisionBits(reader, entry->value);
    if (!bits) return bits.error();
    (isMask ? filter.mask : filter.group) = *bits;
  }
  return std::nullopt;
}

std::optional<Error> applyRobotCollisions(const YamlReader& reader, const YamlMap& robot, const std::string& robotName,
                                          RobotModel& model, std::vector<ExcludedPair>& excluded) {
  if (const YamlMap::Entry* links = robot.find("link_collision"))
    if (auto error = applyLinkFilters(reader, links->value, model)) return error;

  Expected<bool> selfCollision = reader.boolean(robot, "self_collision", false);
  if (!selfCollision) return selfCollision.error();
  std::vector<ExcludedPair> pairs;
  if (const YamlMap::Entry* disabled = robot.find("disable_collisions")) {
    Expected<std::vector<YamlNode>> items = reader.list(disabled->value);
    if (!items) return items.error();
    for (const YamlNode& item : *items) {
      Expected<std::vector<YamlNode>> names = reader.list(item);
      if (!names) return names.error();
      if (names->size() != 2)
        return reader.error(item, "expected a pair of link names [link_a, link_b], got a list of " +
                                      std::to_string(names->size()));
      Expected<std::string> a = bodyOfLink(reader, (*names)[0], model);
      if (!a) return a.error();
      Expected<std::string> b = bodyOfLink(reader, (*names)[1], model);
      if (!b) return b.error();
      if ((*names)[0].node.Scalar() == (*names)[1].node.Scalar())
        return reader.error((*names)[1], "a link cannot be paired with itself");
      if (*a != *b) pairs.push_back(orderedPair(*a, *b));  // links merged into one body never collide anyway
    }
  }
  if (!*selfCollision) {
    // Every pair of the robot's bodies that collide at all; the
    // disable_collisions pairs are among them.
    pairs.clear();
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
      for (std::size_t j = i + 1; j < model.bodies.size(); ++j)
        if (model.bodies[i].collides && model.bodies[j].collides)
          pairs.push_back(orderedPair(model.bodies[i].name, model.bodies[j].name));
  }
  std::sort(pairs.begin(), pairs.end(), [](const ExcludedPair& x, const ExcludedPair& y) {
    return std::tie(x.bodyA, x.bodyB) < std::tie(y.bodyA, y.bodyB);
  });
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  model.report.push_back("robot '" + robotName + "': " +
                         (*selfCollision ? "self-collision on, " + std::to_string(pairs.size()) +
                                               " pairs of its bodies excluded (disable_collisions); joined bodies "
                                               "never collide"
                                         : std::string("self-collision off: its bodies do not collide with each "
                                                       "other (self_collision: true turns it on)")));
  excluded.insert(excluded.end(), pairs.begin(), pairs.end());
  return std::nullopt;
}

}  // namespace rbsim
