// libFuzzer harness: the JSON scene loader and the tracer behind it. Any text
// must either render a 2x2 image at 1 spp or throw aaf::Error; never a crash,
// an Embree assertion (non-finite rays) or another exception type.
#include <cstdint>

#include "aaf/core/util/error.h"
#include "aaf/trace/render.h"
#include "fuzz_temp_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    const aaf::fuzz::TempFile file(".json", data, size);
    aaf::trace::RenderSettings settings;
    settings.width = 2;
    settings.height = 2;
    settings.spp = 1;
    settings.threads = 1;
    try {
        (void)aaf::trace::render_scene(file.path(), settings);
    } catch (const aaf::Error &) {
    }
    return 0;
}
