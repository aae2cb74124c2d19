// libFuzzer harness: the option values a user types. The first byte picks
// the parser: a `--frames` range (aaf::io::FrameRange, used as the commands
// use it before the first frame: its size and first frame), or a
// `name=value` method parameter set on each registered method's
// ParameterSet. Either parses or throws aaf::Error; a range never needs more
// memory than libFuzzer's -malloc_limit_mb.
#include <cstdint>
#include <string>

#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/io/sequence.h"

namespace {

void set_parameter(const std::string &text) {
    const std::size_t equals = text.find('=');
    const std::string name = text.substr(0, equals);
    const std::string value = equals == std::string::npos ? std::string() : text.substr(equals + 1);
    for (const aaf::Method *method : aaf::methods()) {
        aaf::ParameterSet parameters = method->default_parameters();
        try {
            parameters.set(name, value);
            (void)parameters.text(name);
        } catch (const aaf::Error &) {
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    if (size == 0) return 0;
    const std::string text(reinterpret_cast<const char *>(data) + 1, size - 1);
    if (data[0] % 2 == 0) {
        try {
            // What a command does before its first frame: the count for progress, the first frame.
            const aaf::io::FrameRange range = aaf::io::FrameRange::parse(text);
            (void)range.size();
            if (!range.empty()) (void)range.contains(range.front());
        } catch (const aaf::Error &) {
        }
    } else {
        set_parameter(text);
    }
    return 0;
}
