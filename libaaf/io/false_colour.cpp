#include "false_colour.h"

#include <algorithm>

#include "image_writer.h"

namespace aaf::io {

Vec3 false_colour(float t) {
    static const Vec3 stops[] = {{0.05f, 0.05f, 0.45f},
                                 {0.0f, 0.55f, 0.95f},
                                 {0.1f, 0.85f, 0.3f},
                                 {0.98f, 0.9f, 0.1f},
                                 {0.85f, 0.1f, 0.05f}};
    constexpr int kIntervals = 4;
    const float position = std::clamp(t, 0.0f, 1.0f) * kIntervals;
    const int i = std::min(int(position), kIntervals - 1);
    const float f = position - float(i);
    return stops[i] * (1 - f) + stops[i + 1] * f;
}

void write_png(const std::vector<float> &rgb, int width, int height, const std::string &path) {
    write_image_atomically(path, "png", OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8), rgb.data());
}

}  // namespace aaf::io
