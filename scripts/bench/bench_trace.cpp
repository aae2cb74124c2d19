// Shadow-ray throughput of the bundled tracer (libaaf/trace) against raw
// Embree loops over the same rays, in the same run, on one core.
// Run: ./scripts/bench_trace.sh
//
// For each scene, the shadow rays of a 320x240 view at 16 samples per pixel
// are generated exactly as Renderer::trace_shadows generates them (same
// random numbers, strata, light warp and origin offset) and stored. Then
// BM_Throughput times, alternately and single-threaded:
//   tracer      Renderer::trace_shadows over every pixel (what `aaf render`
//               runs per sample: RNG, light sampling, a closest-hit query for
//               the occluder distance d2, statistics)
//   tracer_visibility  the same with visibility only (any hit), what later
//               rounds and the adaptive second pass run
//   tracer_packets  the same in rtcOccluded16 packets of a pixel's rays
//               (what references, 1024 spp or more, run)
//   occluded1   rtcOccluded1 on the stored rays (the fastest possible answer
//               to "is it blocked")
//   intersect1  rtcIntersect1 on the stored rays (what d2 needs)
// and reports rays per second for each and tracer / occluded1.
// BM_Packets compares rtcOccluded4/8/16 against rtcOccluded1, and
// rtcIntersect16 against rtcIntersect1, on the same rays
// (each packet holds consecutive samples of one pixel: same origin, nearby
// light points, the most coherent grouping shadow rays allow).
// BM_BuildQuality compares rtcOccluded1 on a MEDIUM and a HIGH quality BVH,
// BM_Robust rtcOccluded1 and rtcIntersect1 with and without
// RTC_SCENE_FLAG_ROBUST (the tracer's choice), and BM_Denormals the tracer
// with and without flush-to-zero. BM_Threads times render_scene end to end
// (a 320x240 grids reference slice of 64 spp) on 1 thread and on all, and
// reports samples per second per thread.
// BM_EndToEnd and BM_EndToEndBreakdown (bench_trace_end_to_end.cpp): the
// whole `aaf render` process against the raw Embree program on its rays.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/info.h>

#include <time.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "aaf/core/util/instruction_set.h"
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

constexpr int kWidth = 320, kHeight = 240, kSpp = 16;

/// The JSON of a scene with one mesh of 129,240 triangles (a sphere of 360
/// segments) over a ground, lit from above.
std::string write_dense_mesh_scene() {
    const auto path = std::filesystem::temp_directory_path() / "aaf_bench_dense_mesh.json";
    std::ofstream(path) << R"({
  "camera": {"position": [0, 2.2, 3.2], "look_at": [0, 0.4, 0]},
  "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "intensity": 30}],
  "objects": [{"type": "plane", "size": [20, 20]},
              {"type": "sphere", "center": [0, 0.9, 0], "radius": 0.6, "segments": 360, "id": 2}]
})";
    return path.string();
}

struct Fixture {
    SceneDescription scene;
    RenderSettings settings;
    /// The renderer's BVH, as Renderer builds its own for a render of kSpp,
    /// and the same with visibility rays always in packets.
    std::unique_ptr<EmbreeScene> bvh, packet_bvh;
    std::unique_ptr<Renderer> renderer, packet_renderer;
    std::vector<PrimaryHit> primaries;
    std::vector<Ray> rays;
    std::size_t triangles = 0;
    /// Built once, as the Renderer builds its own: the timed sampling loop
    /// pays per ray, not the inverse-CDF table's construction.
    std::unique_ptr<LightSampler> sampler;
};

/// Calls `emit` with every shadow ray the sample loop of
/// Renderer::trace_shadows (pass 0) traces, in the same order.
template <typename Emit>
void for_each_shadow_ray(const Fixture &f, const Emit &emit) {
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::size_t i = std::size_t(y) * kWidth + x;
            for_each_pixel_shadow_ray<kSpp>(f.scene, *f.sampler, f.settings.seed, f.primaries[i], i, emit);
        }
}

