#include "aaf/io/sequence.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <set>

#include "aaf/core/error.h"

namespace aaf::io {

namespace {

/// Where the frame field of a pattern sits: [begin, end) and its padding.
struct FrameField {
    std::size_t begin = std::string::npos, end = 0;
    int padding = 0;
};

FrameField find_field(const std::string &pattern) {
    FrameField field;
    const std::size_t hash = pattern.find_first_of("#@");
    if (hash != std::string::npos) {
        std::size_t end = hash;
        while (end < pattern.size() && pattern[end] == pattern[hash]) ++end;
        return {hash, end, int(end - hash)};
    }
    static const std::regex printf_field("%(0?)([0-9]*)d");
    std::smatch match;
    if (std::regex_search(pattern, match, printf_field)) {
        field.begin = std::size_t(match.position(0));
        field.end = field.begin + std::size_t(match.length(0));
        field.padding = match[2].length() ? std::stoi(match[2].str()) : 0;
    }
    return field;
}

int parse_int(const std::string &text, const std::string &spec) {
    if (text.empty() || !std::all_of(text.begin() + (text[0] == '-' ? 1 : 0), text.end(), ::isdigit) ||
        text == "-")
        throw Error("bad frame range '" + spec + "': '" + text + "' is not a frame number");
    return std::stoi(text);
}

}  // namespace

std::vector<int> parse_frame_range(const std::string &spec) {
    std::vector<int> frames;
    std::set<int> seen;
    std::size_t start = 0;
    while (start <= spec.size()) {
        const std::size_t comma = spec.find(',', start);
        const std::string part =
            spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (part.empty()) throw Error("bad frame range '" + spec + "': empty item");
        // first[-last[(x|:)step]]; a '-' after position 0 separates first and last.
        const std::size_t step_at = part.find_first_of("x:");
        const std::string span = part.substr(0, step_at);
        const int step = step_at == std::string::npos ? 1 : parse_int(part.substr(step_at + 1), spec);
        const std::size_t dash = span.find('-', 1);
        const int first = parse_int(span.substr(0, dash), spec);
        const int last = dash == std::string::npos ? first : parse_int(span.substr(dash + 1), spec);
        if (step <= 0) throw Error("bad frame range '" + spec + "': the step must be positive");
        if (last < first) throw Error("bad frame range '" + spec + "': " + part + " ends before it starts");
        if (dash == std::string::npos && step_at != std::string::npos)
            throw Error("bad frame range '" + spec + "': a step needs a range (first-last)");
        for (int frame = first; frame <= last; frame += step)
            if (seen.insert(frame).second) frames.push_back(frame);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return frames;
}

bool is_sequence_pattern(const std::string &path) {
    return find_field(path).begin != std::string::npos;
}

std::string frame_path(const std::string &pattern, int frame) {
    const FrameField field = find_field(pattern);
    if (field.begin == std::string::npos)
        throw Error(pattern + ": no frame field (#, @ or %0Nd) in the pattern");
    char digits[32];
    std::snprintf(digits, sizeof digits, "%0*d", field.padding, frame);
    return pattern.substr(0, field.begin) + digits + pattern.substr(field.end);
}

std::vector<int> frames_on_disk(const std::string &pattern) {
    const FrameField field = find_field(pattern);
    if (field.begin == std::string::npos)
        throw Error(pattern + ": no frame field (#, @ or %0Nd) in the pattern");
    const std::filesystem::path pattern_path(pattern);
    const std::filesystem::path directory = pattern_path.has_parent_path() ? pattern_path.parent_path() : ".";
    const std::string name = pattern_path.filename().string();
    const FrameField name_field = find_field(name);
    const std::string prefix = name.substr(0, name_field.begin), suffix = name.substr(name_field.end);
    std::vector<int> frames;
    std::error_code ec;
    for (const auto &entry : std::filesystem::directory_iterator(directory, ec)) {
        const std::string candidate = entry.path().filename().string();
        if (candidate.size() <= prefix.size() + suffix.size() ||
            candidate.compare(0, prefix.size(), prefix) != 0 ||
            candidate.compare(candidate.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const std::string number =
            candidate.substr(prefix.size(), candidate.size() - prefix.size() - suffix.size());
        if (!std::all_of(number.begin() + (number[0] == '-' ? 1 : 0), number.end(), ::isdigit) ||
            number == "-")
            continue;
        const int frame = std::stoi(number);
        if (frame_path(name, frame) == candidate) frames.push_back(frame);  // padding must match too
    }
    if (ec) throw Error(directory.string() + ": cannot list the directory: " + ec.message());
    std::sort(frames.begin(), frames.end());
    return frames;
}

}  // namespace aaf::io
