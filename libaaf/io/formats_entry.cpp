// The entry point of the aaf_formats module (formats_module.h).
#include <OpenImageIO/filesystem.h>

#include "formats_module.h"

namespace aaf::io {

namespace {

bool parse_pattern(const std::string &pattern, int padding, std::string &normalized, std::string &framespec) {
    return OIIO::Filesystem::parse_pattern(pattern.c_str(), padding, normalized, framespec);
}

bool enumerate_file_sequence(const std::string &pattern, const std::vector<int> &numbers,
                             std::vector<std::string> &names) {
    return OIIO::Filesystem::enumerate_file_sequence(pattern, numbers, names);
}

bool scan_for_matching_filenames(const std::string &pattern, std::vector<int> &numbers,
                                 std::vector<std::string> &names) {
    return OIIO::Filesystem::scan_for_matching_filenames(pattern, numbers, names);
}

const FormatsModule kModule = {
    read_other_image,
    is_readable_other_image,
    read_other_string_attribute,
    formats::check_display_view,
    formats::write_preview_png,
    formats::write_false_colour_png,
    formats::write_error_heatmap,
    parse_pattern,
    enumerate_file_sequence,
    scan_for_matching_filenames,
};

}  // namespace

}  // namespace aaf::io

extern "C" __attribute__((visibility("default"))) const aaf::io::FormatsModule *AAF_FORMATS_ENTRY() {
    return &aaf::io::kModule;
}