Fixture &fixture(const std::string &scene_name) {
    static std::map<std::string, std::unique_ptr<Fixture>> cache;
    auto &slot = cache[scene_name];
    if (slot) return *slot;
    slot = std::make_unique<Fixture>();
    Fixture &f = *slot;
    const std::string path =
        scene_name == "dense_mesh" ? write_dense_mesh_scene() : resolve_scene(scene_name);
    f.scene = load_scene_file(path, kWidth, kHeight);
    for (const Mesh &mesh : f.scene.meshes) f.triangles += mesh.triangle_count();
    f.settings.width = kWidth;
    f.settings.height = kHeight;
    f.settings.spp = kSpp;
    const bool reference = f.settings.spp >= kSamplesPerRound;
    f.bvh = std::make_unique<EmbreeScene>(f.scene, reference);
    f.packet_bvh = std::make_unique<EmbreeScene>(f.scene, reference, true, true);
    f.renderer = std::make_unique<Renderer>(f.scene, f.settings, *f.bvh);
    f.packet_renderer = std::make_unique<Renderer>(f.scene, f.settings, *f.packet_bvh);
    f.sampler = std::make_unique<LightSampler>(f.scene.key_light());
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) f.primaries.push_back(f.renderer->trace_primary(x, y));
    for_each_shadow_ray(f, [&](const Ray &ray) { f.rays.push_back(ray); });
    return f;
}

/// The calling thread's CPU time. The single-threaded comparisons below time
/// with it, so a thread that waits for a core (other processes on the
/// machine) does not count the wait; BM_Threads times the wall clock.
struct ThreadCpuClock {
    using duration = std::chrono::nanoseconds;
    using rep = duration::rep;
    using period = duration::period;
    using time_point = std::chrono::time_point<ThreadCpuClock>;
    [[maybe_unused]] static constexpr bool is_steady = true;  // the Clock requirements; nothing reads it
    static time_point now() {
        timespec now;
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
        return time_point(duration(rep(now.tv_sec) * 1000000000 + rep(now.tv_nsec)));
    }
};

using aaf::bench::seconds;  // the wall clock's, beside this one

double seconds(const ThreadCpuClock::time_point &start) {
    return std::chrono::duration<double>(ThreadCpuClock::now() - start).count();
}

std::size_t run_tracer(const Fixture &f, bool occluder_distances, bool packets = false) {
    const Renderer &renderer = packets ? *f.packet_renderer : *f.renderer;
    std::size_t traced = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::size_t i = std::size_t(y) * kWidth + x;
            if (!f.primaries[i].found) continue;
            ShadowStats stats;
            renderer.trace_shadows(f.primaries[i], x, y, i, 0, kSpp, occluder_distances, stats, {});
            traced += stats.taken;
            benchmark::DoNotOptimize(stats);
        }
    return traced;
}

template <int N, typename RayPacket>
void fill_packet(const std::vector<Ray> &rays, std::size_t start, int *valid, RayPacket &packet) {
    for (int k = 0; k < N; ++k) {
        const bool active = start + k < rays.size();
        valid[k] = active ? -1 : 0;
        const Ray &ray = rays[active ? start + k : start];
        packet.org_x[k] = ray.origin.x;
        packet.org_y[k] = ray.origin.y;
        packet.org_z[k] = ray.origin.z;
        packet.dir_x[k] = ray.direction.x;
        packet.dir_y[k] = ray.direction.y;
        packet.dir_z[k] = ray.direction.z;
        packet.tnear[k] = 0;
        packet.tfar[k] = ray.t_far;
        packet.time[k] = 0;
        packet.mask[k] = std::numeric_limits<unsigned>::max();
        packet.id[k] = 0;
        packet.flags[k] = 0;
    }
}

/// rtcOccludedN on packets of N consecutive stored rays.
template <int N, typename Packet, typename Occluded>
std::size_t run_packets(RTCScene scene, const std::vector<Ray> &rays, Occluded occluded) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    std::size_t blocked = 0;
    alignas(64) int valid[N];
    alignas(64) Packet packet;
    for (std::size_t start = 0; start < rays.size(); start += N) {
        fill_packet<N>(rays, start, valid, packet);
        occluded(valid, scene, &context, &packet);
        for (int k = 0; k < N; ++k) blocked += valid[k] && packet.tfar[k] < 0;
    }
    return blocked;
}

/// rtcIntersect16 on packets of 16 consecutive stored rays (the closest hit d2 needs).
std::size_t run_intersect16(RTCScene scene, const std::vector<Ray> &rays) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    std::size_t hits = 0;
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 packet;
    for (std::size_t start = 0; start < rays.size(); start += 16) {
        fill_packet<16>(rays, start, valid, packet.ray);
        for (int k = 0; k < 16; ++k) packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect16(valid, scene, &context, &packet);
        for (int k = 0; k < 16; ++k) hits += valid[k] && packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
}

