#include "false_colour.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

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
    // The format the name says: JPEG for .jpg/.jpeg, else PNG (callers refuse other names).
    std::string extension = std::filesystem::path(path).extension().string();
    for (char &c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    const char *format = extension == ".jpg" || extension == ".jpeg" ? "jpeg" : "png";
    write_image_atomically(path, format, OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8),
                           rgb.data());
}

}  // namespace aaf::io
