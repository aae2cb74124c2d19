#include "aaf/core/kernels/fixed_gaussian.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "aaf/core/kernels/fixed_gaussian_rows.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/frame_allocator.h"
#include "aaf/core/util/parallel.h"
#include "aaf/core/util/plane_rows.h"

namespace aaf {

namespace {

/// The sum of the weights of taps [centre - below, centre + above], taken
/// in the taps' order, as each pixel's own sum adds them.
double window_weight(const std::vector<float> &weights, int below, int above) {
    double sum = 0;
    for (int offset = -below; offset <= above; ++offset) sum += weights[std::size_t(std::abs(offset))];
    return sum;
}

}  // namespace

void fixed_gaussian_filter(ConstPlaneView input, float sigma_px, PlaneView output) {
    if (input.width != output.width || input.height != output.height)
        throw Error("fixed Gaussian: input and output sizes differ");
    if (!(sigma_px >= 0)) throw Error("fixed Gaussian: sigma must be >= 0 pixels");
    const int width = input.width, height = input.height;
    const int radius = int(std::ceil(3.0f * sigma_px));
    std::vector<float> weights(std::size_t(radius) + 1, 1.0f);
    for (int i = 1; i <= radius; ++i) weights[i] = std::exp(-0.5f * i * i / (sigma_px * sigma_px));

    // Each pixel's sums run over its taps in order, in double, one add at a
    // time; the loops below keep that order per pixel while neighbouring
    // pixels share vector lanes, so the result is that of a pixel-by-pixel loop.
    FramePlane<float> vertical(std::size_t(width) * std::size_t(height));
    parallel_for_rows(height, [&](int y) {
        const int first = std::max(0, y - radius), last = std::min(height - 1, y + radius);
        std::vector<double> sum(static_cast<std::size_t>(width)), tap_weights;
        std::vector<const float *> rows;
        std::vector<std::vector<float>> buffers(std::size_t(last - first + 1));
        for (int ty = first; ty <= last; ++ty) {
            tap_weights.push_back(weights[std::size_t(std::abs(ty - y))]);
            rows.push_back(contiguous_row(input, ty, buffers[std::size_t(ty - first)]));
        }
        detail::gaussian_taps(rows.data(), tap_weights.data(), int(rows.size()), sum.data(), width);
        const double weight_sum = window_weight(weights, y - first, last - y);
        float *const out = vertical.data() + std::size_t(y) * std::size_t(width);
        for (int x = 0; x < width; ++x) out[x] = float(sum[std::size_t(x)] / weight_sum);
    });
    // Along the row: pixels whose window lies inside it in lanes, the few at its ends one by one.
    const int inner_begin = std::min(radius, width), inner_end = std::max(inner_begin, width - radius);
    const double inner_weight_sum = window_weight(weights, radius, radius);
    parallel_for_rows(height, [&](int y) {
        const float *const row = vertical.data() + std::size_t(y) * std::size_t(width);
        std::vector<double> sum(static_cast<std::size_t>(width)), tap_weights;
        std::vector<const float *> rows;
        for (int offset = -radius; offset <= radius; ++offset) {
            tap_weights.push_back(weights[std::size_t(std::abs(offset))]);
            rows.push_back(row + inner_begin + offset);
        }
        detail::gaussian_taps(rows.data(), tap_weights.data(), int(rows.size()), sum.data() + inner_begin,
                              inner_end - inner_begin);
        if (output.pixel_stride == 1) {
            float *const out = &output(0, y);
            for (int x = inner_begin; x < inner_end; ++x)
                out[x] = float(sum[std::size_t(x)] / inner_weight_sum);
        } else {
            for (int x = inner_begin; x < inner_end; ++x)
                output(x, y) = float(sum[std::size_t(x)] / inner_weight_sum);
        }
        for (int x = 0; x < width; ++x) {
            if (x >= inner_begin && x < inner_end) continue;
            const int first = std::max(0, x - radius), last = std::min(width - 1, x + radius);
            double edge_sum = 0;
            for (int tx = first; tx <= last; ++tx)
                edge_sum += double(weights[std::size_t(std::abs(tx - x))]) * row[tx];
            output(x, y) = float(edge_sum / window_weight(weights, x - first, last - x));
        }
    });
}

}  // namespace aaf