void BM_Throughput(benchmark::State &state, const std::string &scene_name) {
    Fixture &f = fixture(scene_name);
    set_flush_to_zero(true);
    const RTCScene scene = f.bvh->handle();
    double tracer_s = 0, tracer_visibility_s = 0, tracer_packets_s = 0, occluded_s = 0, intersect_s = 0,
           sampling_s = 0;
    std::size_t tracer_rays = 0;
    for (auto _ : state) {
        auto sampling_start = ThreadCpuClock::now();
        float sink = 0;
        for_each_shadow_ray(f, [&](const Ray &ray) { sink += ray.direction.x; });
        benchmark::DoNotOptimize(sink);
        sampling_s += seconds(sampling_start);
        auto start = ThreadCpuClock::now();
        tracer_rays += run_tracer(f, true);
        tracer_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_tracer(f, false));
        tracer_visibility_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_tracer(f, false, true));
        tracer_packets_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_occluded1(scene, f.rays));
        occluded_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_intersect1(scene, f.rays));
        intersect_s += seconds(start);
    }
    const double n = double(state.iterations()), rays = double(f.rays.size());
    state.counters["triangles"] = double(f.triangles);
    state.counters["sampling_ns_per_ray"] = sampling_s / (rays * n) * 1e9;
    // Rays the tracer traced (the stored set); samples behind the receiver's
    // tangent plane are counted by the tracer but need no ray.
    state.counters["tracer_Mrays_s"] = rays * n / tracer_s / 1e6;
    state.counters["tracer_Msamples_s"] = double(tracer_rays) / tracer_s / 1e6;
    state.counters["occluded1_Mrays_s"] = rays * n / occluded_s / 1e6;
    state.counters["intersect1_Mrays_s"] = rays * n / intersect_s / 1e6;
    // The tracer takes a sample behind the receiver's tangent plane without a
    // ray; count only the rays it traces, as the stored set does.
    state.counters["tracer_over_occluded1"] = (rays * n / tracer_s) / (rays * n / occluded_s);
    state.counters["tracer_over_intersect1"] = (rays * n / tracer_s) / (rays * n / intersect_s);
    // Visibility-only passes (later rounds, the adaptive second pass) against the same floor.
    state.counters["tracer_visibility_Mrays_s"] = rays * n / tracer_visibility_s / 1e6;
    state.counters["tracer_visibility_over_occluded1"] = occluded_s / tracer_visibility_s;
    // The same rays in packets of a pixel's 16 (ShadowRayGrouping::Packets;
    // renders of fewer than 1024 spp, like this one, trace them one at a time).
    state.counters["tracer_packets_over_occluded1"] = occluded_s / tracer_packets_s;
}

void BM_Packets(benchmark::State &state, const std::string &scene_name) {
    Fixture &f = fixture(scene_name);
    set_flush_to_zero(true);
    const RTCScene scene = f.bvh->handle();
    double single_s = 0, p4_s = 0, p8_s = 0, p16_s = 0, intersect1_s = 0, intersect16_s = 0;
    for (auto _ : state) {
        auto start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_occluded1(scene, f.rays));
        single_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_packets<4, RTCRay4>(scene, f.rays, rtcOccluded4));
        p4_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_packets<8, RTCRay8>(scene, f.rays, rtcOccluded8));
        p8_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_packets<16, RTCRay16>(scene, f.rays, rtcOccluded16));
        p16_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_intersect1(scene, f.rays));
        intersect1_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_intersect16(scene, f.rays));
        intersect16_s += seconds(start);
    }
    const double rays = double(f.rays.size()) * double(state.iterations());
    state.counters["occluded1_Mrays_s"] = rays / single_s / 1e6;
    state.counters["occluded4_over_1"] = single_s / p4_s;
    state.counters["occluded8_over_1"] = single_s / p8_s;
    state.counters["occluded16_over_1"] = single_s / p16_s;
    state.counters["intersect16_over_1"] = intersect1_s / intersect16_s;
}

void BM_BuildQuality(benchmark::State &state, const std::string &scene_name) {
    Fixture &f = fixture(scene_name);
    set_flush_to_zero(true);
    auto start = std::chrono::steady_clock::now();
    const EmbreeScene medium(f.scene, false);
    const double medium_build_s = seconds(start);
    start = std::chrono::steady_clock::now();
    const EmbreeScene high(f.scene, true);
    const double high_build_s = seconds(start);
    double medium_s = 0, high_s = 0;
    for (auto _ : state) {
        auto run_start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_occluded1(medium.handle(), f.rays));
        medium_s += seconds(run_start);
        run_start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_occluded1(high.handle(), f.rays));
        high_s += seconds(run_start);
    }
    state.counters["medium_build_ms"] = medium_build_s * 1e3;
    state.counters["high_build_ms"] = high_build_s * 1e3;
    state.counters["high_over_medium_rays_s"] = medium_s / high_s;
}

