#include "image_writer.h"

#include <cstdio>
#include <memory>

#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "one_line.h"

namespace aaf::io {

void write_image_atomically(const std::string &path, const char *format, const OIIO::ImageSpec &spec,
                            const float *pixels) {
    const std::string temporary = temporary_path_for(path);
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(format);
    if (!output) throw InputError(path + ": no " + format + " writer: " + one_line(OIIO::geterror()));
    bool ok = output->open(temporary, spec) && output->write_image(OIIO::TypeDesc::FLOAT, pixels);
    ok = output->close() && ok;
    if (!ok) {
        const std::string message = one_line(output->geterror());
        discard_temporary(temporary);
        throw InputError(path + ": cannot write: " + message);
    }
    commit_temporary(temporary, path);
}

}  // namespace aaf::io
