#!/usr/bin/env bash
# Builds and runs the tracer benchmark: shadow rays per second of `aaf render`
# next to raw Embree loops on the same rays (one core), on `grids` and on a
# 129k-triangle mesh; packets, BVH quality, the robust flag and flush-to-zero
# compared too, and render_scene on 1 thread against all.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
"$root/build/scripts/bench/bench_trace" "$@"
