#include "suggestion.h"

#include <algorithm>
#include <cctype>
#include <cstddef>

namespace aaf::cli {

namespace {

std::string lower(std::string text) {
    for (char &c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

/// Edits turning `a` into `b`: insertions, deletions, substitutions and
/// swaps of two neighbours (optimal string alignment distance).
std::size_t edit_distance(const std::string &a, const std::string &b) {
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
    for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= n; ++i)
        for (std::size_t j = 1; j <= m; ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[n][m];
}

/// How many edits still count as a typo of a word of `length` letters: none
/// for one or two (R is not a typo of G), then one per four letters, at most three.
std::size_t typo_budget(std::size_t length) {
    return length <= 2 ? 0 : std::min<std::size_t>(3, (length + 3) / 4);
}

}  // namespace

std::optional<std::string> closest_match(const std::string &word,
                                         const std::vector<std::string> &candidates) {
    const std::string folded = lower(word);
    for (const std::string &candidate : candidates)
        if (lower(candidate) == folded) return candidate;
    for (const std::string &candidate : candidates) {
        const std::string tail = "." + folded, name = lower(candidate);
        if (name.size() > tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0)
            return candidate;
    }
    std::optional<std::string> best;
    std::size_t best_distance = typo_budget(word.size()) + 1;
    for (const std::string &candidate : candidates) {
        const std::size_t distance = edit_distance(folded, lower(candidate));
        if (distance < best_distance) {
            best = candidate;
            best_distance = distance;
        }
    }
    return best;
}

std::string did_you_mean(const std::string &word, const std::vector<std::string> &candidates) {
    const std::optional<std::string> match = closest_match(word, candidates);
    return match ? "; did you mean '" + *match + "'?" : std::string();
}

}  // namespace aaf::cli
