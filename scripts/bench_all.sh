#!/usr/bin/env bash
# Runs the benchmark suite once and writes its results, with the commands
# that produced them, to scripts/bench/results/suite_<UTC date and time>.md:
#   bench_aaf_filter  AAF and its gather against OpenCV GaussianBlur (same mean
#                     width) and bilateralFilter at 640x480, 1920x1080, 3840x2160
#   bench_aaf_scaling AAF against OpenCV GaussianBlur at a fixed filter width,
#                     the 640x480 render tiled up to 3840x2880 (linearity in pixels)
#   bench_maaf_filter MAAF against AAF and OpenCV GaussianBlur (MAAF's mean
#                     central width) on the same render (640x480)
#   bench_ratio_filter the ratio estimator's denoise against OpenCV GaussianBlur
#                     (same mean width) and bilateralFilter (same spatial sigma)
#                     at 640x480, 1920x1080 and 3840x2160
#   bench_methods_bandwidth every registered method against the machine's copy
#                     bandwidth: the bytes it must move (one run: maaf6 alone
#                     takes a minute at 640x480)
#   bench_trace       the tracer against raw Embree loops on the same rays, and
#                     aaf render (640x480, 256 spp, the whole process) against a
#                     raw Embree program over its rays, with where its time goes
#   bench_io.sh       aaf filter end to end against the OpenEXR-only read and
#                     write of the same frame (exr_copy_floor) with the same
#                     threads, aaf --version and aaf info, an oiiotool copy,
#                     peak memory, the adaptive frame
# 1-thread rows set oneTBB and OpenCV to one thread alike (the per-core
# figures); the others give both every thread.
# Every figure is a median; every ratio is of timings taken alternately in
# the same run. On a shared machine absolute times move with the load; the
# ratios are the figures. REPS (default 3) sets the repetitions.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
reps="${REPS:-3}"
bench="$root/build/scripts/bench"
out="$root/scripts/bench/results/suite_$(date -u +%Y-%m-%dT%H%MZ).md"
run() {
    echo
    echo "\`\`\`"
    echo "\$ $*"
    "$@" 2>&1 | grep -v '^\*\*\*' | sed 's/  */ /g'
    echo "\`\`\`"
}
{
    echo "# Benchmark suite, $(date -u +%FT%TZ)"
    echo
    echo "Machine: $("$root/scripts/machine.sh"); load average $(cut -d' ' -f1-3 /proc/loadavg) at the start."
    echo "Produced by: REPS=$reps scripts/bench_all.sh"
    run "$bench/bench_aaf_filter" --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true
    run "$bench/bench_aaf_scaling" --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true
    run "$bench/bench_maaf_filter" --benchmark_filter='640' --benchmark_repetitions="$reps" \
        --benchmark_report_aggregates_only=true
    run "$bench/bench_ratio_filter" --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true
    run "$bench/bench_methods_bandwidth"
    run "$bench/bench_trace" --benchmark_filter='BM_Throughput|BM_Packets' --benchmark_repetitions="$reps" \
        --benchmark_report_aggregates_only=true
    run "$bench/bench_trace" --benchmark_filter='BM_EndToEnd' --benchmark_repetitions="$reps"
    echo
    echo "\$ REPS=$reps scripts/bench_io.sh"
    echo
    REPS="$reps" "$root/scripts/bench_io.sh"
    echo
    echo "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)."
} > "$out"
echo "$out"
