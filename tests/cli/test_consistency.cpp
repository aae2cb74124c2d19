#include <catch2/catch.hpp>

#include <sstream>
#include <vector>

#include "aaf/core/aaf_filter.h"
#include "aaf/core/error_metrics.h"
#include "aaf/core/fixed_gaussian.h"
#include "aaf/trace/render.h"

using namespace aaf;

namespace {

/// RMSE of the beauty r(x) * `visibility` against the reference's R,G,B.
double beauty_rmse(const AovSet &noisy, const std::vector<float> &visibility, const AovSet &reference) {
    AovSet test(noisy.width(), noisy.height());
    for (const char *c : {"R", "G", "B"}) {
        ConstPlaneView r = noisy.channel(std::string("unshadowed.") + c);
        PlaneView out = test.add_channel(c);
        for (int y = 0; y < noisy.height(); ++y)
            for (int x = 0; x < noisy.width(); ++x) out(x, y) = r(x, y) * visibility[std::size_t(y) * noisy.width() + x];
    }
    return compare_channels(test, reference, {"R", "G", "B"}).rmse;
}

}  // namespace

// AAF Sec. 5.2 and Fig. 6(c): with mu following the samples taken, the filtered
// error keeps falling as spp grows (the filter narrows towards one pixel); a
// fixed-width Gaussian's error flattens out at its blurring bias.
TEST_CASE("AAF error decreases monotonically with spp; a fixed-width filter's stalls", "[integration][consistency]") {
    trace::RenderSettings settings;
    settings.width = 160;
    settings.height = 120;
    settings.spp = 2048;
    settings.seed = 99;
    const AovSet reference = trace::render_builtin("grids", settings);

    AafParams params;
    params.mu_from_spp = true;
    std::vector<double> aaf_error, fixed_error, unfiltered_error;
    for (int spp : {9, 36, 144, 576}) {
        settings.spp = spp;
        settings.seed = 1;
        const AovSet noisy = trace::render_builtin("grids", settings);
        const AovSet filtered = aaf_filter_aovs(noisy, ChannelMap{}, params);
        aaf_error.push_back(compare_channels(filtered, reference, {"R", "G", "B"}).rmse);
        unfiltered_error.push_back(compare_channels(noisy, reference, {"R", "G", "B"}).rmse);
        std::vector<float> blurred(noisy.pixel_count());
        fixed_gaussian_filter(noisy.channel("shadow.V"), 1.5f,
                              plane_view(blurred.data(), noisy.width(), noisy.height()));
        fixed_error.push_back(beauty_rmse(noisy, blurred, reference));
    }
    std::ostringstream table;
    for (std::size_t i = 0; i < aaf_error.size(); ++i)
        table << "step " << i << ": unfiltered " << unfiltered_error[i] << ", AAF " << aaf_error[i] << ", fixed "
              << fixed_error[i] << "\n";
    INFO(table.str());
    for (std::size_t i = 1; i < aaf_error.size(); ++i) CHECK(aaf_error[i] < aaf_error[i - 1]);
    for (std::size_t i = 0; i < aaf_error.size(); ++i) CHECK(aaf_error[i] <= unfiltered_error[i]);
    // The fixed filter gains less than 10% from 144 to 576 spp while AAF keeps improving.
    CHECK(fixed_error[3] > 0.9 * fixed_error[2]);
    CHECK(aaf_error[3] < fixed_error[3]);
}
