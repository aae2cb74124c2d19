// Speed of the AAF filter (libaaf core) and of its shared world-space gather
// against OpenCV's cv::GaussianBlur and the project's own fixed-width
// Gaussian, on the same 9 spp render of `grids`, at 640x480, 1920x1080 and
// 3840x2160 (the machine's default threads only at 4K).
// Run: ./scripts/bench.sh
//
// BM_AafVsBaselines times every filter alternately inside each iteration, so
// the ratios it reports come from one run on one machine; every filter runs
// once untimed first, and each counter is the median over the iterations
// (before 2026-12-03, a mean, with aaf_filter's first call in it):
//   aaf_ms      aaf_filter with default AafParams (guides + gather)
//   gather_ms   aaf_gather() alone, one channel, on guides built once outside the timing
//   opencv_ms   cv::GaussianBlur on the visibility (CV_32F), sigma = mean AAF beta in
//               pixels, kernel size OpenCV's default for that sigma, OpenCV's own threads
//   bilateral_ms  cv::bilateralFilter on the same image: spatial sigma the same, range
//               sigma 0.1 (visibility lies in [0, 1]), diameter OpenCV's default (-1)
//   fixed_ms    aaf::fixed_gaussian_filter with the same sigma
//   gather3_ms  aaf_gather() of 3 channels with the same weights in one pass
//   3x_gather1_ms  the same 3 channels as 3 one-channel gathers
// The OpenCV blur has one width for the whole image, no per-pixel width and
// no rejection: it is a lower bound on what any filter of that width costs.
// Rows run with the machine's default threads and with one, the same count
// for oneTBB and OpenCV (counters tbb_threads, opencv_threads): aaf_over_opencv
// is all threads against all on the first rows, one against one on the
// threads:1 rows. The header names the CPU, AAF's instruction set and OpenCV's
// widest (opencv_widest); for AVX2 against AVX2 on an AVX-512 machine run
//   AAF_ISA=avx2 OPENCV_CPU_DISABLE=AVX512_SKX ./build/scripts/bench/bench_aaf_filter
//
// BM_AafPhases times aaf_filter's steps one after the other in each
// iteration, on the same render as BM_AafVsBaselines: fill_ms (AAF Sec. 6's
// occluder fill alone), guide_rows_ms (aaf_gather_guides() minus the fill),
// gather_ms, and the whole aaf_filter (aaf_ms); medians over the iterations,
// so one slow iteration does not move them.
//
// BM_AafGuides times aaf_gather_guides() alone (guides_ms) and the whole
// aaf_filter (aaf_ms) on an adaptive render of `grids` (9 spp first pass,
// AAF Eq. 21 at mu 2, at most 100 spp), with and without its pixel.spp input:
// with it, every filtered pixel bisects its mu (AAF Sec. 5.2), as a real
// render's filter does.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <tbb/task_arena.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "aaf/core/kernels/fixed_gaussian.h"
#include "aaf/core/kernels/gather.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/methods/aaf/aaf_gather_rows.h"
#include "aaf/core/methods/aaf/occluder_fill.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/trace/render.h"

