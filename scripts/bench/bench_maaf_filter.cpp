// Speed of the MAAF filter (N = 3, 25 filters in 4D) as a ratio to the AAF
// filter and to OpenCV's cv::GaussianBlur, all on the same 9 spp render of
// `grids` with the maaf AOVs, at 640x480 and 1920x1080. Each iteration times
// every filter once, alternately, so the ratios come from one run on one machine:
//   aaf_ms        aaf_filter with default AafParams (separable)
//   maaf_ms       maaf_filter with default MaafParams (separable, k = 3)
//   maaf_k1_ms    the same with k = 1, the paper's widths (3 times wider kernels)
//   opencv_ms     cv::GaussianBlur of one plane (the visibility) at MAAF's mean
//                 central width: what the AAF benchmark compares AAF with
//   opencv_sums_ms the same blur of every plane MAAF reads (2 x 25 sums), the
//                 same bytes through a plain Gaussian of that width
// MAAF's mean central width is the mean over the pixels it filters of the
// p = 0 component's primal std, 1 / (k sigma_x^0) metres (MAAF Eq. 8, 12), in
// pixels of each pixel's footprint, capped like the filter's radius.
// (The full-window variant, --filter 2d, is about 20x slower again and is left
// out: it would take minutes per iteration here.)
// BM_Maaf6VsAaf: the combined-effects filter on a 16 spp render of `room`
// with the maaf6 and aaf AOVs, each method's whole in-memory run
// (filter_aovs, defaults) alternately, on `threads` threads (0: all):
//   aaf_ms, maaf6_ms, maaf6_over_aaf; maaf6_scalar_ms, the same with
//   --filter scalar (one centre at a time in double, the reference).
// Run: ./build/scripts/bench/bench_maaf_filter (see scripts/bench/RESULTS.md).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/methods/maaf/maaf_accumulation.h"
#include "aaf/core/methods/maaf/maaf_components.h"
#include "aaf/core/methods/maaf/maaf_filter.h"
#include "aaf/core/methods/maaf/maaf_roles.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/trace/render.h"

