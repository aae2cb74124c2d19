#!/usr/bin/env bash
# Builds and runs the benchmarks (AAF filter vs a fixed-width Gaussian on the same image).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
"$root/build/scripts/bench/bench_aaf_filter" --benchmark_repetitions="${REPS:-3}" "$@"
