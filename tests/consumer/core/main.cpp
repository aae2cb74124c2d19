// Calls the installed core's baseline filter on small hand-built planes.
#include <cmath>
#include <cstdio>
#include <vector>

#include "aaf/core/contract/plane_view.h"
#include "aaf/core/kernels/fixed_gaussian.h"

namespace {

int failures = 0;

void check(bool ok, const char *what) {
    if (!ok) {
        std::fprintf(stderr, "core_consumer: FAILED: %s\n", what);
        ++failures;
    }
}

}  // namespace

int main() {
    constexpr int kWidth = 24, kHeight = 24;
    const float sigma_px = 1.5f;  // cut at 3 sigma: 5 px

    // A constant image is unchanged (the kernel is renormalised at the borders).
    std::vector<float> constant(kWidth * kHeight, 2.0f), out(kWidth * kHeight, -1.0f);
    aaf::fixed_gaussian_filter(aaf::plane_view<const float>(constant.data(), kWidth, kHeight), sigma_px,
                               aaf::plane_view(out.data(), kWidth, kHeight));
    bool all_two = true;
    for (float v : out) all_two = all_two && std::fabs(v - 2.0f) < 1e-5f;
    check(all_two, "a constant image is unchanged");

    // An impulse keeps its sum, spreads, and stays symmetric: at (12, 12) it
    // reaches pixels 7..17, whose windows (2..22) are not cut by the borders.
    constexpr int kCentre = 12;
    std::vector<float> impulse(kWidth * kHeight, 0.0f);
    impulse[kCentre * kWidth + kCentre] = 1.0f;
    aaf::fixed_gaussian_filter(aaf::plane_view<const float>(impulse.data(), kWidth, kHeight), sigma_px,
                               aaf::plane_view(out.data(), kWidth, kHeight));
    double sum = 0;
    for (float v : out) sum += v;
    check(std::fabs(sum - 1.0) < 1e-5, "an impulse keeps its sum");
    const float centre = out[kCentre * kWidth + kCentre];
    check(centre > 0.0f && centre < 0.5f, "an impulse is spread");
    check(out[kCentre * kWidth + kCentre - 1] == out[kCentre * kWidth + kCentre + 1] &&
              out[(kCentre - 1) * kWidth + kCentre] == out[(kCentre + 1) * kWidth + kCentre],
          "the blur is symmetric");
    check(out[0] == 0.0f, "nothing reaches past 3 sigma");

    if (failures != 0) return 1;
    std::printf("core_consumer: ok (centre %.6f, sum %.6f)\n", centre, sum);
    return 0;
}
