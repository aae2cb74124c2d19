#!/usr/bin/env bash
# ISG Table 1 (Robison and Shirley 2009) for this implementation: builds and
# runs scripts/bench/bench_isg.cpp (1024x768 gallery, search x gather samples
# in {9, 25, 49, 81} for isg-shadow, isg-glossy, isg-dof, with the no-ISG
# baseline) and writes scripts/bench/results/isg_table1.{json,md}.
# THREADS (default: all) caps oneTBB's workers.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench="$root/build/scripts/bench/bench_isg"
[ -x "$bench" ] || "$root/scripts/build.sh"
out="$root/scripts/bench/results"
mkdir -p "$out"
"$bench" --benchmark_format=console --benchmark_out="$out/isg_table1.json" --benchmark_out_format=json "$@"
/usr/bin/python3 "$root/scripts/bench/isg_table1.py" "$out/isg_table1.json" "$out/isg_table1.md"
