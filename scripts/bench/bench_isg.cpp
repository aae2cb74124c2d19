// Speed of the three ISG filters (Robison and Shirley 2009) at 1024x768, as
// ISG Table 1: milliseconds per frame for every pair of parameter-search and
// gather sample counts in {9, 25, 49, 81}, beside the no-ISG baseline timed
// in the same iteration: the same filter_aovs() pass with the `gaussian`
// method at sigma 0 (it copies the visibility and composes the beauty, the
// "final shading pass without ISG"). Input: one render of `gallery` with the
// isg group, 1 spp (ISG needs one ray per pixel and effect).
// Run: ./scripts/bench_isg.sh
//   isg_ms       filter_aovs() with the ISG method
//   baseline_ms  filter_aovs() with gaussian --sigma 0
// isg-dof runs on the pinhole render with --aperture 0.15 --focus 4.6 (the
// study's lens), so that it blurs.
#include <benchmark/benchmark.h>

#include <chrono>
#include <functional>
#include <string>

#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/trace/render.h"

namespace {

const aaf::AovSet &gallery() {
    static const aaf::AovSet aovs = [] {
        aaf::trace::RenderSettings settings;
        settings.width = 1024;
        settings.height = 768;
        settings.spp = 1;
        settings.aovs = aaf::trace::parse_aov_groups("isg,aaf,depth");
        return aaf::trace::render_scene("gallery", settings);
    }();
    return aovs;
}

double seconds(const std::function<void()> &run) {
    const auto start = std::chrono::steady_clock::now();
    run();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_IsgTable1(benchmark::State &state) {
    static const char *kEffects[] = {"isg-shadow", "isg-glossy", "isg-dof"};
    const std::string effect = kEffects[state.range(0)];
    const aaf::Method &method = aaf::find_method(effect);
    aaf::ParameterSet parameters = method.default_parameters();
    parameters.set("search_samples", std::to_string(state.range(1)));
    parameters.set("gather_samples", std::to_string(state.range(2)));
    if (effect == "isg-dof") {
        parameters.set("aperture", 0.15);
        parameters.set("focus", 4.6);
    }
    const aaf::Method &baseline = aaf::find_method("gaussian");
    aaf::ParameterSet copy = baseline.default_parameters();
    copy.set("sigma", 0.0);
    const aaf::AovSet &input = gallery();
    double isg_s = 0, baseline_s = 0;
    for (auto _ : state) {
        isg_s += seconds([&] {
            benchmark::DoNotOptimize(aaf::filter_aovs(method, input, aaf::ChannelMap{}, parameters));
        });
        baseline_s += seconds(
            [&] { benchmark::DoNotOptimize(aaf::filter_aovs(baseline, input, aaf::ChannelMap{}, copy)); });
    }
    const double n = double(state.iterations());
    state.counters["isg_ms"] = 1e3 * isg_s / n;
    state.counters["baseline_ms"] = 1e3 * baseline_s / n;
    state.SetLabel(effect);
}

void table1_args(benchmark::internal::Benchmark *b) {
    for (int effect = 0; effect < 3; ++effect)
        for (int search : {9, 25, 49, 81})
            for (int gather : {9, 25, 49, 81}) b->Args({effect, search, gather});
}

}  // namespace

BENCHMARK(BM_IsgTable1)
    ->ArgNames({"effect", "search", "gather"})
    ->Apply(table1_args)
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
