#!/usr/bin/env bash
# Builds and runs the filter benchmark: AAF and its gather against OpenCV's GaussianBlur and a fixed Gaussian.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
"$root/build/scripts/bench/bench_aaf_filter" --benchmark_repetitions="${REPS:-3}" "$@"
