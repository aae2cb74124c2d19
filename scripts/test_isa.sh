#!/usr/bin/env bash
# Runs the whole test suite (build/, as scripts/test.sh leaves it) again with
# the instruction set pinned (AAF_ISA: Embree's kernels and the filters'
# Highway kernels) to sse4.2, which every x86-64 CPU has, to avx2 and, where
# the CPU has them, to avx512: the suite must pass under each.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root/build"
sets=(sse4.2 avx2 avx512)
status=0
for set in "${sets[@]}"; do
  case "$set" in
    avx2) grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo || { echo "isa: this CPU has no avx2, not run" >&2; continue; } ;;
    avx512) grep -qw avx512f /proc/cpuinfo && grep -qw avx512vl /proc/cpuinfo && grep -qw avx512bw /proc/cpuinfo &&
              grep -qw avx512dq /proc/cpuinfo || { echo "isa: this CPU has no avx512, not run" >&2; continue; } ;;
  esac
  start=$(date +%s)
  if AAF_ISA=$set ctest --output-on-failure --parallel "$(nproc)" --timeout 600 >"isa-$set.log" 2>&1; then
    echo "isa: the whole suite passes with AAF_ISA=$set ($(($(date +%s) - start)) s)"
  else
    tail -40 "isa-$set.log"
    echo "isa: the suite FAILS with AAF_ISA=$set (build/isa-$set.log)" >&2
    status=1
  fi
done
exit $status