namespace {

struct Fixture {
    aaf::AovSet aovs;
    aaf::AafInputs aaf_inputs;
    aaf::MaafInputs maaf_inputs;
    aaf::LightPlane light;
    double omega_y_max = 0;
    double mean_central_sigma_px = 0;  ///< at the default k (see the header comment)
    cv::Mat visibility;                ///< shadow.V, finite, for OpenCV
    std::vector<cv::Mat> sum_planes;   ///< every plane MAAF reads, finite, for OpenCV
};

/// A tightly packed copy of a plane with non-finite values read as 0.
cv::Mat finite_copy(aaf::ConstPlaneView plane) {
    cv::Mat copy(plane.height, plane.width, CV_32F);
    for (int y = 0; y < plane.height; ++y)
        for (int x = 0; x < plane.width; ++x)
            copy.at<float>(y, x) = std::isfinite(plane(x, y)) ? plane(x, y) : 0.0f;
    return copy;
}

/// The mean over filtered pixels of the central component's primal std in
/// pixels, as maaf_filter sizes it (the p = 0 component, k = MaafParams' default).
double mean_central_sigma_px(const aaf::MaafInputs &m, double omega_y_max) {
    const aaf::MaafParams params;
    double sum = 0;
    long count = 0;
    for (int y = 0; y < m.pixel_size.height; ++y)
        for (int x = 0; x < m.pixel_size.width; ++x) {
            const float s_min = m.s_min(x, y), s_max = m.s_max(x, y), omega_x = m.omega_x_max(x, y);
            const float pixel = m.pixel_size(x, y);
            if (m.object_id(x, y) == 0 || !(omega_x > 0) || !(pixel > 0) || !std::isfinite(pixel) ||
                !(s_min >= 0) || !(s_max >= s_min))
                continue;
            const auto components = aaf::maaf_pair_components(s_min, s_max, omega_x, omega_y_max, m.pairs);
            const double sigma_m = 1.0 / (params.k * components.front().sigma_x);  // MAAF Eq. 12
            sum += std::min(sigma_m / double(pixel), double(params.max_radius_px) / 3.0);
            ++count;
        }
    return count > 0 ? sum / double(count) : 0.0;
}

const Fixture &fixture(int width, int height) {
    static std::map<int, Fixture> cache;
    auto [it, inserted] = cache.try_emplace(width);
    Fixture &f = it->second;
    if (!inserted) return f;
    aaf::trace::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.spp = 9;
    settings.aovs = aaf::trace::aov_groups_for_method("aaf") | aaf::trace::aov_groups_for_method("maaf");
    f.aovs = aaf::trace::render_scene("grids", settings);
    const aaf::AovSet &a = f.aovs;
    f.light = aaf::read_light_attributes(a);
    f.omega_y_max = double(std::get<float>(a.attributes.at(aaf::attr::kMaafOmegaYMax)));
    f.aaf_inputs.visibility = a.channel("shadow.V");
    f.aaf_inputs.d1 = a.channel("shadow.d1");
    f.aaf_inputs.d2_min = a.channel("shadow.d2min");
    f.aaf_inputs.d2_max = a.channel("shadow.d2max");
    f.aaf_inputs.position = {a.channel("P.X"), a.channel("P.Y"), a.channel("P.Z")};
    f.aaf_inputs.normal = {a.channel("N.X"), a.channel("N.Y"), a.channel("N.Z")};
    f.aaf_inputs.object_id = a.channel("id.object");
    f.aaf_inputs.pixel_size = a.channel("pixel.size");
    aaf::MaafInputs &m = f.maaf_inputs;
    m.pairs = aaf::kMaafContractPairs;
    for (int c = 0; c < aaf::maaf_channel_count(m.pairs); ++c) {
        const std::string suffix = aaf::maaf_channel_suffix(m.pairs, c);
        m.value_sums.push_back(a.channel("maaf.V_" + suffix));
        m.unoccluded_sums.push_back(a.channel("maaf.W_" + suffix));
    }
    m.s_min = a.channel("maaf.smin");
    m.s_max = a.channel("maaf.smax");
    m.omega_x_max = a.channel("maaf.omegax");
    m.position = f.aaf_inputs.position;
    m.normal = f.aaf_inputs.normal;
    m.object_id = f.aaf_inputs.object_id;
    m.pixel_size = f.aaf_inputs.pixel_size;
    f.mean_central_sigma_px = mean_central_sigma_px(m, f.omega_y_max);
    f.visibility = finite_copy(f.aaf_inputs.visibility);
    for (const auto *sums : {&m.value_sums, &m.unoccluded_sums})
        for (const aaf::ConstPlaneView &plane : *sums) f.sum_planes.push_back(finite_copy(plane));
    return f;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void BM_MaafVsAaf(benchmark::State &state) {
    const int width = int(state.range(0)), height = int(state.range(1));
    const Fixture &f = fixture(width, height);
    const std::size_t n = f.aovs.pixel_count();
    std::vector<float> out(n);
    const aaf::PlaneView view = aaf::plane_view(out.data(), width, height);
    aaf::MaafParams separable;
    separable.omega_y_max_rad_per_m = f.omega_y_max;
    aaf::MaafParams paper_widths = separable;
    paper_widths.k = 1.0;
    const double sigma = f.mean_central_sigma_px;
    cv::Mat cv_out(height, width, CV_32F);
    // Size(0, 0): OpenCV picks the kernel size for sigma, as in bench_aaf_filter.
    const auto opencv_blur = [&](const cv::Mat &src) {
        cv::GaussianBlur(src, cv_out, cv::Size(0, 0), sigma, sigma);
    };
    // Warm-up, untimed: the first run pays for fresh pages and caches.
    opencv_blur(f.visibility);
    aaf::aaf_filter(f.aaf_inputs, f.light, aaf::AafParams{}, {view, aaf::PlaneView{}});
    aaf::maaf_filter(f.maaf_inputs, f.light, separable, view);
    double aaf_ms = 0, maaf_ms = 0, maaf_k1_ms = 0, opencv_ms = 0, opencv_sums_ms = 0;
    for (auto _ : state) {
        auto t = std::chrono::steady_clock::now();
        aaf::aaf_filter(f.aaf_inputs, f.light, aaf::AafParams{}, {view, aaf::PlaneView{}});
        aaf_ms += ms_since(t);
        benchmark::DoNotOptimize(out.data());
        t = std::chrono::steady_clock::now();
        aaf::maaf_filter(f.maaf_inputs, f.light, separable, view);
        maaf_ms += ms_since(t);
        benchmark::DoNotOptimize(out.data());
        t = std::chrono::steady_clock::now();
        aaf::maaf_filter(f.maaf_inputs, f.light, paper_widths, view);
        maaf_k1_ms += ms_since(t);
        benchmark::DoNotOptimize(out.data());
        t = std::chrono::steady_clock::now();
        opencv_blur(f.visibility);
        opencv_ms += ms_since(t);
        benchmark::DoNotOptimize(cv_out.data);
        t = std::chrono::steady_clock::now();
        for (const cv::Mat &plane : f.sum_planes) opencv_blur(plane);
        opencv_sums_ms += ms_since(t);
        benchmark::DoNotOptimize(cv_out.data);
        benchmark::ClobberMemory();
    }
    const double iters = double(state.iterations());
    state.counters["aaf_ms"] = aaf_ms / iters;
    state.counters["maaf_ms"] = maaf_ms / iters;
    state.counters["maaf_over_aaf"] = maaf_ms / aaf_ms;
    state.counters["maaf_k1_ms"] = maaf_k1_ms / iters;
    state.counters["maaf_k1_over_aaf"] = maaf_k1_ms / aaf_ms;
    state.counters["opencv_ms"] = opencv_ms / iters;
    state.counters["opencv_sums_ms"] = opencv_sums_ms / iters;
    state.counters["maaf_over_opencv"] = maaf_ms / opencv_ms;
    state.counters["maaf_over_opencv_sums"] = maaf_ms / opencv_sums_ms;
    state.counters["aaf_over_opencv"] = aaf_ms / opencv_ms;
    state.counters["mean_central_sigma_px"] = sigma;
    state.counters["opencv_threads"] = cv::getNumThreads();
}

void BM_Maaf6VsAaf(benchmark::State &state) {
    const int width = int(state.range(0)), height = int(state.range(1)), threads = int(state.range(2));
    static std::map<int, aaf::AovSet> renders;
    if (!renders.count(width)) {
        aaf::trace::RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.spp = 16;
        settings.aovs = aaf::trace::aov_groups_for_method("aaf") | aaf::trace::aov_groups_for_method("maaf6");
        renders.emplace(width, aaf::trace::render_scene("room", settings));
    }
    const aaf::AovSet &render = renders.at(width);
    const aaf::Method &aaf_method = aaf::find_method("aaf"), &maaf6 = aaf::find_method("maaf6");
    aaf::ParameterSet scalar = maaf6.default_parameters();
    scalar.set("filter", std::string("scalar"));
    // Warm-up, untimed: the first run after the render pays for its outputs'
    // fresh pages (measured: AAF's first 1-thread run 9x its later ones).
    aaf::run_with_threads(threads, [&] {
        benchmark::DoNotOptimize(
            aaf::filter_aovs(aaf_method, render, aaf::ChannelMap{}, aaf_method.default_parameters()));
        benchmark::DoNotOptimize(
            aaf::filter_aovs(maaf6, render, aaf::ChannelMap{}, maaf6.default_parameters()));
    });
    double aaf_ms = 0, maaf6_ms = 0, scalar_ms = 0;
    for (auto _ : state) {
        aaf::run_with_threads(threads, [&] {
            auto t = std::chrono::steady_clock::now();
            benchmark::DoNotOptimize(
                aaf::filter_aovs(aaf_method, render, aaf::ChannelMap{}, aaf_method.default_parameters()));
            aaf_ms += ms_since(t);
            t = std::chrono::steady_clock::now();
            benchmark::DoNotOptimize(
                aaf::filter_aovs(maaf6, render, aaf::ChannelMap{}, maaf6.default_parameters()));
            maaf6_ms += ms_since(t);
            t = std::chrono::steady_clock::now();
            benchmark::DoNotOptimize(aaf::filter_aovs(maaf6, render, aaf::ChannelMap{}, scalar));
            scalar_ms += ms_since(t);
        });
    }
    const double iters = double(state.iterations());
    state.counters["aaf_ms"] = aaf_ms / iters;
    state.counters["maaf6_ms"] = maaf6_ms / iters;
    state.counters["maaf6_over_aaf"] = maaf6_ms / aaf_ms;
    state.counters["maaf6_scalar_ms"] = scalar_ms / iters;
    state.counters["scalar_over_vector"] = scalar_ms / maaf6_ms;
}

}  // namespace

BENCHMARK(BM_Maaf6VsAaf)
    ->ArgNames({"width", "height", "threads"})
    ->Args({640, 480, 1})
    ->Args({640, 480, 0})
    ->Iterations(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_MaafVsAaf)
    ->ArgNames({"width", "height"})
    ->Args({640, 480})
    ->Args({1920, 1080})
    ->Iterations(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
