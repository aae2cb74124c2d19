#include <catch2/catch.hpp>

#include "aaf/core/aaf_filter.h"
#include "aaf/core/error_metrics.h"
#include "aaf/trace/render.h"

using namespace aaf;

// The whole slice at small size: 9 spp render, AAF, and a 2048 spp reference.
TEST_CASE("AAF halves the error of a 9 spp render of grids", "[integration]") {
    trace::RenderSettings settings;
    settings.width = 96;
    settings.height = 72;
    settings.spp = 9;
    settings.seed = 1;
    const AovSet noisy = trace::render_builtin("grids", settings);
    settings.spp = 2048;
    settings.seed = 2;  // independent of the noisy render
    const AovSet reference = trace::render_builtin("grids", settings);

    const AovSet filtered = aaf_filter_aovs(noisy, ChannelMap{}, AafParams{});
    const std::vector<std::string> rgb{"R", "G", "B"};
    const double unfiltered_rmse = compare_channels(noisy, reference, rgb).rmse;
    const double filtered_rmse = compare_channels(filtered, reference, rgb).rmse;
    INFO("unfiltered RMSE " << unfiltered_rmse << ", filtered RMSE " << filtered_rmse);
    CHECK(unfiltered_rmse > 0.01);  // the scene really has noisy soft shadows
    CHECK(filtered_rmse < 0.5 * unfiltered_rmse);
}
