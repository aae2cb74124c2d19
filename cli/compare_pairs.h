#pragma once

#include <optional>
#include <string>
#include <vector>

#include "aaf/io/compare_files.h"

namespace aaf::cli {

using io::ImagePair;

/// The pairs `aaf compare` measures:
/// - two sequence patterns (`test.####.exr ref.####.exr`): the frames of
///   `frames` (a range spec, see io::FrameRange::parse), or else every frame of
///   the test pattern found on disk;
/// - two directories: files of the same name present in both, sorted by name;
///   the files of either directory without a namesake in the other are
///   appended to `unmatched` (when given), the test directory's first, by name;
/// - two files: that one pair.
/// A sequence's pairs are produced one at a time, as compare_files() reads
/// them. Throws aaf::Error when nothing matches or the two arguments are of
/// different kinds, UsageError for a bad or empty `frames` or one given
/// without sequence patterns.
io::ImagePairs compare_pairs(const std::string &test, const std::string &reference,
                             const std::optional<std::string> &frames,
                             std::vector<std::string> *unmatched = nullptr);

/// True when compare_pairs treats `test` as a batch (a sequence pattern or a
/// directory), however many pairs it matches; false for a single file.
bool is_batch_input(const std::string &test);

}  // namespace aaf::cli
