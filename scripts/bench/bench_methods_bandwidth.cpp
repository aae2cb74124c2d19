// Every registered method against the physical limit of the machine it runs
// on: the bytes a method must move (each input plane it reads read once,
// each output plane written once) over the machine's measured copy
// bandwidth, with the same threads, in the same run.
//
// Input: one 640x480 render of `grids` with every AOV group (9 spp), the
// way the CLI hands it to a method: filter_aovs() on a moved copy (the copy
// is made outside the timing), default parameters. Its beauty is maaf6's,
// with a pass of the key light, so aaf and gaussian filter that pass too and
// swap it into the beauty.
// Two rows per method (BM_MethodVsCopyBandwidth/<method>/threads:N): all the
// machine's threads (N = 0) and one (N = 1), the copy and the method alike.
// Medians over the iterations:
//   copy_GB_s          a parallel copy of a 512 MiB buffer (read + write bytes per second)
//   method_ms          filter_aovs() of the method, end to end in memory
//   method_cpu_ms      the same call's CPU time over all threads (page faults
//                      included): steadier than method_ms on a shared machine
//   method_MB          the bytes it must move: its declared inputs present in
//                      the render (per-light layers included) plus its outputs
//   floor_ms           those bytes at copy_GB_s
//   method_over_floor  method_ms / floor_ms: how far from memory-bound
// For aaf, gaussian and isg-shadow, each iteration also runs the method's
// kernels alone on the same planes, alternately with filter_aovs():
//   kernels_ms         aaf: aaf_gather_guides() (occluder fill, guides), one
//                      gather of the visibility and the key light's pass (4
//                      channels, the pass demodulated outside the timing), the
//                      beauty's composition; gaussian: the blur of the visibility and
//                      of the pass's 3 channels, the composition; isg-shadow:
//                      isg_shadow_visibility() (its search and gather; this
//                      render's beauty is not r(x) V(x), which isg-shadow
//                      keeps as rendered, so there is no composition)
//   method_over_kernels  method_ms / kernels_ms: what the framework adds
// The header names the CPU and the instruction set the kernels run (AAF_ISA).
// Run: ./build/scripts/bench/bench_methods_bandwidth
#include <benchmark/benchmark.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/ratio_layers.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/kernels/fixed_gaussian.h"
#include "aaf/core/kernels/gather.h"
#include "aaf/core/kernels/gather_rows.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/trace/render.h"
#include "methods/isg/isg_shadow.h"

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

