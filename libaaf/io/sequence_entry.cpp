// The entry point of the aaf_sequences module (sequence_module.h): OpenImageIO's
// utility library alone, no image formats.
#include <OpenImageIO/filesystem.h>

#include "sequence_module.h"

namespace aaf::io {

namespace {

bool parse_pattern(const std::string &file_pattern, int padding, std::string &normalized) {
    std::string framespec;
    return OIIO::Filesystem::parse_pattern(file_pattern.c_str(), padding, normalized, framespec);
}

bool frame_file_name(const std::string &normalized, int frame, std::string &name) {
    std::vector<std::string> names;
    if (!OIIO::Filesystem::enumerate_file_sequence(normalized, {frame}, names) || names.empty()) return false;
    name = names.front();
    return true;
}

bool scan_for_matching_filenames(const std::string &normalized, std::vector<int> &numbers,
                                 std::vector<std::string> &names) {
    return OIIO::Filesystem::scan_for_matching_filenames(normalized, numbers, names);
}

const SequenceModule kModule = {parse_pattern, frame_file_name, scan_for_matching_filenames};

}  // namespace

}  // namespace aaf::io

extern "C" __attribute__((visibility("default"))) const aaf::io::SequenceModule *AAF_SEQUENCES_ENTRY() {
    return &aaf::io::kModule;
}
