#pragma once

#include <string>
#include <vector>

namespace aaf::io {

/// What the aaf_sequences module does for aaf_io: the frame patterns of file
/// sequences (shot.####.exr) through OpenImageIO's Filesystem functions. It is
/// a shared library of its own, loaded on the first pattern, because
/// OpenImageIO's utility library builds its string table when it is loaded
/// (tens of milliseconds): a one-frame command does not pay for it. The
/// module and the library that loads it come from one build: the table
/// passes C++ types.
struct SequenceModule {
    /// OpenImageIO's parse_pattern: a file name's frame field in printf form.
    bool (*parse_pattern)(const std::string &file_pattern, int padding, std::string &normalized);
    /// The file name of `frame` from a normalised pattern.
    bool (*frame_file_name)(const std::string &normalized, int frame, std::string &name);
    /// The frames on disk that match a normalised pattern (folder included).
    bool (*scan_for_matching_filenames)(const std::string &normalized, std::vector<int> &numbers,
                                        std::vector<std::string> &names);
};

/// The module's entry point, a C symbol: returns its table.
#define AAF_SEQUENCES_ENTRY aaf_sequences_module_v1
#define AAF_SEQUENCES_ENTRY_NAME "aaf_sequences_module_v1"

/// The module's functions, loaded on the first call. Throws aaf::Error naming
/// libaaf_sequences.so when it cannot be loaded.
const SequenceModule &sequence_module();

}  // namespace aaf::io