namespace {

struct Fixture {
    aaf::AovSet aovs;
    aaf::AafInputs inputs;
    aaf::LightPlane light;
    /// aaf_filter's guides for default AafParams (built once, untimed).
    aaf::GatherGuides guides;
    aaf::GatherSettings settings;
    /// The visibility as AAF filters it (non-finite read as 0), and two more channels for K = 3.
    std::vector<float> visibility, second, third;
    float mean_sigma_px = 0;  ///< mean AAF beta in pixels over the filtered pixels
    bool gather_matches_aaf = false;
};

/// AAF's inputs as the tracer names them in `a` (the spp AOV left out).
aaf::AafInputs aaf_inputs_of(const aaf::AovSet &a) {
    aaf::AafInputs inputs;
    inputs.visibility = a.channel("shadow.V");
    inputs.d1 = a.channel("shadow.d1");
    inputs.d2_min = a.channel("shadow.d2min");
    inputs.d2_max = a.channel("shadow.d2max");
    inputs.position = {a.channel("P.X"), a.channel("P.Y"), a.channel("P.Z")};
    inputs.normal = {a.channel("N.X"), a.channel("N.Y"), a.channel("N.Z")};
    inputs.object_id = a.channel("id.object");
    inputs.pixel_size = a.channel("pixel.size");
    return inputs;
}

const Fixture &fixture(int width, int height) {
    static std::map<int, Fixture> cache;
    auto [it, inserted] = cache.try_emplace(width);
    Fixture &f = it->second;
    if (!inserted) return f;
    aaf::trace::RenderSettings render_settings;
    render_settings.width = width;
    render_settings.height = height;
    render_settings.spp = 9;
    f.aovs = aaf::trace::render_scene("grids", render_settings);
    const aaf::AovSet &a = f.aovs;
    f.inputs = aaf_inputs_of(a);
    f.light = aaf::read_light_attributes(a);

    const aaf::AafParams params;
    const std::size_t n = a.pixel_count();
    std::vector<float> filtered(n), beta(n);
    aaf::aaf_filter(
        f.inputs, f.light, params,
        {aaf::plane_view(filtered.data(), width, height), aaf::plane_view(beta.data(), width, height)});
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (beta[i] > 0) {
            sum += beta[i] / f.inputs.pixel_size.data[i];
            ++count;
        }
    f.mean_sigma_px = float(sum / double(count));

    f.guides = aaf::aaf_gather_guides(f.inputs, f.light, params);
    f.settings = aaf::aaf_gather_settings(params);
    f.visibility.resize(n);
    f.second.resize(n);
    f.third.resize(n);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = f.guides.index(x, y);
            const float v = f.inputs.visibility(x, y);
            f.visibility[i] = std::isfinite(v) ? v : 0.0f;
            f.second[i] = 1.0f - f.visibility[i];
            f.third[i] = 0.5f * f.visibility[i];
        }

    // The gather timed alone must be the gather aaf_filter runs: same result, bit for bit.
    std::vector<float> gathered(n);
    aaf::aaf_gather(f.guides, aaf::AafParams{}, {aaf::plane_view(f.visibility.data(), width, height)},
                    {aaf::plane_view(gathered.data(), width, height)});
    f.gather_matches_aaf = gathered == filtered;
    return f;
}

