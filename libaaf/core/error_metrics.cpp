#include "aaf/core/error_metrics.h"

#include <cmath>
#include <limits>

#include "aaf/core/error.h"

namespace aaf {

ErrorMetrics compare_channels(const AovSet &test, const AovSet &reference,
                              const std::vector<std::string> &channels) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw Error("image sizes differ: " + std::to_string(test.width()) + "x" +
                    std::to_string(test.height()) + " vs " + std::to_string(reference.width()) + "x" +
                    std::to_string(reference.height()));
    if (channels.empty()) throw Error("no channels to compare");
    ErrorMetrics metrics;
    double sum_sq = 0;
    for (const std::string &name : channels) {
        if (!test.has_channel(name)) throw Error("test image has no channel '" + name + "'");
        if (!reference.has_channel(name)) throw Error("reference image has no channel '" + name + "'");
        ConstPlaneView a = test.channel(name), b = reference.channel(name);
        for (int y = 0; y < test.height(); ++y)
            for (int x = 0; x < test.width(); ++x) {
                const double diff = double(a(x, y)) - double(b(x, y));
                if (!std::isfinite(diff))
                    throw Error("non-finite value in channel '" + name + "' at pixel (" + std::to_string(x) +
                                ", " + std::to_string(y) + ")");
                sum_sq += diff * diff;
            }
    }
    metrics.samples = test.pixel_count() * channels.size();
    metrics.mse = sum_sq / double(metrics.samples);
    metrics.rmse = std::sqrt(metrics.mse);
    metrics.psnr =
        metrics.mse > 0 ? 10.0 * std::log10(1.0 / metrics.mse) : std::numeric_limits<double>::infinity();
    return metrics;
}

}  // namespace aaf
