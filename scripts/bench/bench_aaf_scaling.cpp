// How the AAF filter's cost grows with the pixel count at a fixed filter
// width, against OpenCV's cv::GaussianBlur of the same width in the same run.
//
// Rendering one scene at a higher resolution also widens AAF's filters in
// pixels (the same beta in metres covers more pixels: a mean of 2.4 px at
// 640x480, 11 px at 3840x2160 on `grids`), so bench_aaf_filter's rows mix
// the two effects. Here the 9 spp 640x480 render of `grids` is tiled k x k
// (k = 1, 2, 3, 6: up to 3840x2880): every tile holds the same pixels with
// the same widths, so a filter linear in pixels costs the same per megapixel
// at every k. Tiles meet where positions jump across the image; those taps
// get a negligible weight, as at any depth edge.
//   aaf_ms, aaf_ms_per_Mpx     aaf_filter with default AafParams (guides + gather)
//   opencv_ms, opencv_ms_per_Mpx  cv::GaussianBlur of the visibility at AAF's mean width
//   aaf_over_opencv            their ratio, timed alternately
// Run: ./build/scripts/bench/bench_aaf_scaling
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/trace/render.h"

namespace {

constexpr int kTileWidth = 640, kTileHeight = 480;

/// The channels aaf_filter reads, in AafInputs order.
const char *const kChannels[] = {"shadow.V", "shadow.d1", "shadow.d2min", "shadow.d2max",
                                 "P.X",      "P.Y",       "P.Z",          "N.X",
                                 "N.Y",      "N.Z",       "id.object",    "pixel.size"};

const aaf::AovSet &tile_render() {
    static const aaf::AovSet aovs = [] {
        aaf::trace::RenderSettings settings;
        settings.width = kTileWidth;
        settings.height = kTileHeight;
        settings.spp = 9;
        return aaf::trace::render_scene("grids", settings);
    }();
    return aovs;
}

/// The tile render's AAF inputs repeated k x k times.
struct TiledInputs {
    int width = 0, height = 0;
    std::map<std::string, std::vector<float>> planes;
    aaf::AafInputs inputs;
    aaf::LightPlane light;
    float mean_sigma_px = 0;  ///< mean AAF beta in pixels over the filtered pixels of one tile
};

const TiledInputs &tiled(int k) {
    static std::map<int, TiledInputs> cache;
    auto [it, inserted] = cache.try_emplace(k);
    TiledInputs &t = it->second;
    if (!inserted) return t;
    const aaf::AovSet &tile = tile_render();
    t.width = kTileWidth * k;
    t.height = kTileHeight * k;
    for (const char *name : kChannels) {
        const aaf::ConstPlaneView source = tile.channel(name);
        std::vector<float> &plane = t.planes[name];
        plane.resize(std::size_t(t.width) * std::size_t(t.height));
        for (int y = 0; y < t.height; ++y)
            for (int x = 0; x < t.width; ++x)
                plane[std::size_t(y) * std::size_t(t.width) + std::size_t(x)] =
                    source(x % kTileWidth, y % kTileHeight);
    }
    auto view = [&](const char *name) { return aaf::plane_view(t.planes[name].data(), t.width, t.height); };
    aaf::AafInputs &in = t.inputs;
    in.visibility = view("shadow.V");
    in.d1 = view("shadow.d1");
    in.d2_min = view("shadow.d2min");
    in.d2_max = view("shadow.d2max");
    in.position = {view("P.X"), view("P.Y"), view("P.Z")};
    in.normal = {view("N.X"), view("N.Y"), view("N.Z")};
    in.object_id = view("id.object");
    in.pixel_size = view("pixel.size");
    t.light = aaf::read_light_attributes(tile);

    // The width OpenCV gets: AAF's mean beta in pixels, from the first filter.
    const std::size_t n = std::size_t(t.width) * std::size_t(t.height);
    std::vector<float> filtered(n), beta(n);
    aaf::aaf_filter(in, t.light, aaf::AafParams{},
                    {aaf::plane_view(filtered.data(), t.width, t.height),
                     aaf::plane_view(beta.data(), t.width, t.height)});
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (beta[i] > 0) {
            sum += beta[i] / in.pixel_size.data[i];
            ++count;
        }
    t.mean_sigma_px = float(sum / double(count));
    return t;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void BM_AafScaling(benchmark::State &state) {
    const TiledInputs &t = tiled(int(state.range(0)));
    const std::size_t n = std::size_t(t.width) * std::size_t(t.height);
    std::vector<float> out(n), visibility(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float v = t.inputs.visibility.data[i];
        visibility[i] = std::isfinite(v) ? v : 0.0f;  // as AAF reads it
    }
    const cv::Mat cv_src(t.height, t.width, CV_32F, visibility.data());
    cv::Mat cv_dst(t.height, t.width, CV_32F);
    const double sigma = t.mean_sigma_px;
    // Size(0, 0): OpenCV picks the kernel size for sigma.
    const auto opencv_blur = [&] { cv::GaussianBlur(cv_src, cv_dst, cv::Size(0, 0), sigma, sigma); };
    opencv_blur();  // warm-up, untimed
    double aaf_ms = 0, opencv_ms = 0;
    for (auto _ : state) {
        auto start = std::chrono::steady_clock::now();
        aaf::aaf_filter(t.inputs, t.light, aaf::AafParams{},
                        {aaf::plane_view(out.data(), t.width, t.height), aaf::PlaneView{}});
        aaf_ms += ms_since(start);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
        start = std::chrono::steady_clock::now();
        opencv_blur();
        opencv_ms += ms_since(start);
        benchmark::DoNotOptimize(cv_dst.data);
        benchmark::ClobberMemory();
    }
    const double iterations = double(state.iterations()), megapixels = double(n) * 1e-6;
    state.counters["megapixels"] = megapixels;
    state.counters["mean_sigma_px"] = sigma;
    state.counters["aaf_ms"] = aaf_ms / iterations;
    state.counters["aaf_ms_per_Mpx"] = aaf_ms / iterations / megapixels;
    state.counters["opencv_ms"] = opencv_ms / iterations;
    state.counters["opencv_ms_per_Mpx"] = opencv_ms / iterations / megapixels;
    state.counters["aaf_over_opencv"] = aaf_ms / opencv_ms;
}

}  // namespace

BENCHMARK(BM_AafScaling)
    ->ArgName("tiles_per_side")
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Arg(6)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
