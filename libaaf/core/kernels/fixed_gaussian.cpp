#include "aaf/core/kernels/fixed_gaussian.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

void fixed_gaussian_filter(ConstPlaneView input, float sigma_px, PlaneView output) {
    if (input.width != output.width || input.height != output.height)
        throw Error("fixed Gaussian: input and output sizes differ");
    if (!(sigma_px >= 0)) throw Error("fixed Gaussian: sigma must be >= 0 pixels");
    const int width = input.width, height = input.height;
    const int radius = int(std::ceil(3.0f * sigma_px));
    std::vector<float> weights(std::size_t(radius) + 1, 1.0f);
    for (int i = 1; i <= radius; ++i) weights[i] = std::exp(-0.5f * i * i / (sigma_px * sigma_px));

    std::vector<float> vertical(std::size_t(width) * height);
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            double sum = 0, weight_sum = 0;
            for (int ty = std::max(0, y - radius); ty <= std::min(height - 1, y + radius); ++ty) {
                sum += double(weights[std::abs(ty - y)]) * input(x, ty);
                weight_sum += weights[std::abs(ty - y)];
            }
            vertical[std::size_t(y) * width + x] = float(sum / weight_sum);
        }
    });
    parallel_for_rows(height, [&](int y) {
        const float *row = vertical.data() + std::size_t(y) * width;
        for (int x = 0; x < width; ++x) {
            double sum = 0, weight_sum = 0;
            for (int tx = std::max(0, x - radius); tx <= std::min(width - 1, x + radius); ++tx) {
                sum += double(weights[std::abs(tx - x)]) * row[tx];
                weight_sum += weights[std::abs(tx - x)];
            }
            output(x, y) = float(sum / weight_sum);
        }
    });
}

}  // namespace aaf
