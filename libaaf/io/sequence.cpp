#include "aaf/io/sequence.h"

#include <cstdint>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <mutex>
#include <regex>

#include "aaf/core/util/error.h"
#include "module_loader.h"
#include "sequence_module.h"

namespace aaf::io {

namespace {

/// Where the frame field of a pattern sits: [begin, end) and its padding.
struct FrameField {
    std::size_t begin = std::string::npos, end = 0;
    int padding = 0;
};

/// Where the file name starts: the frame field is looked for there only, so
/// folders named "v@2" or "take#3" are folders, not frame numbers.
std::size_t file_name_start(const std::string &pattern) {
    const std::size_t slash = pattern.find_last_of('/');
    return slash == std::string::npos ? 0 : slash + 1;
}

FrameField find_field(const std::string &pattern) {
    FrameField field;
    const std::size_t name = file_name_start(pattern);
    const std::size_t hash = pattern.find_first_of("#@", name);
    if (hash != std::string::npos) {
        std::size_t end = hash;
        while (end < pattern.size() && pattern[end] == pattern[hash]) ++end;
        return {hash, end, int(end - hash)};
    }
    static const std::regex printf_field("%(0?)([0-9]*)d");
    std::smatch match;
    const std::string file = pattern.substr(name);
    if (std::regex_search(file, match, printf_field)) {
        field.begin = name + std::size_t(match.position(0));
        field.end = field.begin + std::size_t(match.length(0));
        field.padding = match[2].length() ? std::stoi(match[2].str()) : 0;
    }
    return field;
}

/// The file-name part of the pattern in OpenImageIO's normalised printf form,
/// with this project's padding rule: a run of n '#' or '@' is n digits (OIIO's
/// own '#' is 4). The folder part is returned apart, untouched.
std::pair<std::string, std::string> normalized_pattern(const std::string &pattern) {
    const FrameField field = find_field(pattern);
    if (field.begin == std::string::npos)
        throw Error(pattern + ": no frame field (#, @ or %0Nd) in the file name of the pattern");
    const bool hashes = pattern[field.begin] == '#' || pattern[field.begin] == '@';
    const std::size_t name = file_name_start(pattern);
    std::string normalized;
    if (!sequence_module().parse_pattern(pattern.substr(name), hashes ? field.padding : 0, normalized) ||
        normalized.empty())
        throw Error(pattern + ": cannot read the frame field of the pattern");
    return {pattern.substr(0, name), normalized};
}

int parse_int(const std::string &text, const std::string &spec) {
    if (text.empty() || !std::all_of(text.begin() + (text[0] == '-' ? 1 : 0), text.end(), ::isdigit) ||
        text == "-")
        throw Error("bad frame range '" + spec + "': '" + text + "' is not a frame number");
    long long value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value < std::numeric_limits<int>::min() ||
        value > std::numeric_limits<int>::max())
        throw Error("bad frame range '" + spec + "': frame " + text + " is out of range (" +
                    std::to_string(std::numeric_limits<int>::min()) + " to " +
                    std::to_string(std::numeric_limits<int>::max()) + ")");
    return int(value);
}

/// One comma-separated item, first[-last[(x|:)step]]; a '-' after position 0
/// separates first and last.
FrameRange::Item parse_item(const std::string &part, const std::string &spec) {
    if (part.empty()) throw Error("bad frame range '" + spec + "': empty item");
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
    return {first, last, step};
}

/// True when no two items' [first, last] spans overlap.
bool spans_disjoint(std::vector<FrameRange::Item> items) {
    std::sort(items.begin(), items.end(),
              [](const FrameRange::Item &a, const FrameRange::Item &b) { return a.first < b.first; });
    for (std::size_t i = 1; i < items.size(); ++i)
        if (items[i].first <= items[i - 1].last) return false;
    return true;
}

}  // namespace

