#pragma once

#include <optional>
#include <string>
#include <vector>

namespace aaf::cli {

/// The candidate a user most likely meant by `word` (a method, an option, a
/// channel): one equal to it but for case, else one ending in "." + `word`
/// (the same channel under a view layer), else the nearest within a small
/// edit distance for its length (a typo: a letter wrong, missing, extra or
/// two swapped). nullopt when none is that near.
std::optional<std::string> closest_match(const std::string &word, const std::vector<std::string> &candidates);

/// "; did you mean 'X'?" for closest_match(), or "" when there is none: the
/// tail of an error line.
std::string did_you_mean(const std::string &word, const std::vector<std::string> &candidates);

}  // namespace aaf::cli
