// The entry point of the aaf_formats module (formats_module.h).
#include "formats_module.h"

namespace aaf::io {

namespace {

const FormatsModule kModule = {
    read_other_image,
    is_readable_other_image,
    read_other_string_attribute,
    formats::check_display_view,
    formats::write_preview_png,
    formats::write_false_colour_png,
    formats::write_error_heatmap,
};

}  // namespace

}  // namespace aaf::io

extern "C" __attribute__((visibility("default"))) const aaf::io::FormatsModule *AAF_FORMATS_ENTRY() {
    return &aaf::io::kModule;
}
