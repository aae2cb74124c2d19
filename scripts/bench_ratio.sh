#!/usr/bin/env bash
# The ratio estimator's denoise at 640x480, 1920x1080 and 3840x2160 against
# OpenCV's GaussianBlur and bilateralFilter of the same mean width on the same
# image in the same run: builds and runs
# scripts/bench/bench_ratio_filter.cpp and writes
# scripts/bench/results/ratio_filter.{json,md}. REPS (default 3) repetitions.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench="$root/build/scripts/bench/bench_ratio_filter"
[ -x "$bench" ] || "$root/scripts/build.sh"
out="$root/scripts/bench/results"
mkdir -p "$out"
"$bench" --benchmark_repetitions="${REPS:-3}" --benchmark_format=console \
  --benchmark_out="$out/ratio_filter.json" --benchmark_out_format=json "$@"
/usr/bin/python3 - "$out/ratio_filter.json" "$out/ratio_filter.md" <<'PY'
import json, re, sys
data = json.load(open(sys.argv[1]))
ctx = data["context"]
rows = [b for b in data["benchmarks"] if b.get("aggregate_name") == "median"] or \
       [b for b in data["benchmarks"] if b.get("run_type") == "iteration"]
with open(sys.argv[2], "w") as f:
    f.write(f"Ratio estimator denoise (scripts/bench_ratio.sh), {ctx['num_cpus']} CPUs at "
            f"{ctx['mhz_per_cpu']} MHz, {ctx['date']}, load average "
            f"{', '.join(f'{v:.1f}' for v in ctx.get('load_avg', []))} at the start (a shared machine). "
            "Medians of the repetitions. Input: `grids` at 2 spp, one light's layers U = U_N = unshadowed, "
            "S_N = unshadowed x shadow.V; `aaf filter ratio` defaults. OpenCV: cv::GaussianBlur of S_N and U_N "
            "(two CV_32FC3 images) with sigma = the mean bilateral sigma where the bilateral filters; "
            "cv::bilateralFilter of the same images, spatial sigma the same, range sigma 0.1. "
            f"Our instruction set: {rows[0]['label'] if rows else ''}; OpenCV AVX2 / AVX-512: "
            f"{int(rows[0]['opencv_avx2']) if rows else 0} / {int(rows[0]['opencv_avx512']) if rows else 0}.\n\n")
    f.write("| size | threads (oneTBB / OpenCV) | denoise ms | noise estimate ms | bilateral ms | grey ms | OpenCV ms | "
            "denoise / OpenCV | grey / OpenCV | OpenCV bilateral ms | denoise / OpenCV bilateral | mean sigma px | "
            "pixels filtered |\n")
    f.write("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n")
    for b in rows:
        size = re.search(r"width:(\d+)/height:(\d+)", b["name"])
        f.write(f"| {size.group(1)}x{size.group(2)} | {int(b['tbb_threads'])} / {int(b['opencv_threads'])} | {b['denoise_ms']:.1f} | "
                f"{b['noise_ms']:.1f} | {b['bilateral_ms']:.1f} | {b['grey_ms']:.1f} | {b['opencv_ms']:.1f} | "
                f"{b['denoise_over_opencv']:.2f} | {b['grey_over_opencv']:.2f} | {b['cv_bilateral_ms']:.1f} | "
                f"{b['denoise_over_cv_bilateral']:.2f} | {b['mean_sigma_px']:.2f} | "
                f"{100 * b['filtered_fraction']:.1f} % |\n")
print(open(sys.argv[2]).read())
PY
