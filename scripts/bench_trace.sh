#!/usr/bin/env bash
# Builds and runs the tracer benchmark: shadow rays per second of `aaf render`
# next to raw Embree loops on the same rays (one core), on `grids` and on a
# 129k-triangle mesh; packets, BVH quality, the robust flag and flush-to-zero
# compared too, render_scene on 1 thread against all, and `aaf render` at
# 640x480, 256 spp end to end against the raw Embree program on its rays,
# with where its time goes.
#   scripts/bench_trace.sh --benchmark_filter=EndToEnd --benchmark_repetitions=5
#   AAF_ISA=avx2 scripts/bench_trace.sh --benchmark_filter=EndToEnd --benchmark_repetitions=5  # AVX2
#   AAF_BEFORE=/path/to/other/aaf ...  # that build's aaf render too, alternately
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
"$root/scripts/machine.sh"
"$root/build/scripts/bench/bench_trace" "$@"
