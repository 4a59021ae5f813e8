#pragma once
// Names in messages: the closest valid name to a typo, and lists of valid names.
#include <cstddef>
#include <string>
#include <vector>

namespace ballista {

/// Levenshtein distance (insertions, deletions, substitutions each cost 1).
size_t edit_distance(const std::string& a, const std::string& b);
/// The candidate closest to `word` if it is close enough to be a plausible typo, else "".
std::string closest_name(const std::string& word, const std::vector<std::string>& candidates);
/// "; did you mean 'x'?" for a plausible typo, else "; expected one of: a, b, c" ("" if no candidates).
std::string suggest(const std::string& word, const std::vector<std::string>& candidates);
/// "a, b, c".
std::string join_names(const std::vector<std::string>& names);

}  // namespace ballista
