// The tracer end to end, part of bench_trace (bench_trace.cpp has the
// per-ray benchmarks and main). BM_EndToEnd times `aaf render grids --width
// 640 --height 480 --spp 256` as a process (what its user waits for:
// start-up and library loading, the scene, the BVH, the passes, the AOVs,
// the EXR write) against the raw Embree program on the same rays (a BVH
// built as the render builds it, then rtcOccluded1, and separately
// rtcIntersect1, over every key-light shadow ray of that render),
// alternately, every thread each; and `aaf --version`, the start-up alone.
// Its end_to_end_over_raw is rays per second of `aaf render` over the raw
// rtcOccluded1 program's, end_to_end_over_raw_closest over the
// rtcIntersect1 program's. BM_EndToEndBreakdown splits the same render in
// this process into render_scene's stages and the EXR write. `AAF` names
// the aaf program (default: the build tree's), AAF_BEFORE another build's,
// timed alternately too (speed_over_before); AAF_ISA applies to every side.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>  // environ

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"
#include "embree_scene.h"
#include "light_sampler.h"
#include "renderer.h"
#include "scene_file.h"
#include "trace_rays.h"

namespace {

using namespace aaf;
using namespace aaf::trace;
using namespace aaf::bench;

/// `aaf render grids --width 640 --height 480 --spp 256` end to end, the
/// render the tracer's fixed cost is measured on.
constexpr int kEndWidth = 640, kEndHeight = 480;
constexpr std::uint32_t kEndSpp = 256;
/// Rows whose rays are generated, then traced, at a time (640 x 8 x 256 rays, about 30 MiB).
constexpr int kEndChunkRows = 8;

/// The `aaf` program: $AAF, else the build tree's, beside this benchmark's.
std::string aaf_program() {
    if (const char *given = std::getenv("AAF")) return given;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
    return (self.parent_path() / ".." / ".." / "cli" / "aaf").lexically_normal().string();
}

/// Wall-clock seconds of running `arguments` (program first) to its exit,
/// its output discarded; throws when it fails.
double run_process(const std::vector<std::string> &arguments) {
    std::vector<char *> argv;
    for (const std::string &a : arguments) argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    const auto start = std::chrono::steady_clock::now();
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    int status = 0;
    if (spawned != 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error("bench_trace: " + arguments[0] + " failed (set AAF to the aaf program)");
    return seconds(start);
}

std::vector<std::string> aaf_render_command(const std::string &program, const std::string &output) {
    return {program,
            "render",
            "grids",
            "--width",
            std::to_string(kEndWidth),
            "--height",
            std::to_string(kEndHeight),
            "--spp",
            std::to_string(kEndSpp),
            "--progress",
            "none",
            "-o",
            output};
}

/// The end-to-end render's view: its primary hits, to generate its shadow rays from.
struct EndToEndView {
    SceneDescription scene;
    RenderSettings settings;
    std::unique_ptr<Renderer> renderer;
    std::unique_ptr<LightSampler> sampler;
    std::vector<PrimaryHit> primaries;

    EndToEndView() {
        settings.width = kEndWidth;
        settings.height = kEndHeight;
        settings.spp = int(kEndSpp);
        scene = load_scene_file(resolve_scene("grids"), kEndWidth, kEndHeight);
        renderer = std::make_unique<Renderer>(scene, settings);
        sampler = std::make_unique<LightSampler>(scene.key_light());
        primaries.resize(std::size_t(kEndWidth) * kEndHeight);
        for (int y = 0; y < kEndHeight; ++y)
            renderer->trace_primaries(y, 0, kEndWidth, &primaries[std::size_t(y) * kEndWidth]);
    }
};

/// The raw Embree program on the render's rays: a device and a BVH of the
/// scene as the render builds them, then `query` (run_occluded1 or
/// run_intersect1) over every key-light shadow ray of the 256 spp render, on
/// every thread. Only the build and the loops are timed (wall clock): the
/// rays are generated a chunk of rows at a time in between, untimed. Returns
/// the seconds; `rays` counts the rays.
double raw_embree_program(const EndToEndView &view, std::size_t (*query)(RTCScene, const std::vector<Ray> &),
                          std::size_t &rays) {
    auto start = std::chrono::steady_clock::now();
    const EmbreeScene bvh(view.scene, false);
    double total_s = seconds(start);
    std::vector<std::vector<Ray>> row_rays(kEndChunkRows);
    rays = 0;
    for (int y0 = 0; y0 < kEndHeight; y0 += kEndChunkRows) {
        const int rows = std::min(kEndChunkRows, kEndHeight - y0);
        tbb::parallel_for(0, rows, [&](int r) {
            std::vector<Ray> &out = row_rays[std::size_t(r)];
            out.clear();
            const int y = y0 + r;
            for (int x = 0; x < kEndWidth; ++x) {
                const std::size_t i = std::size_t(y) * kEndWidth + x;
                for_each_pixel_shadow_ray<kEndSpp>(view.scene, *view.sampler, view.settings.seed,
                                                   view.primaries[i], i,
                                                   [&](const Ray &ray) { out.push_back(ray); });
            }
        });
        start = std::chrono::steady_clock::now();
        tbb::parallel_for(
            tbb::blocked_range<int>(0, rows, 1),
            [&](const tbb::blocked_range<int> &range) {
                set_flush_to_zero(true);  // as the render's workers
                for (int r = range.begin(); r != range.end(); ++r)
                    benchmark::DoNotOptimize(query(bvh.handle(), row_rays[std::size_t(r)]));
            },
            tbb::simple_partitioner());
        total_s += seconds(start);
        for (int r = 0; r < rows; ++r) rays += row_rays[std::size_t(r)].size();
    }
    return total_s;
}

/// `aaf render` end to end (the process as its user waits for it: start-up,
/// scene, BVH, passes, AOVs, the EXR write) against the raw Embree program
/// on the same rays, alternately, every thread each; and `aaf --version`,
/// the process start-up alone. One set per iteration: with repetitions,
/// the median of end_to_end_over_raw is the median of the pairwise ratios.
/// The raw program runs twice: rtcOccluded1 (visibility alone, the
/// yardstick) and rtcIntersect1 (the closest hit, which a render below
/// kSamplesPerRound spp asks of every ray: its first round gives
/// d2min/d2max, AAF Sec. 6).
void BM_EndToEnd(benchmark::State &state) {
    static const EndToEndView view;
    const std::string output = (std::filesystem::temp_directory_path() / "aaf_bench_end_to_end.exr").string();
    // $AAF_BEFORE, another build's aaf (e.g. main's), alternated with this one: a change's speed-up.
    const char *before = std::getenv("AAF_BEFORE");
    double render_s = 0, raw_s = 0, closest_s = 0, startup_s = 0, before_s = 0;
    std::size_t rays = 0;
    for (auto _ : state) {
        render_s += run_process(aaf_render_command(aaf_program(), output));
        raw_s += raw_embree_program(view, run_occluded1, rays);
        closest_s += raw_embree_program(view, run_intersect1, rays);
        startup_s += run_process({aaf_program(), "--version"});
        if (before) before_s += run_process(aaf_render_command(before, output));
    }
    const double n = double(state.iterations());
    state.counters["rays_M"] = double(rays) / 1e6;
    state.counters["aaf_render_ms"] = render_s / n * 1e3;
    state.counters["raw_embree_ms"] = raw_s / n * 1e3;
    state.counters["aaf_version_ms"] = startup_s / n * 1e3;
    state.counters["aaf_Mrays_s"] = double(rays) * n / render_s / 1e6;
    state.counters["raw_Mrays_s"] = double(rays) * n / raw_s / 1e6;
    state.counters["raw_closest_ms"] = closest_s / n * 1e3;
    // The same rays: rays per second of aaf render over the raw program's.
    state.counters["end_to_end_over_raw"] = raw_s / render_s;
    state.counters["end_to_end_over_raw_closest"] = closest_s / render_s;
    if (!before) return;
    state.counters["before_end_to_end_over_raw"] = raw_s / before_s;
    state.counters["speed_over_before"] = before_s / render_s;
}

/// Where the end-to-end render's time goes, in this process (every thread):
/// the stages render_scene reports (RenderTimings) and io::write_aovs of
/// its result as `aaf render` writes it; the process start-up is
/// BM_EndToEnd's aaf_version_ms.
void BM_EndToEndBreakdown(benchmark::State &state) {
    RenderSettings settings;
    settings.width = kEndWidth;
    settings.height = kEndHeight;
    settings.spp = int(kEndSpp);
    const std::string output = (std::filesystem::temp_directory_path() / "aaf_bench_breakdown.exr").string();
    RenderTimings sum;
    double render_s = 0, write_s = 0;
    for (auto _ : state) {
        auto start = std::chrono::steady_clock::now();
        RenderTimings timings;
        const AovSet aovs = render_scene("grids", settings, &timings);
        render_s += seconds(start);
        start = std::chrono::steady_clock::now();
        io::write_aovs(aovs, output);
        write_s += seconds(start);
        sum.scene_s += timings.scene_s;
        sum.setup_s += timings.setup_s;
        sum.primaries_s += timings.primaries_s;
        sum.first_pass_s += timings.first_pass_s;
        sum.aovs_s += timings.aovs_s;
    }
    const double ms = 1e3 / double(state.iterations());
    state.counters["scene_ms"] = sum.scene_s * ms;
    state.counters["bvh_and_groups_ms"] = sum.setup_s * ms;
    state.counters["primaries_ms"] = sum.primaries_s * ms;
    state.counters["shadow_pass_ms"] = (sum.first_pass_s - sum.primaries_s) * ms;
    state.counters["aov_assembly_ms"] = sum.aovs_s * ms;
    // What render_scene spends outside the stages (settings checks, the arena).
    state.counters["render_other_ms"] =
        (render_s - sum.scene_s - sum.setup_s - sum.first_pass_s - sum.aovs_s) * ms;
    state.counters["exr_write_ms"] = write_s * ms;
}
}  // namespace

// One pair (one render) per repetition: --benchmark_repetitions=5 gives medians.
BENCHMARK(BM_EndToEnd)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_EndToEndBreakdown)->Unit(benchmark::kMillisecond)->Iterations(1);
