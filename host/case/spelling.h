// "Did you mean ...?" for misspelt keys, material names and option values.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace repose {

// Levenshtein distance (insertions, deletions, substitutions each cost 1).
int edit_distance(std::string_view a, std::string_view b);

// "; did you mean 'density'?" when one candidate is close to word, else "". Close: at most two
// edits, and fewer edits than half the word, so that short words do not match everything.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace repose