/// Seconds of CPU time the process has used, over all its threads.
double process_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double median_of(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

/// The planes a shadow filter's kernels read and write, outside any timing.
struct KernelPlanes {
    const aaf::AovSet *aovs = nullptr;
    int width = 0, height = 0;
    std::vector<float> visibility, filtered, beta, composed[3];
    /// The key light's pass as read (for the composition) and demodulated by the albedo (for AAF's gather).
    aaf::ConstPlaneView pass[3], beauty[3];
    std::vector<float> demodulated[3], filtered_pass[3];
    bool swaps_pass = false;

    explicit KernelPlanes(const aaf::AovSet &a) : aovs(&a), width(a.width()), height(a.height()) {
        const std::size_t n = a.pixel_count();
        const aaf::ChannelMap found = aaf::ChannelMap{}.resolved(a);
        const aaf::ConstPlaneView v = a.channel(found.channels(aaf::Role::Visibility)[0]);
        visibility.resize(n);
        for (std::size_t i = 0; i < n; ++i) visibility[i] = std::isfinite(v.data[i]) ? v.data[i] : 0.0f;
        filtered.resize(n);
        beta.resize(n);
        const std::vector<std::string> &pass_names = found.channels(aaf::Role::KeyLight);
        swaps_pass = !pass_names.empty() && a.has_channel(pass_names[0]) &&
                     !aaf::beauty_holds_exactly(a.attributes, aaf::beauty_holds::kDirect);
        for (std::size_t c = 0; c < 3; ++c) {
            composed[c].resize(n);
            beauty[c] = a.channel(found.channels(aaf::Role::Beauty)[c]);
            if (!swaps_pass) continue;
            pass[c] = a.channel(pass_names[c]);
            const aaf::ConstPlaneView albedo = a.channel(found.channels(aaf::Role::Albedo)[c]);
            demodulated[c].resize(n);
            filtered_pass[c].resize(n);
            for (std::size_t i = 0; i < n; ++i) {
                const float value = albedo.data[i] > 0 ? pass[c].data[i] / albedo.data[i] : pass[c].data[i];
                demodulated[c][i] = std::isfinite(value) ? value : 0.0f;
            }
        }
    }
    aaf::PlaneView view(std::vector<float> &plane) { return aaf::plane_view(plane.data(), width, height); }
    /// The beauty less the pass plus the filtered pass (or r(x) V(x)'s swap): one pass over the planes.
    void compose() {
        const aaf::ConstPlaneView r0 = aovs->channel("unshadowed.R");
        tbb::parallel_for(0, height, [&](int y) {
            const std::size_t row = std::size_t(y) * std::size_t(width);
            for (std::size_t c = 0; c < 3; ++c) {
                float *const out = composed[c].data() + row;
                const float *const in = beauty[c].data + row;
                const float *const swapped =
                    swaps_pass ? filtered_pass[c].data() + row : filtered.data() + row;
                const float *const removed = swaps_pass ? pass[c].data + row : r0.data + row;
                for (int x = 0; x < width; ++x) out[x] = (in[x] - removed[x]) + swapped[x];
            }
        });
    }
};

/// isg-shadow's filter on `k`'s planes with the method's `parameters`.
std::function<void()> isg_shadow_kernels(KernelPlanes &k, const aaf::ParameterSet &parameters) {
    const aaf::AovSet &a = *k.aovs;
    const aaf::ChannelMap found = aaf::ChannelMap{}.resolved(a);
    const auto plane = [&](aaf::Role role, std::size_t c) { return a.channel(found.channels(role)[c]); };
    aaf::isg::ShadowInputs in;
    in.hard = plane(aaf::roles::HardVisibility, 0);
    in.occluder_m = plane(aaf::roles::OccluderDistance, 0);
    in.depth_m = plane(aaf::Role::Depth, 0);
    for (std::size_t c = 0; c < 3; ++c) in.position.c[c] = plane(aaf::Role::Position, c);
    const aaf::LightPlane light = aaf::read_light_attributes(a);
    const float focal_px = aaf::isg::focal_px_attribute(a.attributes, a.height());
    const aaf::isg::IsgShadowSettings settings = aaf::isg::isg_shadow_settings(parameters);
    return [&k, in, light, focal_px, settings] {
        aaf::isg::isg_shadow_visibility(in, settings, light, focal_px, k.view(k.filtered));
    };
}

/// The kernels of `method` on `k`'s planes, or none for a method without them here.
std::function<void()> method_kernels(const aaf::Method &m, KernelPlanes &k) {
    const std::string &method = m.info().name;
    const aaf::AovSet &a = *k.aovs;
    if (method == "isg-shadow") return isg_shadow_kernels(k, m.default_parameters());
    if (method == "gaussian")
        return [&k] {
            const float sigma_px = 2;  // the method's default
            aaf::fixed_gaussian_filter(k.view(k.visibility), sigma_px, k.view(k.filtered));
            if (k.swaps_pass)
                for (std::size_t c = 0; c < 3; ++c)
                    aaf::fixed_gaussian_filter(k.view(k.demodulated[c]), sigma_px,
                                               k.view(k.filtered_pass[c]));
            k.compose();
        };
    if (method != "aaf") return {};
    aaf::AafInputs in;
    in.visibility = a.channel("shadow.V");
    in.d1 = a.channel("shadow.d1");
    in.d2_min = a.channel("shadow.d2min");
    in.d2_max = a.channel("shadow.d2max");
    in.position = {a.channel("P.X"), a.channel("P.Y"), a.channel("P.Z")};
    in.normal = {a.channel("N.X"), a.channel("N.Y"), a.channel("N.Z")};
    in.object_id = a.channel("id.object");
    in.pixel_size = a.channel("pixel.size");
    if (a.has_channel("pixel.spp")) in.spp = a.channel("pixel.spp");  // the method's default: mu from spp
    const aaf::LightPlane light = aaf::read_light_attributes(a);
    return [&k, in, light] {
        const aaf::AafParams params;
        const aaf::GatherGuides guides = aaf::aaf_gather_guides(in, light, params, k.view(k.beta));
        if (!k.swaps_pass) {
            aaf::aaf_filter_visibility(guides, params, in.visibility, k.view(k.filtered));
        } else {
            // As the method: the visibility and the pass in one four-channel gather.
            std::copy(k.visibility.begin(), k.visibility.end(), k.filtered.begin());
            std::vector<aaf::ConstPlaneView> sources{k.view(k.filtered)};
            std::vector<aaf::PlaneView> outputs{k.view(k.filtered)};
            for (std::size_t c = 0; c < 3; ++c) {
                sources.push_back(k.view(k.demodulated[c]));
                outputs.push_back(k.view(k.filtered_pass[c]));
            }
            aaf::aaf_gather(guides, params, sources, outputs);
        }
        k.compose();
    };
}

void method_vs_copy_bandwidth(benchmark::State &state, const aaf::Method *method) {
    const aaf::AovSet &aovs = render();
    const aaf::MissingInputs missing = aaf::missing_inputs(*method, aovs, aaf::ChannelMap{});
    if (!missing.roles.empty() || !missing.attributes.empty()) {
        state.SkipWithError("the render lacks this method's inputs");
        return;
    }
    const aaf::ParameterSet parameters = method->default_parameters();
    const double bandwidth = copy_bytes_per_s();
    KernelPlanes planes(aovs);
    const std::function<void()> kernels = method_kernels(*method, planes);
    if (kernels) kernels();  // warm-up, untimed
    std::vector<double> method_ms, method_cpu_ms, kernels_ms;
    for (auto _ : state) {
        state.PauseTiming();
        aaf::AovSet input = aovs;
        state.ResumeTiming();
        const double cpu_start = process_cpu_s();
        const auto start = std::chrono::steady_clock::now();
        aaf::AovSet out = aaf::filter_aovs(*method, std::move(input), aaf::ChannelMap{}, parameters);
        method_ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        method_cpu_ms.push_back((process_cpu_s() - cpu_start) * 1e3);
        benchmark::DoNotOptimize(out.plane(0).data());
        if (!kernels) continue;
        const auto kernels_start = std::chrono::steady_clock::now();
        kernels();
        kernels_ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - kernels_start)
                .count());
        benchmark::ClobberMemory();
    }
    const double bytes = bytes_moved(*method, aovs), ms = median_of(method_ms);
    const double floor_ms = bytes / bandwidth * 1e3;
    state.counters["copy_GB_s"] = bandwidth * 1e-9;
    state.counters["method_ms"] = ms;
    state.counters["method_cpu_ms"] = median_of(method_cpu_ms);
    state.counters["method_MB"] = bytes * 1e-6;
    state.counters["floor_ms"] = floor_ms;
    state.counters["method_over_floor"] = ms / floor_ms;
    if (!kernels) return;
    state.counters["kernels_ms"] = median_of(kernels_ms);
    state.counters["method_over_kernels"] = ms / median_of(kernels_ms);
}

/// method_vs_copy_bandwidth() on the threads of the row's argument (0 = all).
void BM_MethodVsCopyBandwidth(benchmark::State &state, const aaf::Method *method) {
    aaf::run_with_threads(int(state.range(0)), [&] { method_vs_copy_bandwidth(state, method); });
}

/// The CPU's name, from /proc/cpuinfo where there is one.
std::string cpu_name() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

}  // namespace

int main(int argc, char **argv) {
    benchmark::AddCustomContext("cpu", cpu_name());
    benchmark::AddCustomContext("aaf_isa", aaf::instruction_set_name(aaf::instruction_set()));
    benchmark::AddCustomContext("kernels_target", aaf::detail::gather_row_target());
    for (const aaf::Method *method : aaf::methods())
        benchmark::RegisterBenchmark(("BM_MethodVsCopyBandwidth/" + method->info().name).c_str(),
                                     BM_MethodVsCopyBandwidth, method)
            ->ArgName("threads")
            ->Arg(0)
            ->Arg(1)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(1.0);
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
