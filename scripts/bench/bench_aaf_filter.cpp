// Speed of the AAF filter (libaaf core) against a fixed-width separable
// Gaussian of the same mean width, on the same 9 spp render of `grids`, at
// 640x480 and 1920x1080. Run: ./scripts/bench.sh
//
// BM_AafVsFixed times both filters alternately inside one benchmark, so the
// ratio it reports (counter `aaf_over_fixed`) comes from one run on one machine.
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <vector>

#include "aaf/core/aaf_filter.h"
#include "aaf/core/fixed_gaussian.h"
#include "aaf/trace/render.h"

namespace {

struct Fixture {
    aaf::AovSet aovs;
    aaf::AafInputs inputs;
    aaf::LightPlane light;
    float mean_sigma_px = 0;  ///< mean AAF beta in pixels over the filtered pixels
};

const Fixture &fixture(int width, int height) {
    static std::map<int, Fixture> cache;
    auto [it, inserted] = cache.try_emplace(width);
    Fixture &f = it->second;
    if (!inserted) return f;
    aaf::trace::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.spp = 9;
    f.aovs = aaf::trace::render_scene("grids", settings);
    const aaf::AovSet &a = f.aovs;
    f.inputs.visibility = a.channel("shadow.V");
    f.inputs.d1 = a.channel("shadow.d1");
    f.inputs.d2_min = a.channel("shadow.d2min");
    f.inputs.d2_max = a.channel("shadow.d2max");
    f.inputs.position = {a.channel("P.X"), a.channel("P.Y"), a.channel("P.Z")};
    f.inputs.normal = {a.channel("N.X"), a.channel("N.Y"), a.channel("N.Z")};
    f.inputs.object_id = a.channel("id.object");
    f.inputs.pixel_size = a.channel("pixel.size");
    f.light = aaf::read_light_attributes(a);

    std::vector<float> filtered(a.pixel_count()), beta(a.pixel_count());
    aaf::aaf_filter(
        f.inputs, f.light, aaf::AafParams{},
        {aaf::plane_view(filtered.data(), width, height), aaf::plane_view(beta.data(), width, height)});
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < beta.size(); ++i)
        if (beta[i] > 0) {
            sum += beta[i] / f.inputs.pixel_size.data[i];
            ++count;
        }
    f.mean_sigma_px = float(sum / double(count));
    return f;
}

void BM_AafVsFixed(benchmark::State &state) {
    const int width = int(state.range(0)), height = int(state.range(1));
    const Fixture &f = fixture(width, height);
    std::vector<float> out(f.aovs.pixel_count()), beta(f.aovs.pixel_count());
    const aaf::AafOutputs outputs{aaf::plane_view(out.data(), width, height),
                                  aaf::plane_view(beta.data(), width, height)};
    double aaf_seconds = 0, fixed_seconds = 0;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        aaf::aaf_filter(f.inputs, f.light, aaf::AafParams{}, outputs);
        const auto t1 = std::chrono::steady_clock::now();
        aaf::fixed_gaussian_filter(f.inputs.visibility, f.mean_sigma_px, outputs.filtered_visibility);
        const auto t2 = std::chrono::steady_clock::now();
        aaf_seconds += std::chrono::duration<double>(t1 - t0).count();
        fixed_seconds += std::chrono::duration<double>(t2 - t1).count();
        benchmark::DoNotOptimize(out.data());
    }
    const double n = double(state.iterations()), megapixels = double(f.aovs.pixel_count()) / 1e6;
    state.counters["aaf_ms"] = 1e3 * aaf_seconds / n;
    state.counters["fixed_ms"] = 1e3 * fixed_seconds / n;
    state.counters["aaf_ms_per_MP"] = 1e3 * aaf_seconds / n / megapixels;
    state.counters["aaf_over_fixed"] = aaf_seconds / fixed_seconds;
    state.counters["mean_sigma_px"] = f.mean_sigma_px;
}

}  // namespace

BENCHMARK(BM_AafVsFixed)->Args({640, 480})->Args({1920, 1080})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