double median_of(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void BM_AafVsBaselines(benchmark::State &state) {
    const int width = int(state.range(0)), height = int(state.range(1));
    const int threads = int(state.range(2));  // 0 = the machine default, for oneTBB and OpenCV alike
    const Fixture &f = fixture(width, height);
    if (!f.gather_matches_aaf) {
        state.SkipWithError("gather on the benchmark's guides differs from aaf_filter's result");
        return;
    }
    const std::size_t n = f.aovs.pixel_count();
    std::vector<float> out(n), beta(n), out2(n), out3(n);
    const aaf::AafOutputs aaf_outputs{aaf::plane_view(out.data(), width, height),
                                      aaf::plane_view(beta.data(), width, height)};
    const aaf::ConstPlaneView vis = aaf::plane_view(f.visibility.data(), width, height);
    const std::vector<aaf::ConstPlaneView> sources3{vis, aaf::plane_view(f.second.data(), width, height),
                                                    aaf::plane_view(f.third.data(), width, height)};
    const std::vector<aaf::PlaneView> outputs3{aaf::plane_view(out.data(), width, height),
                                               aaf::plane_view(out2.data(), width, height),
                                               aaf::plane_view(out3.data(), width, height)};

    // OpenCV reads the same sanitised visibility the gather reads; Size(0, 0)
    // lets OpenCV pick the kernel size for sigma (for CV_32F: 2 * round(4 sigma) + 1).
    const cv::Mat cv_src(height, width, CV_32F, const_cast<float *>(f.visibility.data()));
    cv::Mat cv_dst(height, width, CV_32F);
    const double sigma = f.mean_sigma_px;
    const auto opencv_blur = [&] { cv::GaussianBlur(cv_src, cv_dst, cv::Size(0, 0), sigma, sigma); };
    cv::Mat cv_bilateral(height, width, CV_32F);
    const auto opencv_bilateral = [&] { cv::bilateralFilter(cv_src, cv_bilateral, -1, 0.1, sigma); };
    const int opencv_default = threads == 0 ? -1 : threads;  // -1: OpenCV's default count
    cv::setNumThreads(opencv_default);
    const int opencv_threads = cv::getNumThreads();
    int tbb_threads = 0;
    // Per iteration, so that the counters are medians: one slow iteration
    // (another process, a page fault) does not move them.
    std::vector<double> aaf_ms, gather_ms, opencv_ms, opencv_1t_ms, fixed_ms, gather3_ms, gather1x3_ms,
        bilateral_ms;
    aaf::run_with_threads(threads, [&] {
        tbb_threads = tbb::this_task_arena::max_concurrency();

        // Warm-up, untimed: every filter once, so first-touch and allocations are out of the timing.
        aaf::aaf_filter(f.inputs, f.light, aaf::AafParams{}, aaf_outputs);
        opencv_blur();
        aaf::aaf_gather(f.guides, aaf::AafParams{}, {vis}, {outputs3[0]});
        aaf::fixed_gaussian_filter(vis, f.mean_sigma_px, outputs3[0]);
        opencv_bilateral();

        for (auto _ : state) {
            auto t = std::chrono::steady_clock::now();
            aaf::aaf_filter(f.inputs, f.light, aaf::AafParams{}, aaf_outputs);
            aaf_ms.push_back(ms_since(t));
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();

            t = std::chrono::steady_clock::now();
            aaf::aaf_gather(f.guides, aaf::AafParams{}, {vis}, {outputs3[0]});
            gather_ms.push_back(ms_since(t));
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();

            t = std::chrono::steady_clock::now();
            opencv_blur();
            opencv_ms.push_back(ms_since(t));
            benchmark::DoNotOptimize(cv_dst.data);
            benchmark::ClobberMemory();

            t = std::chrono::steady_clock::now();
            opencv_bilateral();
            bilateral_ms.push_back(ms_since(t));
            benchmark::DoNotOptimize(cv_bilateral.data);
            benchmark::ClobberMemory();

            // The same blur on one OpenCV thread: shows how much OpenCV's threading buys.
            cv::setNumThreads(1);
            t = std::chrono::steady_clock::now();
            opencv_blur();
            opencv_1t_ms.push_back(ms_since(t));
            benchmark::DoNotOptimize(cv_dst.data);
            benchmark::ClobberMemory();
            cv::setNumThreads(opencv_default);

            t = std::chrono::steady_clock::now();
            aaf::fixed_gaussian_filter(vis, f.mean_sigma_px, outputs3[0]);
            fixed_ms.push_back(ms_since(t));
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();

            t = std::chrono::steady_clock::now();
            aaf::aaf_gather(f.guides, aaf::AafParams{}, sources3, outputs3);
            gather3_ms.push_back(ms_since(t));
            benchmark::DoNotOptimize(out3.data());
            benchmark::ClobberMemory();

            t = std::chrono::steady_clock::now();
            for (int k = 0; k < 3; ++k)
                aaf::aaf_gather(f.guides, aaf::AafParams{}, {sources3[k]}, {outputs3[k]});
            gather1x3_ms.push_back(ms_since(t));
            benchmark::DoNotOptimize(out3.data());
            benchmark::ClobberMemory();
        }
    });
    const double aaf = median_of(aaf_ms), gather = median_of(gather_ms), opencv = median_of(opencv_ms),
                 fixed = median_of(fixed_ms), gather3 = median_of(gather3_ms),
                 gather1x3 = median_of(gather1x3_ms), bilateral = median_of(bilateral_ms);
    state.counters["aaf_ms"] = aaf;
    state.counters["gather_ms"] = gather;
    state.counters["opencv_ms"] = opencv;
    state.counters["opencv_1thread_ms"] = median_of(opencv_1t_ms);
    state.counters["fixed_ms"] = fixed;
    state.counters["gather3_ms"] = gather3;
    state.counters["3x_gather1_ms"] = gather1x3;
    state.counters["bilateral_ms"] = bilateral;
    state.counters["aaf_over_bilateral"] = aaf / bilateral;
    const double megapixels = double(n) / 1e6;
    state.counters["aaf_ms_per_Mpx"] = aaf / megapixels;
    state.counters["opencv_ms_per_Mpx"] = opencv / megapixels;
    state.counters["gather_over_opencv"] = gather / opencv;
    state.counters["aaf_over_opencv"] = aaf / opencv;
    state.counters["fixed_over_opencv"] = fixed / opencv;
    state.counters["aaf_over_fixed"] = aaf / fixed;
    state.counters["gather3_over_3x_gather1"] = gather3 / gather1x3;
    state.counters["mean_sigma_px"] = f.mean_sigma_px;
    state.counters["tbb_threads"] = tbb_threads;
    state.counters["opencv_threads"] = opencv_threads;
}

struct AdaptiveFixture {
    aaf::AovSet aovs;
    aaf::AafInputs inputs;  ///< with the spp input
    aaf::LightPlane light;
};

const AdaptiveFixture &adaptive_fixture(int width, int height) {
    static std::map<int, AdaptiveFixture> cache;
    auto [it, inserted] = cache.try_emplace(width);
    AdaptiveFixture &f = it->second;
    if (!inserted) return f;
    aaf::trace::RenderSettings render_settings;
    render_settings.width = width;
    render_settings.height = height;
    render_settings.adaptive = true;
    f.aovs = aaf::trace::render_scene("grids", render_settings);
    const aaf::AovSet &a = f.aovs;
    f.inputs = aaf_inputs_of(a);
    f.inputs.spp = a.channel("pixel.spp");
    f.light = aaf::read_light_attributes(a);
    return f;
}

void BM_AafPhases(benchmark::State &state) {
    const int width = int(state.range(0)), height = int(state.range(1));
    const Fixture &f = fixture(width, height);
    const std::size_t n = f.aovs.pixel_count();
    std::vector<float> out(n), beta(n);
    const aaf::AafOutputs outputs{aaf::plane_view(out.data(), width, height),
                                  aaf::plane_view(beta.data(), width, height)};
    const aaf::AafParams params;
    std::vector<double> fill_ms, guide_rows_ms, gather_ms, aaf_ms;
    aaf::run_with_threads(int(state.range(2)), [&] {
        for (auto _ : state) {
            auto t = std::chrono::steady_clock::now();
            {
                const aaf::FilledOccluders filled = aaf::fill_occluder_distances(
                    f.inputs.d2_min, f.inputs.d2_max, f.inputs.object_id, params.fill_radius_px);
                benchmark::DoNotOptimize(filled.d2_max_m.data());
            }
            fill_ms.push_back(ms_since(t));
            t = std::chrono::steady_clock::now();
            {
                const aaf::GatherGuides guides = aaf::aaf_gather_guides(f.inputs, f.light, params);
                benchmark::DoNotOptimize(guides.radius_px.data());
            }
            guide_rows_ms.push_back(ms_since(t) - fill_ms.back());
            std::copy(f.visibility.begin(), f.visibility.end(), out.begin());
            t = std::chrono::steady_clock::now();
            aaf::aaf_gather(f.guides, aaf::AafParams{},
                            {aaf::plane_view<const float>(out.data(), width, height)},
                            {aaf::plane_view(out.data(), width, height)});
            gather_ms.push_back(ms_since(t));
            t = std::chrono::steady_clock::now();
            aaf::aaf_filter(f.inputs, f.light, params, outputs);
            aaf_ms.push_back(ms_since(t));
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();
        }
    });
    state.counters["fill_ms"] = median_of(fill_ms);
    state.counters["guide_rows_ms"] = median_of(guide_rows_ms);
    state.counters["gather_ms"] = median_of(gather_ms);
    state.counters["aaf_ms"] = median_of(aaf_ms);
}

void BM_AafGuides(benchmark::State &state) {
    const int width = int(state.range(0)), height = int(state.range(1));
    const bool with_spp = state.range(2) != 0;
    const AdaptiveFixture &f = adaptive_fixture(width, height);
    aaf::AafInputs inputs = f.inputs;
    if (!with_spp) inputs.spp = {};
    const std::size_t n = f.aovs.pixel_count();
    std::vector<float> out(n), beta(n);
    const aaf::AafOutputs outputs{aaf::plane_view(out.data(), width, height),
                                  aaf::plane_view(beta.data(), width, height)};
    const aaf::AafParams params;
    double guides_ms = 0, aaf_ms = 0;
    aaf::run_with_threads(1, [&] {
        benchmark::DoNotOptimize(aaf::aaf_gather_guides(inputs, f.light, params));  // warm-up, untimed
        for (auto _ : state) {
            auto t = std::chrono::steady_clock::now();
            const aaf::GatherGuides guides = aaf::aaf_gather_guides(inputs, f.light, params);
            guides_ms += ms_since(t);
            benchmark::DoNotOptimize(guides.radius_px.data());
            benchmark::ClobberMemory();

            t = std::chrono::steady_clock::now();
            aaf::aaf_filter(inputs, f.light, params, outputs);
            aaf_ms += ms_since(t);
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();
        }
    });
    const double iters = double(state.iterations());
    state.counters["guides_ms"] = guides_ms / iters;
    state.counters["aaf_ms"] = aaf_ms / iters;
    state.counters["guides_over_aaf"] = guides_ms / aaf_ms;
}

}  // namespace

