#include "compare_pairs.h"

#include <algorithm>
#include <filesystem>
#include <set>
#include <utility>

#include "aaf/core/util/error.h"
#include "aaf/io/sequence.h"
#include "commands.h"
#include "frame_runner.h"

namespace aaf::cli {

namespace fs = std::filesystem;

io::ImagePairs compare_pairs(const std::string &test, const std::string &reference,
                             const std::optional<std::string> &frames, std::vector<std::string> *unmatched) {
    const bool test_sequence = io::is_sequence_pattern(test),
               reference_sequence = io::is_sequence_pattern(reference);
    if (test_sequence || reference_sequence) {
        if (!(test_sequence && reference_sequence))
            throw UsageError(test + " vs " + reference +
                             ": compare two sequence patterns or two files, not one of each");
        io::FrameRange range = sequence_frames(test, frames);
        const std::size_t count = range.size();
        return io::ImagePairs(count, [range = std::move(range), test,
                                      reference](const io::ImagePairs::Visit &visit) {
            range.for_each([&](int frame) {
                visit({std::to_string(frame), io::frame_path(test, frame), io::frame_path(reference, frame)});
            });
        });
    }
    if (frames) throw UsageError("--frames needs sequence patterns (e.g. test.####.exr ref.####.exr)");
    std::error_code ec;
    const bool test_dir = fs::is_directory(test, ec), reference_dir = fs::is_directory(reference, ec);
    if (test_dir != reference_dir)
        throw UsageError(test + " vs " + reference +
                         ": compare two directories or two files, not one of each");
    if (!test_dir) return {{fs::path(test).filename().string(), test, reference}};

    std::vector<ImagePair> pairs;
    std::set<std::string> reference_names;
    for (const auto &entry : fs::directory_iterator(reference, ec))
        if (entry.is_regular_file()) reference_names.insert(entry.path().filename().string());
    std::set<std::string> test_names;
    for (const auto &entry : fs::directory_iterator(test, ec)) {
        const std::string name = entry.path().filename().string();
        if (!entry.is_regular_file()) continue;
        test_names.insert(name);
        if (reference_names.count(name))
            pairs.push_back({name, entry.path().string(), (fs::path(reference) / name).string()});
    }
    if (ec) throw InputError(test + ": cannot list the directory: " + ec.message());
    // Sets iterate in name order: the list does not depend on the directory's order.
    if (unmatched) {
        for (const std::string &name : test_names)
            if (!reference_names.count(name)) unmatched->push_back((fs::path(test) / name).string());
        for (const std::string &name : reference_names)
            if (!test_names.count(name)) unmatched->push_back((fs::path(reference) / name).string());
    }
    if (pairs.empty()) throw InputError(test + " vs " + reference + ": no file names in common");
    std::sort(pairs.begin(), pairs.end(),
              [](const ImagePair &a, const ImagePair &b) { return a.label < b.label; });
    return pairs;
}

bool is_batch_input(const std::string &test) {
    std::error_code ec;
    return io::is_sequence_pattern(test) || fs::is_directory(test, ec);
}

}  // namespace aaf::cli
