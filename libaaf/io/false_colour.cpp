#include "false_colour.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "aaf/core/error.h"
#include "aaf/io/atomic_file.h"

namespace aaf::io {

Vec3 false_colour(float t) {
    static const Vec3 stops[] = {{0.05f, 0.05f, 0.45f}, {0.0f, 0.55f, 0.95f}, {0.1f, 0.85f, 0.3f},
                                 {0.98f, 0.9f, 0.1f},   {0.85f, 0.1f, 0.05f}};
    constexpr int kIntervals = 4;
    const float position = std::clamp(t, 0.0f, 1.0f) * kIntervals;
    const int i = std::min(int(position), kIntervals - 1);
    const float f = position - float(i);
    return stops[i] * (1 - f) + stops[i + 1] * f;
}

void write_png(const std::vector<float> &rgb, int width, int height, const std::string &path) {
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    const std::string temporary = temporary_path_for(path);
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create("png");
    if (!output) throw Error(path + ": PNG writer unavailable: " + OIIO::geterror());
    bool ok = output->open(temporary, spec) && output->write_image(OIIO::TypeDesc::FLOAT, rgb.data());
    ok = output->close() && ok;
    if (!ok) {
        std::string message = output->geterror();
        std::remove(temporary.c_str());
        throw Error(path + ": cannot write PNG: " + message);
    }
    commit_temporary(temporary, path);
}

}  // namespace aaf::io
