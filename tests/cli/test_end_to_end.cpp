#include <catch2/catch.hpp>

#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/metrics/error_metrics.h"
#include "aaf/trace/render.h"
#include "grids_closeup.h"
#include "run_aaf.h"

using namespace aaf;

// The whole slice at 96x72: 9 spp render, AAF, and a 2048 spp reference.
// AAF's beta is a world-space width (Eq. 13), so its reach in pixels depends on
// how much world a pixel covers: with grids' own wide view at 96x72 a pixel
// spans ~0.12 m, more than most penumbrae, and AAF rightly leaves them nearly
// unfiltered (measured RMSE 0.034 -> 0.029). So the test looks at grids'
// penumbrae through a 7 degree lens (pixels of ~1 cm, as the 640x480 demo's),
// where the filter has room to work (measured 0.069 -> 0.022).
TEST_CASE("AAF halves the error of a 9 spp render of grids at 96x72", "[integration]") {
    const std::string scene_path = aaf_test::write_grids_closeup(aaf_test::scratch_dir("end_to_end"));

    trace::RenderSettings settings;
    settings.width = 96;
    settings.height = 72;
    settings.spp = 9;
    settings.seed = 1;
    const AovSet noisy = trace::render_scene(scene_path, settings);
    settings.spp = 2048;
    settings.seed = 2;  // independent of the noisy render
    const AovSet reference = trace::render_scene(scene_path, settings);

    const AovSet filtered = aaf_filter_aovs(noisy, ChannelMap{}, AafParams{});
    const std::vector<std::string> rgb{"R", "G", "B"};
    const double unfiltered_rmse = compare_channels(noisy, reference, rgb).rmse;
    const double filtered_rmse = compare_channels(filtered, reference, rgb).rmse;
    INFO("unfiltered RMSE " << unfiltered_rmse << ", filtered RMSE " << filtered_rmse);
    CHECK(unfiltered_rmse > 0.03);  // the view really is full of noisy soft shadows
    CHECK(filtered_rmse < 0.5 * unfiltered_rmse);
}
