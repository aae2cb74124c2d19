#!/usr/bin/env bash
# Times `aaf compare` on a 1920x1080 RGB EXR pair: reading both files against
# the metrics pass (default metrics, with SSIM, with HDR-FLIP). The pair is made
# once with oiiotool under ${AAF_BENCH_DIR:-/tmp/aaf_bench_compare}: a smooth
# gradient as reference, the same plus Gaussian noise (sd 0.05) as test.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dir="${AAF_BENCH_DIR:-/tmp/aaf_bench_compare}"
mkdir -p "$dir"
if [[ ! -f "$dir/test.exr" ]]; then
    oiiotool --pattern fill:topleft=0.05,0.1,0.2:topright=0.9,0.6,0.3:bottomleft=0.2,0.7,0.1:bottomright=2.0,1.5,1.0 \
        1920x1080 3 -d float -o "$dir/ref.exr"
    oiiotool "$dir/ref.exr" --pattern noise:type=gaussian:mean=0:stddev=0.05:seed=1 1920x1080 3 --add \
        -d float -o "$dir/test.exr"
fi
"$root/scripts/build.sh" >/dev/null
AAF_BENCH_TEST="$dir/test.exr" AAF_BENCH_REF="$dir/ref.exr" \
    "$root/build/scripts/bench/bench_compare" --benchmark_repetitions="${REPS:-5}" \
    --benchmark_report_aggregates_only=true "$@"
