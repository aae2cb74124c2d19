// Speed of the ratio estimator's denoise (libaaf core, `aaf filter ratio`)
// against OpenCV's cv::bilateralFilter and cv::GaussianBlur of the same mean
// width on the same image in the same run, at 640x480, 1920x1080 (also on
// one thread) and 3840x2160 (the paper's GPU denoise: 3.5 ms, Table 1).
// OpenCV runs on as many threads as oneTBB (cv::setNumThreads).
// Run: ./scripts/bench_ratio.sh
//
// Input: the bundled tracer's `grids` at 2 spp, its geometry (P, N,
// pixel.size) as rendered, and one light's ratio layers made from it:
// U = U_N = unshadowed, S_N = unshadowed x shadow.V (a noisy light-weighted
// visibility, W_N = shadow.V), so the noise estimate sees real penumbrae.
// Timed alternately in each iteration:
//   noise_ms      luminance, W_N and the noise estimate E (Eq. 29, 3x3 box), sigma = min(k E, cap)
//   bilateral_ms  the two joint-bilateral passes over S_N and U_N RGB (6 planes) writing U x W
//   denoise_ms    noise_ms + bilateral_ms + the planes' preparation: the whole denoise
//   grey_ms       the same with the grey approximation (2 planes)
//   opencv_ms     cv::GaussianBlur of S_N and U_N as two CV_32FC3 images (the same 6 planes),
//                 sigma = the mean bilateral sigma over the pixels it filters, OpenCV's kernel size
//   cv_bilateral_ms  cv::bilateralFilter of the same two images, spatial sigma the same mean
//                 sigma (OpenCV's window: radius round(1.5 sigma), a disc), range sigma
//                 kCvRangeSigma (0.1, in the radiance's units; the cost does not depend on it)
// The OpenCV blur has one width, no per-pixel width, no weights: a lower bound
// for a filter of that width; OpenCV's bilateral weighs its taps by colour
// where ours weighs them by plane distance. Counters: filtered_fraction
// (pixels with sigma > 0), mean_sigma_px, tbb_threads, opencv_threads,
// opencv_avx2 and opencv_avx512 (whether OpenCV may use them: env
// OPENCV_CPU_DISABLE=AVX512_SKX restricts it to AVX2); the label names our
// instruction set (env AAF_ISA=sse4.2|avx2|avx512 pins it).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <vector>

#include <tbb/task_arena.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "aaf/core/methods/ratio/ratio_bilateral.h"
#include "aaf/core/methods/ratio/ratio_composition.h"
#include "aaf/core/methods/ratio/ratio_noise_estimate.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/trace/render.h"

namespace {

// The `aaf filter ratio` defaults (ratio_method.cpp).
constexpr int kNoiseRadiusPx = 6;
constexpr float kSigmaPerNoisePx = 3.0f, kMaxSigmaPx = 8.0f;
/// OpenCV bilateral's range sigma (S_N and U_N of `grids` lie in about [0, 1]).
constexpr double kCvRangeSigma = 0.1;

struct Fixture {
    int width = 0, height = 0;
    aaf::AovSet aovs;
    std::vector<float> s[3], s_y, u_y;  ///< S_N RGB and the luminances
    aaf::RatioLayers layers;
    aaf::RatioBilateralGuides guides;
    float mean_sigma_px = 0, filtered_fraction = 0;
};

const Fixture &fixture(int width, int height) {
    static std::map<int, Fixture> cache;
    auto [it, inserted] = cache.try_emplace(width);
    Fixture &f = it->second;
    if (!inserted) return f;
    f.width = width;
    f.height = height;
    aaf::trace::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.spp = 2;
    f.aovs = aaf::trace::render_scene("grids", settings);
    const aaf::AovSet &a = f.aovs;
    const std::size_t n = a.pixel_count();
    const char *rgb[3] = {"R", "G", "B"};
    const aaf::ConstPlaneView v = a.channel("shadow.V");
    f.s_y.assign(n, 0.0f);
    f.u_y.assign(n, 0.0f);
    const float luminance[3] = {0.2126f, 0.7152f, 0.0722f};
    for (int c = 0; c < 3; ++c) {
        const aaf::ConstPlaneView u = a.channel(std::string("unshadowed.") + rgb[c]);
        f.s[c].assign(n, 0.0f);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * width + x;
                const float uu = std::isfinite(u(x, y)) ? u(x, y) : 0.0f;
                const float vv = std::isfinite(v(x, y)) ? v(x, y) : 0.0f;
                f.s[c][i] = uu * vv;
                f.s_y[i] += luminance[c] * f.s[c][i];
                f.u_y[i] += luminance[c] * uu;
            }
        f.layers.analytic[c] = u;
        f.layers.unshadowed[c] = u;
        f.layers.shadowed[c] = aaf::plane_view(static_cast<const float *>(f.s[c].data()), width, height);
    }
    f.layers.shadowed_y = aaf::plane_view(static_cast<const float *>(f.s_y.data()), width, height);
    f.layers.unshadowed_y = aaf::plane_view(static_cast<const float *>(f.u_y.data()), width, height);
    const char *xyz[3] = {"X", "Y", "Z"};
    for (int c = 0; c < 3; ++c) {
        f.guides.position[c] = a.channel(std::string("P.") + xyz[c]);
        f.guides.normal[c] = a.channel(std::string("N.") + xyz[c]);
    }
    f.guides.scale_m = a.channel("pixel.size");
    return f;
}

