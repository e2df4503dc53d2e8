#pragma once
// "Did you mean": the known names closest to one a client got wrong, so a
// refusal of an unknown joint or body points at the name meant (a typo, a
// missing robot prefix, another case).

#include <string>
#include <string_view>
#include <vector>

namespace rbsim {

// The Levenshtein distance between a and b, ignoring ASCII case.
std::size_t editDistanceIgnoringCase(std::string_view a, std::string_view b);

// Up to `count` of `known` within max(2, name's length / 3) edits of `name`,
// closest first (ties in alphabetical order). None for a name longer than
// kMaxSuggestedNameLength: a guess at it would cost more than it tells.
inline constexpr std::size_t kMaxSuggestedNameLength = 128;
std::vector<std::string> closestNames(std::string_view name, const std::vector<std::string>& known,
                                      std::size_t count = 3);

// " (did you mean 'a'?)", " (did you mean 'a' or 'b'?)",
// " (did you mean 'a', 'b' or 'c'?)", or "" when nothing is close.
std::string didYouMean(std::string_view name, const std::vector<std::string>& known);

}  // namespace rbsim
