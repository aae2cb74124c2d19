// Every registered method against the physical limit of the machine it runs
// on: the bytes a method must move (each input plane it reads read once,
// each output plane written once) over the machine's measured copy
// bandwidth, with the same threads, in the same run.
//
// Input: one 640x480 render of `grids` with every AOV group (9 spp), the
// way the CLI hands it to a method: filter_aovs() on a moved copy (the copy
// is made outside the timing), default parameters.
// One row per method (BM_MethodVsCopyBandwidth/<method>):
//   copy_GB_s          a parallel copy of a 512 MiB buffer (read + write bytes per second)
//   method_ms          filter_aovs() of the method, end to end in memory
//   method_MB          the bytes it must move: its declared inputs present in
//                      the render (per-light layers included) plus its outputs
//   floor_ms           those bytes at copy_GB_s
//   method_over_floor  method_ms / floor_ms: how far from memory-bound
// Run: ./build/scripts/bench/bench_methods_bandwidth
#include <benchmark/benchmark.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/ratio_layers.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/trace/render.h"

namespace {

const aaf::AovSet &render() {
    static const aaf::AovSet aovs = [] {
        aaf::trace::RenderSettings settings;
        settings.width = 640;
        settings.height = 480;
        settings.spp = 9;
        settings.aovs = aaf::trace::parse_aov_groups("all,maaf,isg,ratio,maaf6");
        return aaf::trace::render_scene("grids", settings);
    }();
    return aovs;
}

/// Bytes `method` must move on `aovs`: every channel of its declared input
/// roles that is present, read once, and every output channel written once
/// (the noisy beauty is the input's plane moved, no bytes).
double bytes_moved(const aaf::Method &method, const aaf::AovSet &aovs) {
    const aaf::MethodInfo &info = method.info();
    const aaf::ChannelMap found = aaf::ChannelMap{}.resolved(aovs);
    const int lights = aaf::ratio_light_count(aovs.attributes, aovs.channel_names().size());
    std::vector<aaf::Role> roles = info.roles.required;
    roles.insert(roles.end(), info.roles.optional.begin(), info.roles.optional.end());
    std::vector<std::string> read;
    for (aaf::Role role : roles)
        for (const std::string &name : found.channels(role)) {
            if (aovs.has_channel(name)) read.push_back(name);
            if (!aaf::is_per_light_role(role)) continue;
            for (int light = 0; light < lights; ++light) {
                const std::string layer = aaf::per_light_channel(name, light);
                if (aovs.has_channel(layer)) read.push_back(layer);
            }
        }
    std::sort(read.begin(), read.end());
    read.erase(std::unique(read.begin(), read.end()), read.end());
    std::size_t written = 0;
    for (aaf::Role role : info.roles.outputs) written += found.channels(role).size();
    return double(read.size() + written) * double(aovs.pixel_count()) * sizeof(float);
}

/// Read + write bytes per second of a parallel copy larger than any cache.
double copy_bytes_per_s() {
    constexpr std::size_t kBytes = std::size_t(512) << 20, kChunk = std::size_t(1) << 20;
    std::vector<char> source(kBytes, 1), target(kBytes, 0);
    const auto copy = [&] {
        tbb::parallel_for(std::size_t(0), kBytes / kChunk, [&](std::size_t c) {
            std::memcpy(target.data() + c * kChunk, source.data() + c * kChunk, kChunk);
        });
    };
    copy();  // warm-up: the pages exist
    double best_s = 1e9;
    for (int repeat = 0; repeat < 5; ++repeat) {
        const auto start = std::chrono::steady_clock::now();
        copy();
        best_s =
            std::min(best_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        benchmark::DoNotOptimize(target.data());
    }
    return 2.0 * double(kBytes) / best_s;
}

void BM_MethodVsCopyBandwidth(benchmark::State &state, const aaf::Method *method) {
    const aaf::AovSet &aovs = render();
    const aaf::MissingInputs missing = aaf::missing_inputs(*method, aovs, aaf::ChannelMap{});
    if (!missing.roles.empty() || !missing.attributes.empty()) {
        state.SkipWithError("the render lacks this method's inputs");
        return;
    }
    const aaf::ParameterSet parameters = method->default_parameters();
    const double bandwidth = copy_bytes_per_s();
    double method_s = 0;
    for (auto _ : state) {
        state.PauseTiming();
        aaf::AovSet input = aovs;
        state.ResumeTiming();
        const auto start = std::chrono::steady_clock::now();
        aaf::AovSet out = aaf::filter_aovs(*method, std::move(input), aaf::ChannelMap{}, parameters);
        method_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        benchmark::DoNotOptimize(out.plane(0).data());
    }
    const double bytes = bytes_moved(*method, aovs), seconds = method_s / double(state.iterations());
    state.counters["copy_GB_s"] = bandwidth * 1e-9;
    state.counters["method_ms"] = seconds * 1e3;
    state.counters["method_MB"] = bytes * 1e-6;
    state.counters["floor_ms"] = bytes / bandwidth * 1e3;
    state.counters["method_over_floor"] = seconds / (bytes / bandwidth);
}

}  // namespace

int main(int argc, char **argv) {
    for (const aaf::Method *method : aaf::methods())
        benchmark::RegisterBenchmark(("BM_MethodVsCopyBandwidth/" + method->info().name).c_str(),
                                     BM_MethodVsCopyBandwidth, method)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(1.0);
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