const SequenceModule &sequence_module() {
    static std::mutex mutex;
    static const SequenceModule *module = nullptr;
    const std::lock_guard<std::mutex> lock(mutex);
    if (!module)  // a failure is reported again on the next call
        module = static_cast<const SequenceModule *>(
            load_module_table("libaaf_sequences.so", AAF_SEQUENCES_ENTRY_NAME,
                              "file sequences (OpenImageIO's frame patterns)"));
    return *module;
}

FrameRange FrameRange::parse(const std::string &spec) {
    FrameRange range;
    std::size_t start = 0;
    while (start <= spec.size()) {
        const std::size_t comma = spec.find(',', start);
        range.items_.push_back(parse_item(
            spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start), spec));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    range.disjoint_ = spans_disjoint(range.items_);
    // Overlapping items are walked frame by frame, each checked against the
    // items before it, to skip repeats: bound that work, so that a spec like
    // "1-2000000000,5" is refused at once instead of counting for minutes.
    constexpr double kMaxOverlapWork = 2e8;
    double frames = 0;
    for (const Item &item : range.items_) frames += (double(item.last) - item.first) / item.step + 1;
    if (!range.disjoint_ && frames * double(range.items_.size()) > kMaxOverlapWork)
        throw Error("bad frame range '" + spec +
                    "': its items overlap over too many frames to skip the repeats (list each frame once)");
    return range;
}

FrameRange FrameRange::of(const std::vector<int> &frames) {
    FrameRange range;
    for (int frame : frames) range.items_.push_back({frame, frame, 1});
    range.disjoint_ = spans_disjoint(range.items_);
    return range;
}

bool FrameRange::contains(int frame) const {
    for (const Item &item : items_)
        if (frame >= item.first && frame <= item.last && (std::int64_t(frame) - item.first) % item.step == 0)
            return true;
    return false;
}

bool FrameRange::given_before(std::size_t item, int frame) const {
    for (std::size_t i = 0; i < item; ++i) {
        const Item &earlier = items_[i];
        if (frame >= earlier.first && frame <= earlier.last &&
            (static_cast<long long>(frame) - earlier.first) % earlier.step == 0)
            return true;
    }
    return false;
}

std::size_t FrameRange::size() const {
    std::size_t count = 0;
    if (disjoint_) {
        for (const Item &item : items_)
            count += std::size_t((static_cast<long long>(item.last) - item.first) / item.step + 1);
    } else {
        for_each([&count](int) { ++count; });
    }
    return count;
}

std::vector<int> FrameRange::to_vector() const {
    std::vector<int> frames;
    for_each([&frames](int frame) { frames.push_back(frame); });
    return frames;
}

bool is_sequence_pattern(const std::string &path) {
    return find_field(path).begin != std::string::npos;
}

std::string frame_path(const std::string &pattern, int frame) {
    const auto [directory, file] = normalized_pattern(pattern);
    std::string name;
    if (!sequence_module().frame_file_name(file, frame, name))
        throw Error(pattern + ": cannot make the path of frame " + std::to_string(frame));
    return directory + name;
}

std::vector<int> frames_on_disk(const std::string &pattern) {
    const std::filesystem::path pattern_path(pattern);
    const std::filesystem::path directory = pattern_path.has_parent_path() ? pattern_path.parent_path() : ".";
    std::error_code ec;
    if (!std::filesystem::is_directory(directory, ec))
        throw InputError(directory.string() + ": cannot list the directory: no such directory");
    std::vector<int> numbers;
    std::vector<std::string> names;
    const auto [folder, file] = normalized_pattern(pattern);
    if (!sequence_module().scan_for_matching_filenames(folder + file, numbers, names))
        throw InputError(directory.string() + ": cannot list the directory");
    // OpenImageIO also matches other paddings (shot.7.exr for shot.####.exr); this rule does not.
    std::vector<int> frames;
    for (std::size_t i = 0; i < numbers.size(); ++i)
        if (std::filesystem::path(names[i]).filename() ==
            std::filesystem::path(frame_path(pattern, numbers[i])).filename())
            frames.push_back(numbers[i]);
    std::sort(frames.begin(), frames.end());
    return frames;
}

}  // namespace aaf::io