void BM_Robust(benchmark::State &state, const std::string &scene_name) {
    Fixture &f = fixture(scene_name);
    set_flush_to_zero(true);
    const EmbreeScene robust(f.scene, false, true), plain(f.scene, false, false);
    double robust_occluded_s = 0, plain_occluded_s = 0, robust_intersect_s = 0, plain_intersect_s = 0;
    std::size_t robust_blocked = 0, plain_blocked = 0;
    for (auto _ : state) {
        auto start = ThreadCpuClock::now();
        robust_blocked = run_occluded1(robust.handle(), f.rays);
        robust_occluded_s += seconds(start);
        start = ThreadCpuClock::now();
        plain_blocked = run_occluded1(plain.handle(), f.rays);
        plain_occluded_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_intersect1(robust.handle(), f.rays));
        robust_intersect_s += seconds(start);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_intersect1(plain.handle(), f.rays));
        plain_intersect_s += seconds(start);
    }
    // rays/s with the flag over rays/s without it: below 1 is its cost.
    state.counters["robust_over_plain_occluded1"] = plain_occluded_s / robust_occluded_s;
    state.counters["robust_over_plain_intersect1"] = plain_intersect_s / robust_intersect_s;
    // Rays whose answer the flag changes (leaks between adjacent triangles).
    state.counters["blocked_difference"] = double(robust_blocked) - double(plain_blocked);
}

void BM_Threads(benchmark::State &state) {
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.spp = 64;
    const int all = tbb::info::default_concurrency();
    double one_s = 0, all_s = 0, samples = 0;
    for (auto _ : state) {
        settings.threads = 1;
        auto start = std::chrono::steady_clock::now();
        const AovSet aovs = render_scene("grids", settings);
        one_s += seconds(start);
        settings.threads = all;
        start = std::chrono::steady_clock::now();
        benchmark::DoNotOptimize(render_scene("grids", settings));
        all_s += seconds(start);
        const ConstPlaneView spp = aovs.channel("pixel.spp");
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) samples += spp(x, y);
    }
    state.counters["threads"] = all;
    state.counters["one_thread_Msamples_s"] = samples / one_s / 1e6;
    state.counters["all_threads_Msamples_s_per_thread"] = samples / all_s / all / 1e6;
    state.counters["per_thread_all_over_one"] = one_s / all_s / all;
}

void BM_Denormals(benchmark::State &state, const std::string &scene_name) {
    Fixture &f = fixture(scene_name);
    double ftz_s = 0, plain_s = 0;
    for (auto _ : state) {
        set_flush_to_zero(true);
        auto start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_tracer(f, true));
        ftz_s += seconds(start);
        set_flush_to_zero(false);
        start = ThreadCpuClock::now();
        benchmark::DoNotOptimize(run_tracer(f, true));
        plain_s += seconds(start);
    }
    set_flush_to_zero(true);
    state.counters["ftz_over_plain_rays_s"] = plain_s / ftz_s;
}

}  // namespace

BENCHMARK_CAPTURE(BM_Throughput, grids, std::string("grids"))->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Throughput, dense_mesh, std::string("dense_mesh"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2);
BENCHMARK_CAPTURE(BM_Packets, grids, std::string("grids"))->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Packets, dense_mesh, std::string("dense_mesh"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2);
BENCHMARK_CAPTURE(BM_BuildQuality, grids, std::string("grids"))->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_BuildQuality, dense_mesh, std::string("dense_mesh"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2);
BENCHMARK_CAPTURE(BM_Robust, grids, std::string("grids"))->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Robust, dense_mesh, std::string("dense_mesh"))
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2);
BENCHMARK_CAPTURE(BM_Denormals, grids, std::string("grids"))->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK(BM_Threads)->Unit(benchmark::kMillisecond)->MinTime(2);
int main(int argc, char **argv) {
    // The header names the machine and the instruction set the rays ran on.
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line, cpu = "unknown CPU";
    while (std::getline(cpuinfo, line))
        if (line.rfind("model name", 0) == 0) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    benchmark::AddCustomContext("cpu", cpu);
    // The set in force, and for native the widest this CPU runs (what Embree picks).
    std::string isa = aaf::instruction_set_name(aaf::instruction_set());
    if (aaf::instruction_set() == aaf::InstructionSet::Native)
        for (aaf::InstructionSet set : {aaf::InstructionSet::Avx512, aaf::InstructionSet::Avx2})
            if (aaf::cpu_supports(set)) {
                isa += std::string(" (widest here: ") + aaf::instruction_set_name(set) + ")";
                break;
            }
    benchmark::AddCustomContext("isa", isa);
    benchmark::AddCustomContext("threads", std::to_string(tbb::info::default_concurrency()));
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
