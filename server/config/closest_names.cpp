#include "config/closest_names.h"

#include <algorithm>
#include <cctype>
#include <utility>

namespace rbsim {

namespace {

char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

// The distance, or anything above `bound` once it is sure to exceed it: a
// row's smallest entry never shrinks in later rows, so the rest of the table
// need not be filled for a name that is far off.
std::size_t boundedDistance(std::string_view a, std::string_view b, std::size_t bound) {
  const std::size_t lengthGap = a.size() > b.size() ? a.size() - b.size() : b.size() - a.size();
  if (lengthGap > bound) return bound + 1;
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    std::size_t smallest = row[0];
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const std::size_t substitution = diagonal + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1);
      row[j] = std::min({above + 1, row[j - 1] + 1, substitution});
      diagonal = above;
      smallest = std::min(smallest, row[j]);
    }
    if (smallest > bound) return bound + 1;
  }
  return row[b.size()];
}

}  // namespace

std::size_t editDistanceIgnoringCase(std::string_view a, std::string_view b) {
  return boundedDistance(a, b, std::max(a.size(), b.size()));
}

std::vector<std::string> closestNames(std::string_view name, const std::vector<std::string>& known,
                                      std::size_t count) {
  if (name.size() > kMaxSuggestedNameLength || count == 0) return {};
  // A third of the name may be wrong, but a short name's suggestions would
  // otherwise be none at all: "lft" for "lift" is one edit of three letters.
  const std::size_t bound = std::max<std::size_t>(2, name.size() / 3);
  std::vector<std::pair<std::size_t, const std::string*>> near;
  for (const std::string& candidate : known) {
    const std::size_t distance = boundedDistance(name, candidate, bound);
    if (distance <= bound) near.emplace_back(distance, &candidate);
  }
  std::sort(near.begin(), near.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first < y.first : *x.second < *y.second;
  });
  std::vector<std::string> names;
  for (const auto& [distance, candidate] : near) {
    if (names.size() == count) break;
    // A world may hold one name once, but the caller's list need not be unique.
    if (std::find(names.begin(), names.end(), *candidate) == names.end()) names.push_back(*candidate);
  }
  return names;
}

std::string didYouMean(std::string_view name, const std::vector<std::string>& known) {
  const std::vector<std::string> names = closestNames(name, known);
  if (names.empty()) return "";
  std::string text = " (did you mean ";
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += "'" + names[i] + "'";
  }
  return text + "?)";
}

}  // namespace rbsim
