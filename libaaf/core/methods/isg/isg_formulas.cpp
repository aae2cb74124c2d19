// ISG's shared formulas and sample sets (aaf/core/methods/isg/isg_formulas.h).
#include <cmath>
#include <cstdint>
#include <limits>

#include "aaf/core/math/concentric_disc.h"
#include "aaf/core/methods/isg/isg_formulas.h"
#include "aaf/core/util/error.h"

namespace aaf::isg {

namespace {

/// A fixed jitter in [-0.5, 0.5) from a cell index (SplitMix64's finaliser).
float hashed_jitter(std::uint64_t key) {
    key += 0x9e3779b97f4a7c15ull;
    key = (key ^ (key >> 30)) * 0xbf58476d1ce4e5b9ull;
    key = (key ^ (key >> 27)) * 0x94d049bb133111ebull;
    key ^= key >> 31;
    return float(key >> 40) * 0x1p-24f - 0.5f;
}

}  // namespace

std::vector<Tap> tap_set(int count, TapShape shape, TapPattern pattern, float half_width, float half_height) {
    const int k = int(std::lround(std::sqrt(double(count))));
    if (count < 1 || k * k != count || k % 2 == 0)
        throw Error("an ISG sample count must be the square of an odd number (1, 9, 25, 49, 81, ...), not " +
                    std::to_string(count));
    if (!(half_width > 0) || !(half_height > 0)) throw Error("an ISG sample rectangle needs a positive size");
    const float scale = std::max(half_width, half_height);
    std::vector<Tap> taps = {{0, 0}};  // the centre first (ISG Eq. 4 sums from i = 0)
    for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
            if (i == k / 2 && j == k / 2) continue;
            float u = float(i) + 0.5f, v = float(j) + 0.5f;
            if (pattern == TapPattern::Stratified) {
                const std::uint64_t cell = std::uint64_t(j) * 1024u + std::uint64_t(i);
                u += hashed_jitter(2 * cell);
                v += hashed_jitter(2 * cell + 1);
            }
            const float a = 2 * u / float(k) - 1, b = 2 * v / float(k) - 1;  // [-1, 1]^2
            if (shape == TapShape::Disk) {
                const DiscPoint d = concentric_disc(a, b);
                taps.push_back({d.x, d.y});
            } else {
                taps.push_back({a * half_width / scale, b * half_height / scale});
            }
        }
    return taps;
}

float penumbra_radius_m(float light_size_m, float occluder_distance_m, float light_distance_m) {
    const float gap_m = light_distance_m - occluder_distance_m;
    if (!(gap_m > 0)) return std::numeric_limits<float>::infinity();
    return light_size_m * occluder_distance_m / gap_m;  // ISG Eq. 8
}

float screen_radius_px(float length_m, float z_eye_m, float focal_px) {
    return length_m / z_eye_m * focal_px;  // ISG Eq. 5, 9 (texture units times the image's focal length)
}

float glossy_gather_angle(float theta_max_rad, float eye_distance_m, float reflected_distance_m) {
    if (std::isinf(reflected_distance_m)) return theta_max_rad;
    // ISG Eq. 13
    return std::atan(reflected_distance_m * std::tan(theta_max_rad) /
                     (eye_distance_m + reflected_distance_m));
}

float circle_of_confusion_px(float depth_m, float focus_depth_m, float coc_at_infinity_px) {
    if (std::isinf(depth_m)) return coc_at_infinity_px;
    return std::fabs(depth_m - focus_depth_m) / depth_m * coc_at_infinity_px;  // ISG Eq. 15
}

float smoothstep(float width, float x) {
    if (!(width > 0)) return x > 0 ? 1.0f : 0.0f;
    const float t = std::min(1.0f, std::max(0.0f, x / width));
    return t * t * (3 - 2 * t);
}

}  // namespace aaf::isg