/// The method's sigma: E of W_N (luminance), times k, capped.
void sigma_from_noise(const Fixture &f, std::vector<float> &w, std::vector<float> &sigma) {
    const int width = f.width, height = f.height;
    aaf::weighted_shadow(f.layers.shadowed_y, f.layers.unshadowed_y,
                         aaf::plane_view(w.data(), width, height));
    aaf::ratio_noise_estimate(aaf::plane_view(static_cast<const float *>(w.data()), width, height),
                              kNoiseRadiusPx, 0, aaf::plane_view(sigma.data(), width, height));
    for (float &e : sigma) e = std::min(kSigmaPerNoisePx * e, kMaxSigmaPx);
}

std::vector<aaf::ConstPlaneView> views(const std::vector<aaf::FramePlane<float>> &planes, int width,
                                       int height) {
    std::vector<aaf::ConstPlaneView> out;
    for (const aaf::FramePlane<float> &plane : planes)
        out.push_back(aaf::plane_view(plane.data(), width, height));
    return out;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void BM_RatioDenoiseVsOpenCv(benchmark::State &state) {
    const int width = int(state.range(0)), height = int(state.range(1));
    const int threads = int(state.range(2));
    const Fixture &f = fixture(width, height);
    const std::size_t n = std::size_t(width) * height;
    std::vector<float> w(n), sigma(n), out[3];
    for (auto &o : out) o.assign(n, 0.0f);
    const std::array<aaf::PlaneView, 3> rgb = {aaf::plane_view(out[0].data(), width, height),
                                               aaf::plane_view(out[1].data(), width, height),
                                               aaf::plane_view(out[2].data(), width, height)};
    const aaf::RatioComposition composition(f.layers, aaf::RatioEstimator::Ratio, false);
    const aaf::RatioComposition grey(f.layers, aaf::RatioEstimator::Ratio, true);

    // The width OpenCV gets: the mean sigma where the bilateral filters.
    sigma_from_noise(f, w, sigma);
    double sum = 0;
    std::size_t count = 0;
    for (float s : sigma)
        if (s > 0) {
            sum += s;
            ++count;
        }
    const double mean_sigma = count ? sum / double(count) : 0.0;
    std::vector<float> s_packed(n * 3), u_packed(n * 3);
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            s_packed[i * 3 + c] = f.layers.shadowed[c].data[i];
            u_packed[i * 3 + c] = f.layers.unshadowed[c].data[i];
        }
    const cv::Mat cv_s(height, width, CV_32FC3, s_packed.data()),
        cv_u(height, width, CV_32FC3, u_packed.data());
    cv::Mat cv_s_out(height, width, CV_32FC3), cv_u_out(height, width, CV_32FC3);
    const auto opencv_blur = [&] {
        cv::GaussianBlur(cv_s, cv_s_out, cv::Size(0, 0), mean_sigma, mean_sigma);
        cv::GaussianBlur(cv_u, cv_u_out, cv::Size(0, 0), mean_sigma, mean_sigma);
    };
    const auto opencv_bilateral = [&] {
        cv::bilateralFilter(cv_s, cv_s_out, 0, kCvRangeSigma, mean_sigma);
        cv::bilateralFilter(cv_u, cv_u_out, 0, kCvRangeSigma, mean_sigma);
    };
    cv::setNumThreads(threads == 0 ? -1 : threads);
    const int opencv_threads = cv::getNumThreads();
    int tbb_threads = 0;
    double noise_ms = 0, bilateral_ms = 0, denoise_ms = 0, grey_ms = 0, opencv_ms = 0, cv_bilateral_ms = 0;
    aaf::run_with_threads(threads, [&] {
        tbb_threads = tbb::this_task_arena::max_concurrency();
        opencv_blur();  // warm-up, untimed
        opencv_bilateral();
        for (auto _ : state) {
            auto t = std::chrono::steady_clock::now();
            const std::vector<aaf::FramePlane<float>> planes = composition.sources();
            const std::vector<aaf::ConstPlaneView> sources = views(planes, width, height);
            const double prepare_ms = ms_since(t);
            t = std::chrono::steady_clock::now();
            sigma_from_noise(f, w, sigma);
            const double this_noise_ms = ms_since(t);
            t = std::chrono::steady_clock::now();
            aaf::ratio_bilateral_compose(
                f.guides, aaf::plane_view(static_cast<const float *>(sigma.data()), width, height), {},
                sources, composition, rgb, false);
            const double this_bilateral_ms = ms_since(t);
            benchmark::DoNotOptimize(out[0].data());
            benchmark::ClobberMemory();
            noise_ms += this_noise_ms;
            bilateral_ms += this_bilateral_ms;
            denoise_ms += prepare_ms + this_noise_ms + this_bilateral_ms;

            t = std::chrono::steady_clock::now();
            const std::vector<aaf::FramePlane<float>> grey_planes = grey.sources();
            const std::vector<aaf::ConstPlaneView> grey_sources = views(grey_planes, width, height);
            sigma_from_noise(f, w, sigma);
            aaf::ratio_bilateral_compose(
                f.guides, aaf::plane_view(static_cast<const float *>(sigma.data()), width, height), {},
                grey_sources, grey, rgb, false);
            grey_ms += ms_since(t);
            benchmark::DoNotOptimize(out[0].data());
            benchmark::ClobberMemory();

            t = std::chrono::steady_clock::now();
            opencv_blur();
            opencv_ms += ms_since(t);
            benchmark::DoNotOptimize(cv_s_out.data);
            benchmark::ClobberMemory();

            t = std::chrono::steady_clock::now();
            opencv_bilateral();
            cv_bilateral_ms += ms_since(t);
            benchmark::DoNotOptimize(cv_s_out.data);
            benchmark::ClobberMemory();
        }
    });
    const double iters = double(state.iterations());
    state.counters["noise_ms"] = noise_ms / iters;
    state.counters["bilateral_ms"] = bilateral_ms / iters;
    state.counters["denoise_ms"] = denoise_ms / iters;
    state.counters["grey_ms"] = grey_ms / iters;
    state.counters["opencv_ms"] = opencv_ms / iters;
    state.counters["denoise_over_opencv"] = denoise_ms / opencv_ms;
    state.counters["grey_over_opencv"] = grey_ms / opencv_ms;
    state.counters["cv_bilateral_ms"] = cv_bilateral_ms / iters;
    state.counters["denoise_over_cv_bilateral"] = denoise_ms / cv_bilateral_ms;
    state.counters["mean_sigma_px"] = mean_sigma;
    state.counters["filtered_fraction"] = double(count) / double(n);
    state.counters["tbb_threads"] = tbb_threads;
    state.counters["opencv_threads"] = opencv_threads;
    state.counters["opencv_avx2"] = cv::checkHardwareSupport(CV_CPU_AVX2);
    state.counters["opencv_avx512"] = cv::checkHardwareSupport(CV_CPU_AVX512_SKX);
    state.SetLabel(std::string("aaf ") + aaf::instruction_set_name(aaf::instruction_set()));
}

}  // namespace

BENCHMARK(BM_RatioDenoiseVsOpenCv)
    ->ArgNames({"width", "height", "threads"})
    ->Args({640, 480, 0})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->Args({3840, 2160, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
