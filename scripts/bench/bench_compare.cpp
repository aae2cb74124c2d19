// Where `aaf compare` spends its time on one 1920x1080 RGB EXR pair: reading
// both files (OpenEXR) against the metrics pass with the default metrics
// (RMSE, MSE, PSNR: one pass over the pixels), with SSIM added (five Gaussian
// blurs) and with HDR-FLIP added. The pair is read from $AAF_BENCH_TEST and
// $AAF_BENCH_REF; ./scripts/bench_compare.sh makes it with oiiotool and runs this.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

#include "aaf/core/metrics/error_metrics.h"
#include "aaf/io/exr_io.h"

namespace {

std::string path_from(const char *variable) {
    const char *value = std::getenv(variable);
    return value ? value : "";
}

struct Pair {
    aaf::AovSet test, reference;
};

const Pair &pair() {
    static const Pair loaded{aaf::io::read_aovs(path_from("AAF_BENCH_TEST")),
                             aaf::io::read_aovs(path_from("AAF_BENCH_REF"))};
    return loaded;
}

void BM_Read(benchmark::State &state) {
    for (auto _ : state) {
        aaf::AovSet test = aaf::io::read_aovs(path_from("AAF_BENCH_TEST"));
        aaf::AovSet reference = aaf::io::read_aovs(path_from("AAF_BENCH_REF"));
        benchmark::DoNotOptimize(test.pixel_count() + reference.pixel_count());
    }
}

/// The metrics pass; state.range(0): 0 default metrics, 1 with SSIM, 2 with HDR-FLIP.
void BM_Metrics(benchmark::State &state) {
    const Pair &p = pair();
    aaf::CompareOptions options;
    options.compute_ssim = state.range(0) == 1;
    options.flip = state.range(0) == 2 ? aaf::CompareOptions::Flip::Hdr : aaf::CompareOptions::Flip::Off;
    for (auto _ : state) benchmark::DoNotOptimize(aaf::compare_images(p.test, p.reference, options));
    state.SetLabel(state.range(0) == 0 ? "rmse,mse,psnr" : state.range(0) == 1 ? "+ssim" : "+flip");
}

}  // namespace

BENCHMARK(BM_Read)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Metrics)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
