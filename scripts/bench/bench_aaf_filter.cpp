// AAF filter cost against a fixed-width separable Gaussian on the same
// 640x480 render of `grids` (9 spp). Run: ./scripts/bench.sh
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "aaf/core/aaf_filter.h"
#include "aaf/core/fixed_gaussian.h"
#include "aaf/trace/render.h"

namespace {

const aaf::AovSet &scene() {
    static const aaf::AovSet aovs = [] {
        aaf::trace::RenderSettings settings;
        settings.spp = 9;
        return aaf::trace::render_builtin("grids", settings);
    }();
    return aovs;
}

void BM_AafFilter(benchmark::State &state) {
    const aaf::AovSet &aovs = scene();
    for (auto _ : state) {
        aaf::AovSet out = aaf::aaf_filter_aovs(aovs, aaf::ChannelMap{}, aaf::AafParams{});
        benchmark::DoNotOptimize(out.channel("aaf.V").data);
    }
    state.SetItemsProcessed(state.iterations() * int64_t(aovs.pixel_count()));
}

/// The fixed Gaussian gets the median AAF tap radius of the filtered pixels,
/// so both filters touch about as many taps.
void BM_FixedGaussian(benchmark::State &state) {
    const aaf::AovSet &aovs = scene();
    const aaf::AovSet filtered = aaf::aaf_filter_aovs(aovs, aaf::ChannelMap{}, aaf::AafParams{});
    std::vector<float> radii;
    const aaf::ConstPlaneView beta = filtered.channel("aaf.beta"), size = aovs.channel("pixel.size");
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x)
            if (beta(x, y) > 0) radii.push_back(beta(x, y) / size(x, y));
    std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
    const float sigma_px = radii[radii.size() / 2];
    state.counters["sigma_px"] = sigma_px;
    std::vector<float> out(aovs.pixel_count());
    for (auto _ : state) {
        aaf::fixed_gaussian_filter(aovs.channel("shadow.V"),
                                   sigma_px, aaf::plane_view(out.data(), aovs.width(), aovs.height()));
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * int64_t(aovs.pixel_count()));
}

}  // namespace

BENCHMARK(BM_AafFilter)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FixedGaussian)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
