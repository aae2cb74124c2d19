// libFuzzer harness: the EXR AOV reader on arbitrary file bytes. The promise
// under test: any file either reads or throws aaf::Error (one line naming
// the file); never a crash, a sanitizer report, another exception type or an
// allocation beyond libFuzzer's -malloc_limit_mb.
#include <cstdint>

#include <OpenImageIO/imageio.h>

#include "aaf/core/util/error.h"
#include "aaf/io/exr_io.h"
#include "fuzz_temp_file.h"

// One thread in OpenImageIO (other formats) and OpenEXR: a pool per tiny
// file costs more than the file, and libFuzzer runs one input at a time anyway.
extern "C" int LLVMFuzzerInitialize(int *, char ***) {
    OIIO::attribute("threads", 1);
    aaf::io::set_io_threads(1);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    const aaf::fuzz::TempFile file(".exr", data, size);
    try {
        aaf::io::ImageLayout layout;
        const aaf::AovSet aovs = aaf::io::read_aovs(file.path(), &layout);
        (void)aovs.channel_names();
    } catch (const aaf::Error &) {
    }
    return 0;
}