// Third argument: threads for oneTBB and OpenCV, 0 = the machine default. The
// one-thread rows compare like with like where OpenCV's blur runs on one
// thread whatever it is given (see opencv_1thread_ms).
BENCHMARK(BM_AafVsBaselines)
    ->ArgNames({"width", "height", "threads"})
    ->Args({640, 480, 0})
    ->Args({1920, 1080, 0})
    ->Args({3840, 2160, 0})
    ->Args({640, 480, 1})
    ->Args({1920, 1080, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_AafPhases)
    ->ArgNames({"width", "height", "threads"})
    ->Args({640, 480, 0})
    ->Args({1920, 1080, 0})
    ->Args({640, 480, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
// One thread: the guides' own cost, without the machine's other load spread over threads.
BENCHMARK(BM_AafGuides)
    ->ArgNames({"width", "height", "spp"})
    ->Args({640, 480, 0})
    ->Args({640, 480, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

namespace {

/// The CPU's name, from /proc/cpuinfo where there is one.
std::string cpu_name() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

}  // namespace

// The header names the CPU, the instruction set of AAF's kernels (AAF_ISA)
// and the widest OpenCV dispatches to, after OPENCV_CPU_DISABLE (e.g.
// OPENCV_CPU_DISABLE=AVX512_SKX holds OpenCV to AVX2 as AAF_ISA=avx2 holds AAF).
int main(int argc, char **argv) {
    benchmark::AddCustomContext("cpu", cpu_name());
    benchmark::AddCustomContext("aaf_isa", aaf::instruction_set_name(aaf::instruction_set()));
    benchmark::AddCustomContext("aaf_gather_target", aaf::detail::aaf_gather_row_target());
    const char *opencv_widest = cv::checkHardwareSupport(CV_CPU_AVX512_SKX) ? "AVX512_SKX"
                                : cv::checkHardwareSupport(CV_CPU_AVX2)     ? "AVX2"
                                                                            : "below AVX2";
    benchmark::AddCustomContext("opencv_widest", opencv_widest);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
